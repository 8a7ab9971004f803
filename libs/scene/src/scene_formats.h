// The scene file formats behind scene_io.h, one file each: gltf_read.cpp, obj_read.cpp,
// obj_write.cpp, glb_write.cpp; the helpers they share live in scene_io.cpp, where a loaded
// scene stands in near_origin.cpp, which way is up in up_axis.cpp, and its many small meshes
// merged in mesh_merge.cpp.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

// .gltf and .glb; skins and morph weights posed as at `poseSeconds` (LoadOptions::poseSeconds).
core::Result<Scene> loadGltf(const std::filesystem::path& file, double poseSeconds = 0.0);
core::Result<Scene> loadObj(const std::filesystem::path& file);
core::Status exportObj(const Scene& scene, const std::filesystem::path& file);
core::Status exportGlb(const Scene& scene, const std::filesystem::path& file);

// ".GLB" -> ".glb"
std::string lowerExtension(const std::filesystem::path& file);
// A name from the file as it may appear in a one-line message: control characters replaced.
std::string printable(std::string text);
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

// Geometry farther from the origin than this many times its own size (its bounds' diagonal)
// is moved to it (near_origin.cpp).
inline constexpr double kFarFromOriginSizes = 16.0;
// The whole metres nearest the centre of `bounds` when they lie far from the origin (above),
// else 0: what a loader subtracts, in double, before a coordinate becomes float.
glm::dvec3 anchorOf(const core::Aabb& bounds);
// Fills each batch's worldFromObject from its placements in the file's coordinates
// (`fileFromObject`, a list per batch, in double) and sets Scene::wsOrigin: a mesh far from its
// own origin is moved to it, and a scene far from the world's origin stands at its anchor with
// everything relative to it — world points stay the file's, floats stay small.
void placeNearOrigin(Scene& scene, const std::vector<std::vector<glm::dmat4>>& fileFromObject);

// Static batching (mesh_merge.cpp): in a scene of kMergeFromBatches batches or more, the opaque
// meshes placed once, under kTileTriangles each, baked into tiles of neighbours by material —
// up to kTileTriangles or kTileMeshes meshes a tile, one batch each, placed at the identity.
inline constexpr size_t kMergeFromBatches = 1024, kTileTriangles = 16384, kTileMeshes = 256;
void mergeSmallMeshes(Scene& scene);

// A z-up file's scene turned y-up, (x, y, z) → (x, z, −y), exactly (up_axis.cpp).
void turnZUpToYUp(Scene& scene);
// Why a scene loaded y-up looks z-up (its net ground area faces +z), or nullopt.
std::optional<std::string> zUpWarning(const Scene& scene);

} // namespace shadowkit::scene::formats
