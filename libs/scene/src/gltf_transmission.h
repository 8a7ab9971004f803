// KHR_materials_transmission read for shadows (gltf_transmission.cpp). Internal to libs/scene.
#pragma once

#include "gltf_materials.h"

#include <filesystem>
#include <optional>
#include <string>

namespace shadowkit::scene::formats {

// A texture of a material's and what its primitives read it with: the glTF texture reference
// (index, TEXCOORD set, KHR_texture_transform) and what it is, for messages.
struct TextureUse {
    tinygltf::TextureInfo info;
    const char* label;
};

// The texture whose coordinates a material's primitives keep: its base colour texture, or where
// it has none the texture its KHR_materials_transmission reads (its alpha then comes from
// there: applyTransmission, below); nullopt for neither.
std::optional<TextureUse> cuttingTexture(const tinygltf::Model& model, const tinygltf::Material& material);

// A material's KHR_materials_transmission: the share of light its surface lets through,
// transmissionFactor times the red channel of transmissionTexture where it has one.
struct Transmission {
    double factor = 0.0;
    std::optional<tinygltf::TextureInfo> texture;
};

// The material's transmission, nullopt without the extension; an error naming the material
// (`where`) for a factor outside [0, 1] or a texture that names none of the file's.
core::Result<std::optional<Transmission>> readTransmission(const tinygltf::Model& model, const tinygltf::Material& in,
                                                           const std::string& where);

// The material's surface as shadows see it: what it lets through taken out of its alpha, an
// opaque material made a mask at 0.5 (textures decoded and added to scene.textures, counted
// in `textureBytes`). Returns the sentence its warning says.
core::Result<std::string> applyTransmission(const tinygltf::Model& model, const std::filesystem::path& file,
                                            const ImageContext& images, const tinygltf::Material& in,
                                            const Transmission& transmission, Material& out, Scene& scene,
                                            size_t& textureBytes);

} // namespace shadowkit::scene::formats
