// Alpha-cut OBJ materials: the MTL's dissolve texture (`map_d`) read as a mask, so that a tree
// exported as OBJ casts its leaves' shadows and not its cards' rectangles.
//
// The MTL format (Wavefront, "Material library file (.mtl)"; map_d: "a scalar texture file",
// read through the channel `-imfchan` names, `m` — matte — by default) has no alpha mode, cutoff
// or sidedness. shadowkit reads a material with a map_d (or `map_D`, DAZ Studio's spelling,
// obj_read.cpp) as glTF's MASK at its default cutoff 0.5, drawn and cast from both sides: what a
// leaf card needs, and the rule the ray-traced truth follows too. The mask's value per texel:
//   - `-imfchan r|g|b`: that channel; `l`: the luminance (Rec. 709 weights);
//   - `m` (the default): the image's alpha where it has one (any texel below 255), else its
//     luminance — a grey mask saved without alpha, as most map_d files are, reads as one.
// Colour is not read from textures (as for every OBJ material, the diffuse colour Kd is the
// vertices'): the texture holds white with the mask as alpha, which is what every pass and the
// ray-traced truth test.
//
// A material with no map_d whose diffuse texture (map_Kd) is a PNG with texels under half alpha is
// drawn and cast opaque, as the MTL format and most OBJ importers read it, with one warning per
// file: a tree whose leaves are cut only by map_Kd's alpha otherwise casts whole cards unexplained.
//
// Glass. The MTL's dissolve `d` is "the amount this material dissolves into the background",
// 1 fully opaque, 0 completely transparent, and a map_d's value "is multiplied by the d value";
// files without `d` may write `Tr`, its complement (tinyobjloader reads dissolve = 1 − Tr, and
// `d` wins where both are written). shadowkit has no transparency, so the dissolve is read as
// glTF reads alpha: a factor on the mask, cut at 0.5. A material that dissolves below half —
// a window pane written `d 0.1` — is cut away whole, neither drawn nor cast, so the sun passes it
// as it passes glass; one that dissolves less casts whole; with a map_d the product is cut. One
// warning per file names those that faces wear. Exporters
// disagree on `Tr` (3ds Max once wrote it as opacity, tinyobjloader's issue 43), and a `d` with
// no number reads 0; where every face of the file would dissolve away — nothing left to draw —
// its materials are read opaque with one warning instead. A dissolve outside [0, 1] is read
// opaque, with one warning.
//
// A map_d that cannot be read (missing — OBJ files travel without their textures, or name them
// by a path on their author's disk —, not an image, past the decoder's limits) leaves its
// material opaque with one warning: the file still loads, its cards cast whole. A name with
// backslashes (Windows exporters) is read with slashes, and a name not found as written is
// looked for by its file name beside the OBJ.
#include "obj_materials.h"

#include "scene_formats.h"

#include "shadowkit/scene/file_read.h"
#include "shadowkit/scene/image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <tuple>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

// Where a map_d names its image: as written (backslashes as slashes), relative to the OBJ's
// directory unless absolute; failing that, its file name beside the OBJ.
fs::path findImage(const std::string& name, const fs::path& directory) {
    std::string portable = name;
    std::replace(portable.begin(), portable.end(), '\\', '/');
    const fs::path written(portable);
    const fs::path asWritten = written.is_absolute() ? written : directory / written;
    std::error_code error;
    if (fs::is_regular_file(asWritten, error)) return asWritten;
    const fs::path beside = directory / written.filename();
    return fs::is_regular_file(beside, error) ? beside : asWritten;
}

uint8_t luminance(const uint8_t* texel) {
    return uint8_t(std::clamp(0.2126f * texel[0] + 0.7152f * texel[1] + 0.0722f * texel[2] + 0.5f, 0.0f, 255.0f));
}

// The mask as the alpha of a white texture (above: the channel -imfchan names).
Texture maskTexture(const Image& image, char channel, bool clamp) {
    const size_t texels = size_t(image.width) * size_t(image.height);
    bool hasAlpha = false;
    for (size_t i = 0; i < texels && !hasAlpha; ++i) hasAlpha = image.rgba[4 * i + 3] < 255;
    Texture out;
    out.image = Image(image.width, image.height);
    for (size_t i = 0; i < texels; ++i) {
        const uint8_t* in = &image.rgba[4 * i];
        uint8_t mask = 0;
        switch (channel) {
        case 'r':
            mask = in[0];
            break;
        case 'g':
            mask = in[1];
            break;
        case 'b':
            mask = in[2];
            break;
        case 'l':
            mask = luminance(in);
            break;
        default:
            mask = hasAlpha ? in[3] : luminance(in);
            break; // 'm', and what tinyobjloader lets through
        }
        uint8_t* texel = &out.image.rgba[4 * i];
        texel[0] = texel[1] = texel[2] = 255;
        texel[3] = mask;
    }
    out.wrapS = out.wrapT = clamp ? TextureWrap::ClampToEdge : TextureWrap::Repeat;
    return out;
}

// Whether `file` is a PNG whose pixels carry alpha (colour type 4, grey and alpha, or 6, RGBA:
// PNG §11.2.2, the IHDR chunk's byte 9), read from its first 26 bytes alone.
bool pngWithAlpha(const fs::path& file) {
    std::error_code error;
    if (!fs::is_regular_file(file, error)) return false;
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 26> head{};
    if (!in.read(reinterpret_cast<char*>(head.data()), head.size())) return false;
    constexpr std::array<unsigned char, 8> kSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    const bool png = std::equal(kSignature.begin(), kSignature.end(), head.begin()) &&
                     std::string_view(reinterpret_cast<const char*>(&head[12]), 4) == "IHDR";
    return png && (head[25] == 4 || head[25] == 6);
}

// Whether a glTF-style cut at 0.5 would take anything from the image at `file`: a PNG with an
// alpha channel (pngWithAlpha, from its header; most are not) decoded, any texel's alpha under
// half. An image that cannot be read says nothing here: its material is opaque either way.
bool cutByItsAlpha(const fs::path& file) {
    if (!pngWithAlpha(file)) return false;
    const auto bytes = readFile(file);
    if (!bytes) return false;
    const auto image =
        decodeImage(std::span(reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()), file.string());
    if (!image) return false;
    for (size_t i = 3; i < image->rgba.size(); i += 4)
        if (image->rgba[i] < 128) return true;
    return false;
}

// A material's name in quotes, as the warnings name it.
std::string quoted(const std::string& name) {
    std::string out = "'";
    out += printable(name);
    out += '\'';
    return out;
}

// The first of `names`, and how many more: one line however many materials a file holds.
std::string firstAndCount(const std::vector<std::string>& names) {
    std::string out = names.front();
    if (names.size() > 1) out += " and " + std::to_string(names.size() - 1) + " more";
    return out;
}

constexpr float kCutoff = 0.5f; // glTF's default alphaCutoff, which OBJ masks are read at

// The material a cut material's faces wear: its mask (−1: none) times its dissolve, cut at half
// and drawn and cast from both sides — what a leaf card needs, and a pane of glass is the same
// seen from either side.
Material cutMaterial(const std::string& name, int32_t mask, float dissolve) {
    Material material;
    material.name = name;
    material.baseColorFactor.a = dissolve;
    material.baseColorTexture = mask;
    material.alphaMode = AlphaMode::Mask;
    material.alphaCutoff = kCutoff;
    material.doubleSided = true;
    return material;
}

// Each material's dissolve as it is read (above): tinyobjloader's, 1 where it lies outside [0, 1],
// and 1 for every material where every face of the file would otherwise dissolve away.
std::vector<float> dissolvesOf(const std::vector<tinyobj::material_t>& materials, std::span<const size_t> facesWearing,
                               const fs::path& file, Scene& scene) {
    std::vector<float> dissolve(materials.size(), 1.0f);
    std::vector<std::string> outOfRange;
    size_t faces = 0, dissolvedFaces = 0;
    for (size_t m = 0; m < materials.size(); ++m) {
        const double d = materials[m].dissolve;
        if (std::isfinite(d) && d >= 0.0 && d <= 1.0)
            dissolve[m] = float(d);
        else
            outOfRange.push_back(quoted(materials[m].name));
        const size_t wearing = m < facesWearing.size() ? facesWearing[m] : 0;
        faces += wearing;
        if (dissolve[m] < kCutoff) dissolvedFaces += wearing;
    }
    if (!outOfRange.empty())
        scene.warnings.push_back(file.string() + ": material " + firstAndCount(outOfRange) +
                                 ": a dissolve (d, or 1 − Tr) outside [0, 1], read as opaque");
    if (faces > 0 && dissolvedFaces == faces) {
        scene.warnings.push_back(file.string() +
                                 ": every face wears a material that dissolves below half (d under 0.5, or Tr over "
                                 "0.5), which would leave nothing to draw: read as opaque, as exporters that write Tr "
                                 "for opacity, or d 0, mean it");
        std::fill(dissolve.begin(), dissolve.end(), 1.0f);
    }
    return dissolve;
}

} // namespace

std::vector<int32_t> readObjMaterials(const std::vector<tinyobj::material_t>& materials,
                                      std::span<const size_t> facesWearing, const fs::path& file, Scene& scene) {
    std::vector<int32_t> out(materials.size(), -1);
    const std::vector<float> dissolve = dissolvesOf(materials, facesWearing, file, scene);
    std::map<std::tuple<fs::path, char, bool>, int32_t> textureOf; // a mask read once (−1: unreadable)
    std::vector<std::string> alphaUnread; // materials whose map_Kd has alpha and no map_d cuts them
    std::vector<std::string> glass;       // materials dissolved away whole
    std::map<fs::path, bool> diffuseCut;  // each map_Kd looked at once
    for (size_t m = 0; m < materials.size(); ++m) {
        const tinyobj::material_t& in = materials[m];
        if (dissolve[m] < kCutoff && m < facesWearing.size() && facesWearing[m] > 0) {
            char figure[32];
            std::snprintf(figure, sizeof figure, " (d %.3g)", double(dissolve[m]));
            glass.push_back(quoted(in.name) + figure);
        }
        if (in.alpha_texname.empty()) {
            if (dissolve[m] < kCutoff) {
                out[m] = int32_t(scene.materials.size());
                scene.materials.push_back(cutMaterial(in.name, -1, dissolve[m]));
                continue;
            }
            if (in.diffuse_texname.empty()) continue;
            const fs::path diffuse = findImage(in.diffuse_texname, file.parent_path());
            auto [seen, first] = diffuseCut.try_emplace(diffuse, false);
            if (first) seen->second = cutByItsAlpha(diffuse);
            if (seen->second) alphaUnread.push_back(quoted(in.name) + " (" + quoted(in.diffuse_texname) + ")");
            continue;
        }
        const std::string where = file.string() + ": material " + quoted(in.name);
        const fs::path image = findImage(in.alpha_texname, file.parent_path());
        const char channel = in.alpha_texopt.imfchan;
        const auto key = std::tuple(image, channel, bool(in.alpha_texopt.clamp));
        auto known = textureOf.find(key);
        if (known == textureOf.end()) {
            const auto bytes = readFile(image);
            auto decoded = bytes
                               ? decodeImage(std::span(reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()),
                                             image.string())
                               : core::Result<Image>(bytes.errorInfo());
            if (decoded) {
                known = textureOf.emplace(key, int32_t(scene.textures.size())).first;
                scene.textures.push_back(maskTexture(*decoded, channel, in.alpha_texopt.clamp));
            } else { // said once, however many materials name it
                known = textureOf.emplace(key, -1).first;
                scene.warnings.push_back(where + ": its map_d '" + printable(in.alpha_texname) + "' cannot be read (" +
                                         decoded.error() +
                                         "): read as covering every texel, its faces cast whole unless "
                                         "their dissolve is under half");
            }
        }
        if (known->second < 0 && dissolve[m] >= kCutoff) continue;
        out[m] = int32_t(scene.materials.size());
        scene.materials.push_back(cutMaterial(in.name, known->second, dissolve[m]));
    }
    if (!glass.empty())
        scene.warnings.push_back(
            file.string() + ": material " + firstAndCount(glass) + (glass.size() > 1 ? " dissolve" : " dissolves") +
            " below half: cut away whole, neither drawn nor cast, so the sun passes " +
            (glass.size() > 1 ? "them" : "it") + " as it passes glass (shadowkit has no transparency)");
    if (!alphaUnread.empty())
        scene.warnings.push_back(
            file.string() + ": material " + firstAndCount(alphaUnread) +
            ": a map_Kd with alpha and no map_d, drawn and cast opaque as OBJ reads it; a map_d line naming the "
            "same image cuts it");
    return out;
}

glm::vec2 objTextureUv(const tinyobj::texture_option_t& options, glm::vec2 vt) {
    const glm::vec2 scaled = vt * glm::vec2(float(options.scale[0]), float(options.scale[1])) +
                             glm::vec2(float(options.origin_offset[0]), float(options.origin_offset[1]));
    return {scaled.x, 1.0f - scaled.y};
}

} // namespace shadowkit::scene::formats
