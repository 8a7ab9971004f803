// KHR_materials_transmission (Khronos, 2020) read for shadows. A transmissive surface — glass,
// most often: Blender writes the extension for every material with Principled transmission —
// lets a share of the light through, tinted by its base colour, as a thin pane lets the sun
// through a window. Drawn and cast whole, a window's panes kept the sun out of every room, in
// the maps and in the ray-traced truth alike, so `eval` scored a dark room as right.
//
// shadowkit has no transparency (materials.md: one depth per texel, one surface per pixel), so
// a transmissive surface is read as an alpha-tested one, the light it lets through taken out of
// its alpha:
//
//     alpha' = alpha · (1 − t · tint),   t = transmissionFactor · transmissionTexture.r,
//     tint = the luminance of baseColorFactor's RGB (Rec. 709 weights; the light is tinted by it)
//
// and an opaque material becomes a mask at 0.5: the sun passes where more than half of it gets
// through — a clear pane is cut away, a dark-tinted one still casts. The camera then sees through
// a cut pane too, as an eye does. The base colour texture's own colour does not tint (only its
// factor's), and a transmission texture that the base colour texture does not share coordinates
// with is taken at its mean.
#include "gltf_transmission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

constexpr const char* kExtension = "KHR_materials_transmission";

// The texture reference a `textureInfo` JSON object writes (index, texCoord, its extensions), or
// nullopt where its index or texCoord is not a whole number in range.
std::optional<tinygltf::TextureInfo> textureInfoOf(const tinygltf::Value& value) {
    if (!value.IsObject()) return std::nullopt;
    const std::optional<int> index = indexIn(value.Get("index"));
    const std::optional<int> texCoord = value.Has("texCoord") ? indexIn(value.Get("texCoord")) : 0;
    if (!index || !texCoord) return std::nullopt;
    tinygltf::TextureInfo info;
    info.index = *index;
    info.texCoord = *texCoord;
    if (const tinygltf::Value& extensions = value.Get("extensions"); extensions.IsObject())
        for (const std::string& key : extensions.Keys()) info.extensions[key] = extensions.Get(key);
    return info;
}

// Texel (x, y) of `to`'s size read from `from` at the same texture coordinates, nearest.
float redAt(const Image& from, const Image& to, int x, int y) {
    const int fx = std::min(from.width - 1, int((x + 0.5) * from.width / to.width));
    const int fy = std::min(from.height - 1, int((y + 0.5) * from.height / to.height));
    return from.pixel(fx, fy)[0] / 255.0f;
}

float meanRed(const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) sum += image.rgba[i];
    return image.rgba.empty() ? 1.0f : float(sum / (255.0 * double(image.rgba.size() / 4)));
}

std::string percent(double share) {
    char text[16];
    std::snprintf(text, sizeof text, "%.3g %%", 100.0 * share);
    return text;
}

} // namespace

std::optional<TextureUse> cuttingTexture(const tinygltf::Model& model, const tinygltf::Material& material) {
    if (material.pbrMetallicRoughness.baseColorTexture.index >= 0)
        return TextureUse{material.pbrMetallicRoughness.baseColorTexture, "base colour texture"};
    const auto ext = material.extensions.find(kExtension);
    if (ext == material.extensions.end() || !ext->second.IsObject()) return std::nullopt;
    const tinygltf::Value& factor = ext->second.Get("transmissionFactor");
    if (!factor.IsNumber() || !(factor.GetNumberAsDouble() > 0.0)) return std::nullopt; // nothing gets through
    std::optional<tinygltf::TextureInfo> info = textureInfoOf(ext->second.Get("transmissionTexture"));
    if (!info || info->index < 0 || size_t(info->index) >= model.textures.size()) return std::nullopt;
    return TextureUse{std::move(*info), "transmission texture"};
}

core::Result<std::optional<Transmission>> readTransmission(const tinygltf::Model& model, const tinygltf::Material& in,
                                                           const std::string& where) {
    const auto ext = in.extensions.find(kExtension);
    if (ext == in.extensions.end()) return std::optional<Transmission>();
    const std::string what = where + ": " + kExtension;
    if (!ext->second.IsObject()) return core::makeError(what + " is not an object");
    Transmission out;
    if (ext->second.Has("transmissionFactor")) {
        const tinygltf::Value& factor = ext->second.Get("transmissionFactor");
        out.factor = factor.IsNumber() ? factor.GetNumberAsDouble() : NAN;
        if (!(out.factor >= 0.0 && out.factor <= 1.0)) // NaN-safe
            return core::makeError(what + "'s transmissionFactor is not a number in [0, 1]");
    }
    if (ext->second.Has("transmissionTexture")) {
        out.texture = textureInfoOf(ext->second.Get("transmissionTexture"));
        if (!out.texture || out.texture->index < 0 || size_t(out.texture->index) >= model.textures.size())
            return core::makeError(what + "'s transmissionTexture is not a reference to one of the file's textures");
    }
    return std::optional<Transmission>(std::move(out));
}

namespace {

// applyTransmission's work: the material cut, and what its warning says of the light let through.
core::Result<std::string> cutByTransmission(const tinygltf::Model& model, const fs::path& file,
                                            const ImageContext& images, const tinygltf::Material& in,
                                            const Transmission& transmission, Material& out, Scene& scene,
                                            size_t& textureBytes) {
    const glm::vec3 colour = glm::clamp(glm::vec3(out.baseColorFactor), 0.0f, 1.0f);
    const float tint = glm::dot(colour, glm::vec3(0.2126f, 0.7152f, 0.0722f));
    const float passes = float(transmission.factor) * tint; // where the texture's red is 1
    std::string said = std::string(kExtension) + " lets " + percent(passes) + " of the light through";

    std::optional<Texture> pattern; // the transmission texture, decoded
    if (transmission.texture) {
        core::Result<Texture> decoded = readTexture(model, file, transmission.texture->index, images);
        if (decoded)
            pattern = std::move(*decoded);
        else
            said += " (its transmission texture cannot be read: " + decoded.error() + "; taken as 1)";
    }
    const auto addTexture = [&](Texture texture) -> core::Status {
        if ((textureBytes += texture.image.rgba.size()) > kMaxTextureBytes)
            return core::makeError(file.string() + ": the file's textures decode to more than 1 GiB");
        out.baseColorTexture = int32_t(scene.textures.size());
        scene.textures.push_back(std::move(texture));
        return core::Ok{};
    };
    // An opaque material's alpha means nothing (glTF §3.9.4): it becomes a mask here, and must
    // not start cutting where its factor or its colour texture's alpha happen to be low.
    const bool wasOpaque = out.alphaMode == AlphaMode::Opaque;
    if (wasOpaque) out.alphaMode = AlphaMode::Mask, out.alphaCutoff = 0.5f, out.baseColorFactor.a = 1.0f;
    const tinygltf::TextureInfo& base = in.pbrMetallicRoughness.baseColorTexture;
    const bool sameCoordinates = pattern && base.texCoord == transmission.texture->texCoord &&
                                 textureTransform(base) == textureTransform(*transmission.texture);
    if (pattern && out.baseColorTexture < 0 && base.index < 0) {
        // The pattern alone cuts: white texels (the factor keeps its colour), alpha what it stops.
        Texture cut = std::move(*pattern);
        for (size_t i = 0; i < cut.image.rgba.size(); i += 4) {
            const float stops = 1.0f - passes * cut.image.rgba[i] / 255.0f;
            cut.image.rgba[i] = cut.image.rgba[i + 1] = cut.image.rgba[i + 2] = 255;
            cut.image.rgba[i + 3] = uint8_t(std::lround(255.0f * stops));
        }
        said += " where its transmission texture lets all through";
        if (core::Status s = addTexture(std::move(cut)); !s) return s.errorInfo();
        return said;
    }
    float uniform = passes; // what the factor's alpha loses where no texel says otherwise
    if (pattern && !(out.baseColorTexture >= 0 && sameCoordinates)) {
        uniform = passes * meanRed(pattern->image);
        said += " where its transmission texture lets all through, which reads other coordinates than its base "
                "colour texture: taken at its mean, " +
                percent(uniform);
    } else if (pattern) {
        said += " where its transmission texture lets all through";
    }
    if (out.baseColorTexture >= 0 && (wasOpaque || (pattern && sameCoordinates))) {
        // A copy of the base colour texture (other materials may share it): its alpha opaque where
        // the material was, times what the pattern stops at each texel where both read the same
        // coordinates.
        Texture cut = scene.textures[size_t(out.baseColorTexture)];
        for (int y = 0; y < cut.image.height; ++y)
            for (int x = 0; x < cut.image.width; ++x) {
                uint8_t& alpha = cut.image.pixel(x, y)[3];
                const float stops =
                    pattern && sameCoordinates ? 1.0f - passes * redAt(pattern->image, cut.image, x, y) : 1.0f;
                alpha = uint8_t(std::lround((wasOpaque ? 255.0f : float(alpha)) * stops));
            }
        if (core::Status s = addTexture(std::move(cut)); !s) return s.errorInfo();
        if (pattern && sameCoordinates) return said;
    }
    out.baseColorFactor.a *= 1.0f - uniform;
    return said;
}

} // namespace

core::Result<std::string> applyTransmission(const tinygltf::Model& model, const fs::path& file,
                                            const ImageContext& images, const tinygltf::Material& in,
                                            const Transmission& transmission, Material& out, Scene& scene,
                                            size_t& textureBytes) {
    auto said = cutByTransmission(model, file, images, in, transmission, out, scene, textureBytes);
    if (!said) return said;
    char cutoff[64];
    std::snprintf(cutoff, sizeof cutoff, "%.3g", out.alphaCutoff);
    return *said + ": taken out of its alpha, which its cutoff " + cutoff +
           " then cuts (shadowkit has no transparency), so the sun passes it as it passes glass";
}

} // namespace shadowkit::scene::formats
