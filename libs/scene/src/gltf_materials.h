// glTF materials and images (gltf_materials.cpp) and the buffer access they share with the
// mesh reader (gltf_read.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

// tinygltf's image callback (ImageContext as its user data). Images in a buffer view are left
// for readMaterials (their bytes are checked against the buffer there; tinygltf hands them
// over unchecked); the bytes of data URIs and external files are whole, and decoded here. An
// image that cannot be decoded does not stop the load: whether it matters depends on the
// materials that use it.
struct ImageContext {
    std::string file;
    std::map<int, core::Error> failures; // by image index
    // Why each file the glTF names that scene::readFile refused was refused ("a directory, not a
    // file"), by the path tinygltf asked for: an unreadable image says why rather than guessing.
    std::map<std::string, std::string> refusedFiles;
};
bool loadImage(tinygltf::Image* image, int index, std::string* err, std::string* warn, int reqWidth, int reqHeight,
               const unsigned char* bytes, int size, void* user);

// Scene::materials in the file's order (Mesh::material is the glTF index) and the textures
// their base colours use, decoded; the textures dropped go to Scene::warnings. A material that
// no placed primitive uses (`used[m]` false) is kept as the default, its index unchanged, and
// neither read nor checked: a spare material in a library of them must not refuse the scene.
core::Status readMaterials(const tinygltf::Model& model, const std::filesystem::path& file, const ImageContext& images,
                           const std::vector<bool>& used, Scene& scene);

// A JSON number that is a whole index in [0, 2^31), read without the float-to-int overflow that
// tinygltf's GetNumberAsInt() makes of 1e300; nullopt for anything else.
std::optional<int> indexIn(const tinygltf::Value& value);

// KHR_texture_transform on a texture reference: uv' = T · R · S · uv (the extension's order),
// or nullopt when there is none.
std::optional<glm::mat3> textureTransform(const tinygltf::TextureInfo& info);

// A texture with its sampler, from the first of its sources that decodes; else the first
// source's failure.
core::Result<Texture> readTexture(const tinygltf::Model& model, const std::filesystem::path& file, int textureIndex,
                                  const ImageContext& images);

// Decoded texels of all a file's textures, at most: 1 GiB.
constexpr size_t kMaxTextureBytes = size_t(1) << 30;

// `count` elements of `elementSize` bytes every `stride` bytes from `offset` in view
// `viewIndex`: the first byte, or an error when any of it lies outside the view or its buffer.
core::Result<const unsigned char*> bytesOf(const tinygltf::Model& model, int viewIndex, size_t offset, size_t count,
                                           size_t elementSize, size_t stride, const std::string& what);

} // namespace shadowkit::scene::formats
