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

// The texture reference a `textureInfo` JSON object writes (index, texCoord, its extensions).
std::optional<tinygltf::TextureInfo> textureInfoOf(const tinygltf::Value& value) {
    if (!value.IsObject() || !value.Has("index") || !value.Get("index").IsNumber()) return std::nullopt;
    tinygltf::TextureInfo info;
    info.index = value.Get("index").GetNumberAsInt();
    if (value.Has("texCoord") && value.Get("texCoord").IsNumber())
        info.texCoord = value.Get("texCoord").GetNumberAsInt();
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
            return core::makeError(what + "'s transmissionTexture names no texture of the file's");
    }
    return std::optional<Transmission>(std::move(out));
}

core::Result<std::string> applyTransmission(const tinygltf::Model& model, const fs::path& file,
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
    const tinygltf::TextureInfo& base = in.pbrMetallicRoughness.baseColorTexture;
    if (!pattern) {
        out.baseColorFactor.a *= 1.0f - passes;
    } else if (out.baseColorTexture < 0 && base.index < 0) {
        // The pattern alone cuts: white texels (the factor keeps its colour), alpha what it stops.
        Texture cut = std::move(*pattern);
        for (size_t i = 0; i < cut.image.rgba.size(); i += 4) {
            const float stops = 1.0f - passes * cut.image.rgba[i] / 255.0f;
            cut.image.rgba[i] = cut.image.rgba[i + 1] = cut.image.rgba[i + 2] = 255;
            cut.image.rgba[i + 3] = uint8_t(std::lround(255.0f * stops));
        }
        said += " where its transmission texture lets all through";
        if (core::Status s = addTexture(std::move(cut)); !s) return s.errorInfo();
    } else if (out.baseColorTexture >= 0 && base.texCoord == transmission.texture->texCoord &&
               textureTransform(base) == textureTransform(*transmission.texture)) {
        // Both read the same coordinates: the base colour texture's alpha times what the pattern
        // stops at each of its texels (a copy: other materials may share the base texture).
        Texture cut = scene.textures[size_t(out.baseColorTexture)];
        for (int y = 0; y < cut.image.height; ++y)
            for (int x = 0; x < cut.image.width; ++x) {
                uint8_t& alpha = cut.image.pixel(x, y)[3];
                alpha = uint8_t(std::lround(alpha * (1.0f - passes * redAt(pattern->image, cut.image, x, y))));
            }
        said += " where its transmission texture lets all through";
        if (core::Status s = addTexture(std::move(cut)); !s) return s.errorInfo();
    } else {
        const float mean = meanRed(pattern->image);
        said += " where its transmission texture lets all through, which reads other coordinates than its base "
                "colour texture: taken at its mean, " +
                percent(passes * mean);
        out.baseColorFactor.a *= 1.0f - passes * mean;
    }
    if (out.alphaMode == AlphaMode::Opaque) {
        out.alphaMode = AlphaMode::Mask;
        out.alphaCutoff = 0.5f;
    }
    char cutoff[64];
    std::snprintf(cutoff, sizeof cutoff, "%.3g", out.alphaCutoff);
    return said + ": taken out of its alpha, which its cutoff " + cutoff +
           " then cuts (shadowkit has no transparency), so the sun passes it as it passes glass";
}

} // namespace shadowkit::scene::formats
