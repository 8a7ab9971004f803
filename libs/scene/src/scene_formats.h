// The scene file formats behind scene_io.h, one file each: gltf_read.cpp, obj_read.cpp,
// obj_write.cpp, glb_write.cpp; the helpers they share live in scene_io.cpp.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

core::Result<Scene> loadGltf(const std::filesystem::path& file); // .gltf and .glb
core::Result<Scene> loadObj(const std::filesystem::path& file);
core::Status exportObj(const Scene& scene, const std::filesystem::path& file);
core::Status exportGlb(const Scene& scene, const std::filesystem::path& file);

// ".GLB" -> ".glb"
std::string lowerExtension(const std::filesystem::path& file);
// Smooth normals from triangle areas, for files that carry none.
void computeNormals(Mesh& mesh);
// Triangles and the vertices they use (not those only a mesh's coarser levels use).
struct BakedBatch {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
};
// A mesh's full triangles in object space.
BakedBatch fullMesh(const Mesh& mesh);
// `object` (a fullMesh) once per placement, transformed into world space.
BakedBatch placed(const BakedBatch& object, std::span<const glm::mat4> worldFromObject);

} // namespace shadowkit::scene::formats
