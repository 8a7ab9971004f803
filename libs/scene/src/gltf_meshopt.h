// glTF buffer views compressed with meshoptimizer's codecs (EXT_meshopt_compression, and
// KHR_meshopt_compression where its streams are of the versions Debian's library decodes):
// the two steps around tinygltf, which knows nothing of them (gltf_meshopt.cpp). Internal to
// libs/scene.
#pragma once

#include "shadowkit/core/result.h"

#include <tiny_gltf.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadowkit::scene::formats {

/// A file's bytes as tinygltf is to parse them, and the buffers that only stand in for views
/// decoded after it (placeholders: their declared lengths, by buffer index).
struct MeshoptFile {
    std::string bytes;
    std::vector<std::pair<size_t, uint64_t>> placeholders;
};

/// Before tinygltf: for a file whose buffer views are meshopt-compressed, its bytes with every
/// placeholder buffer (marked `fallback`, or with no data of its own) given one byte of data,
/// which tinygltf would otherwise refuse or fill with the glb's binary chunk. nullopt for a
/// file that uses no such extension, or one whose JSON tinygltf will refuse anyway (it is then
/// parsed as it is, for tinygltf's own message).
std::optional<MeshoptFile> prepareMeshopt(std::string_view bytes, bool binary);

/// After tinygltf: every compressed view checked against the extension's rules and decoded
/// into its place in its buffer (a placeholder first made as long as its views need). One-line
/// errors name the file, the view and what is wrong with it.
core::Status decodeMeshoptViews(tinygltf::Model& model, const std::vector<std::pair<size_t, uint64_t>>& placeholders,
                                const std::string& file);

} // namespace shadowkit::scene::formats
