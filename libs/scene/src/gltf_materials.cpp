// glTF materials and the images their base colour textures use (§3.8.4, §3.9), read for
// gltf_read.cpp: images decoded by scene::decodeImage (PNG, JPEG, WebP) as tinygltf hands
// them over, a texture's sources tried in order, and a texture that cannot be had dropped with
// one warning where its material is opaque (shadows never read an opaque colour) and refused
// where the material's alpha matters.
#include "gltf_materials.h"
#include "gltf_transmission.h"
#include "scene_formats.h"

#include "shadowkit/scene/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <variant>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

std::string imageName(const std::string& file, int index, const tinygltf::Image& image) {
    const std::string label = printable(!image.name.empty() ? image.name : image.uri.substr(0, 80));
    return file + ": image " + std::to_string(index) +
           (label.empty() || label.starts_with("data:") ? "" : " '" + label + "'");
}

TextureWrap wrapOf(int gltfWrap) {
    return gltfWrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::ClampToEdge
           : gltfWrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                               : TextureWrap::Repeat;
}

// One image decoded: from its buffer view (bytes checked against the buffer), or as the image
// callback left it.
core::Result<Image> readImage(const tinygltf::Model& model, const fs::path& file, int source,
                              const ImageContext& images) {
    if (source < 0 || size_t(source) >= model.images.size())
        return core::makeError(file.string() + ": no image " + std::to_string(source));
    const tinygltf::Image& image = model.images[size_t(source)];
    const std::string name = imageName(file.string(), source, image);
    if (const auto failed = images.failures.find(source); failed != images.failures.end()) return failed->second;
    if (image.bufferView >= 0) {
        const auto& views = model.bufferViews;
        const size_t length = size_t(image.bufferView) < views.size() ? views[size_t(image.bufferView)].byteLength : 0;
        auto bytes = bytesOf(model, image.bufferView, 0, 1, length, length, name);
        if (!bytes) return bytes.errorInfo();
        return decodeImage(std::span(*bytes, length), name);
    }
    if (image.image.empty() || image.width <= 0 || image.height <= 0 ||
        image.image.size() != size_t(image.width) * size_t(image.height) * 4) {
        if (image.uri.empty()) return core::makeError(name + ": neither a uri nor a buffer view");
        // The file tinygltf looked for, beside the glTF (a percent-encoded uri is not matched:
        // the general reason stands there).
        for (const auto& [path, why] : images.refusedFiles)
            if (path == image.uri || path.ends_with("/" + image.uri)) return core::makeError(name + ": " + why);
        return core::makeError(name + ": cannot read it (a missing file?)");
    }
    Image out;
    out.width = image.width, out.height = image.height;
    out.rgba = image.image;
    return out;
}

// The image sources of a texture, best first: EXT_texture_webp's, the core source (PNG or
// JPEG, the extensions' fallback), KHR_texture_basisu's.
std::vector<int> textureSources(const tinygltf::Texture& texture) {
    std::vector<int> sources;
    const auto extensionSource = [&](const char* name) {
        const auto ext = texture.extensions.find(name);
        if (ext == texture.extensions.end() || !ext->second.IsObject()) return;
        if (const std::optional<int> source = indexIn(ext->second.Get("source"))) sources.push_back(*source);
    };
    extensionSource("EXT_texture_webp");
    if (texture.source >= 0) sources.push_back(texture.source);
    extensionSource("KHR_texture_basisu");
    return sources;
}

} // namespace

std::optional<int> indexIn(const tinygltf::Value& value) {
    if (!value.IsNumber()) return std::nullopt;
    const double number = value.GetNumberAsDouble();
    if (!(number >= 0.0 && number < 2147483648.0) || number != std::floor(number)) return std::nullopt;
    return int(number);
}

// uv' = T · R · S · uv, the extension's order.
std::optional<glm::mat3> textureTransform(const tinygltf::TextureInfo& info) {
    const auto ext = info.extensions.find("KHR_texture_transform");
    if (ext == info.extensions.end() || !ext->second.IsObject()) return std::nullopt;
    const tinygltf::Value& v = ext->second;
    auto number = [&](const char* key, int i, double fallback) {
        const tinygltf::Value& a = v.Get(key);
        if (!a.IsArray() || int(a.ArrayLen()) <= i || !a.Get(i).IsNumber()) return fallback;
        return a.Get(i).GetNumberAsDouble();
    };
    const double rotation = v.Get("rotation").IsNumber() ? v.Get("rotation").GetNumberAsDouble() : 0.0;
    const glm::dmat3 translate(1, 0, 0, 0, 1, 0, number("offset", 0, 0.0), number("offset", 1, 0.0), 1);
    const double c = std::cos(rotation), s = std::sin(rotation);
    const glm::dmat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1); // columns: the extension's matrix transposed
    const glm::dmat3 scale(number("scale", 0, 1.0), 0, 0, 0, number("scale", 1, 1.0), 0, 0, 0, 1);
    const glm::mat3 m(translate * rotate * scale);
    if (!core::isFinite(glm::dmat4(glm::dmat3(m)))) return std::nullopt;
    return m;
}

core::Result<Texture> readTexture(const tinygltf::Model& model, const fs::path& file, int textureIndex,
                                  const ImageContext& images) {
    const tinygltf::Texture& texture = model.textures[size_t(textureIndex)];
    const std::vector<int> sources = textureSources(texture);
    if (sources.empty())
        return core::makeError(file.string() + ": texture " + std::to_string(textureIndex) + " names no image");
    std::optional<core::Error> firstFailure;
    Texture decoded;
    for (int source : sources) {
        core::Result<Image> image = readImage(model, file, source, images);
        if (image) {
            decoded.image = std::move(*image);
            firstFailure.reset();
            break;
        }
        if (!firstFailure) firstFailure = image.errorInfo();
    }
    if (firstFailure) return *firstFailure;
    if (texture.sampler >= 0 && size_t(texture.sampler) < model.samplers.size()) {
        const tinygltf::Sampler& sampler = model.samplers[size_t(texture.sampler)];
        decoded.wrapS = wrapOf(sampler.wrapS);
        decoded.wrapT = wrapOf(sampler.wrapT);
        decoded.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        decoded.mipmaps =
            sampler.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST && sampler.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
    }
    return decoded;
}

bool loadImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    if (image->bufferView >= 0) return true;
    auto& context = *static_cast<ImageContext*>(user);
    auto decoded = decodeImage(std::span(bytes, size_t(std::max(size, 0))), imageName(context.file, index, *image));
    if (!decoded) {
        context.failures.emplace(index, decoded.errorInfo());
        return true;
    }
    image->width = decoded->width, image->height = decoded->height;
    image->component = 4, image->bits = 8, image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(decoded->rgba);
    return true;
}

core::Status readMaterials(const tinygltf::Model& model, const fs::path& file, const ImageContext& images,
                           const std::vector<bool>& used, Scene& scene) {
    std::map<int, std::variant<int32_t, core::Error>> textureOf; // glTF texture -> Scene::textures, or why not
    std::set<int> dropped;                                       // textures warned about
    std::map<int32_t, float> maxAlphaOf;                         // Scene::textures -> their largest alpha
    size_t textureBytes = 0;
    for (size_t m = 0; m < model.materials.size(); ++m) {
        if (m >= used.size() || !used[m]) {
            scene.materials.emplace_back();
            continue;
        }
        const tinygltf::Material& in = model.materials[m];
        const std::string where = file.string() + ": material " + std::to_string(m) +
                                  (in.name.empty() ? "" : " '" + printable(in.name) + "'");
        Material out;
        out.name = in.name;
        const auto& f = in.pbrMetallicRoughness.baseColorFactor;
        for (size_t c = 0; c < std::min<size_t>(f.size(), 4); ++c) out.baseColorFactor[int(c)] = float(f[c]);
        if (!core::isFinite(glm::dvec4(out.baseColorFactor)))
            return core::makeError(where + ": baseColorFactor is not finite");
        out.alphaMode = in.alphaMode == "MASK"    ? AlphaMode::Mask
                        : in.alphaMode == "BLEND" ? AlphaMode::Blend
                                                  : AlphaMode::Opaque;
        out.alphaCutoff = float(in.alphaCutoff);
        if (!(out.alphaCutoff >= 0.0f && out.alphaCutoff <= 1.0f)) // NaN-safe
            return core::makeError(where + ": alphaCutoff " + std::to_string(in.alphaCutoff) + " is not in [0, 1]");
        out.doubleSided = in.doubleSided;
        const int t = in.pbrMetallicRoughness.baseColorTexture.index;
        if (t >= 0) {
            if (size_t(t) >= model.textures.size()) return core::makeError(where + ": no texture " + std::to_string(t));
            auto known = textureOf.find(t);
            if (known == textureOf.end()) {
                core::Result<Texture> decoded = readTexture(model, file, t, images);
                if (decoded && (textureBytes += decoded->image.rgba.size()) > kMaxTextureBytes)
                    return core::makeError(file.string() + ": the file's textures decode to more than 1 GiB");
                if (decoded) {
                    known = textureOf.emplace(t, int32_t(scene.textures.size())).first;
                    scene.textures.push_back(std::move(*decoded));
                } else {
                    known = textureOf.emplace(t, decoded.errorInfo()).first;
                }
            }
            if (const auto* index = std::get_if<int32_t>(&known->second)) {
                out.baseColorTexture = *index;
            } else if (out.alphaMode != AlphaMode::Opaque) {
                return core::makeError(std::get<core::Error>(known->second).message + " (" + where +
                                       " needs its alpha)");
            } else if (dropped.insert(t).second) {
                scene.warnings.push_back(std::get<core::Error>(known->second).message +
                                         "; its opaque materials are drawn untextured");
            }
        }
        // Glass: the light it lets through taken out of its alpha (gltf_transmission.cpp).
        std::optional<std::string> transmits;
        auto transmission = readTransmission(model, in, where);
        if (!transmission) return transmission.errorInfo();
        if (*transmission && (*transmission)->factor > 0.0) {
            auto said = applyTransmission(model, file, images, in, **transmission, out, scene, textureBytes);
            if (!said) return said.errorInfo();
            transmits = std::move(*said);
        }
        // A mask whose alpha never reaches its cutoff covers nothing: the meshes wearing it
        // vanish from every pass (a BLEND factor of 0.12, as a glass pane may be authored,
        // cast as MASK at 0.5). Say so rather than leave an empty picture unexplained — by the
        // rule the passes and the truth leave it out by (coversNothing), each texture scanned once.
        bool cutWhole = false;
        if (out.alphaMode != AlphaMode::Opaque) {
            float textureAlpha = 1.0f;
            if (out.baseColorTexture >= 0) {
                auto [at, first] = maxAlphaOf.try_emplace(out.baseColorTexture, 0.0f);
                if (first) at->second = largestAlpha(scene.textures[size_t(out.baseColorTexture)].image);
                textureAlpha = at->second;
            }
            cutWhole = coversNothing(out, textureAlpha);
            if (cutWhole && !transmits) {
                const float alpha = alphaAtMost(out, textureAlpha);
                char figures[96];
                std::snprintf(figures, sizeof figures, "its alpha is at most %.3g, below its cutoff %.3g", alpha,
                              out.alphaCutoff);
                scene.warnings.push_back(where + (out.alphaMode == AlphaMode::Blend ? " (BLEND, cast as MASK)" : "") +
                                         ": " + figures + ": cut away whole, it is neither drawn nor cast");
            }
        }
        if (transmits)
            scene.warnings.push_back(
                where + ": " + *transmits +
                (cutWhole ? "; here everywhere: cut away whole, it is neither drawn nor cast" : ""));
        scene.materials.push_back(std::move(out));
    }
    return core::Ok{};
}

} // namespace shadowkit::scene::formats
