// Many small meshes placed once each, merged into spatial tiles (static batching).
//
// A town exported from a city model or an engine — every building a mesh of its own, placed
// once — loads as one batch a mesh, and every pass draws each batch with a call of its own:
// 20,000 buildings were 20,001 draws a pass and 0.46 s of CPU a frame here, where the same
// boxes instanced by one mesh were 2 draws (reliability.md, "Many meshes"). Engines answer with
// static batching; so does the loader. Opaque meshes placed once, under kTileTriangles each,
// are baked into scene coordinates and gathered by material into tiles of neighbours (their
// centres split at the median of the widest axis), so a pass culls a tile as it culled its
// buildings, and a tile of kClusterMinTriangles or more (gl::GpuScene) is drawn by its clusters
// where a pass sees part of it. Only a scene of kMergeFromBatches batches or more is merged: below that the
// draws cost less than the tiles' coarser culling and levels, and the tile, not the building,
// becomes the instance the evaluation's raster and ray must agree on.
#include "scene_formats.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>

namespace shadowkit::scene::formats {

namespace {

struct Candidate {
    core::Vec3 centre; // of its placed box, in scene coordinates
    size_t batch = 0;
    size_t triangles = 0;
};

// Splits `items` at the median of its centres along their widest axis until each part holds
// at most kTileMeshes meshes and kTileTriangles triangles (or one mesh): tiles of neighbours,
// compact whatever the town's shape.
void splitIntoTiles(std::span<Candidate> items, std::vector<std::span<Candidate>>& tiles) {
    size_t triangles = 0;
    for (const Candidate& c : items) triangles += c.triangles;
    if (items.size() <= 1 || (items.size() <= kTileMeshes && triangles <= kTileTriangles)) {
        tiles.push_back(items);
        return;
    }
    core::Aabb box;
    for (const Candidate& c : items) box.extend(c.centre);
    const core::Vec3 extent = box.extent();
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const auto middle = items.begin() + std::ptrdiff_t(items.size() / 2);
    std::nth_element(items.begin(), middle, items.end(), [axis](const Candidate& a, const Candidate& b) {
        return a.centre[axis] < b.centre[axis] || (a.centre[axis] == b.centre[axis] && a.batch < b.batch);
    });
    splitIntoTiles(items.first(items.size() / 2), tiles);
    splitIntoTiles(items.subspan(items.size() / 2), tiles);
}

} // namespace

void mergeSmallMeshes(Scene& scene) {
    if (scene.batches.size() < kMergeFromBatches) return;
    // The batches to merge, by material: static, placed once, opaque, without levels of their own.
    std::map<int32_t, std::vector<size_t>> byMaterial;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const MeshBatch& batch = scene.batches[b];
        const Mesh& mesh = scene.meshes[batch.mesh];
        const Material* material = scene.materialOf(mesh);
        if (batch.dynamic || batch.worldFromObject.size() != 1 || !mesh.authoredLods.empty() ||
            (material && material->alphaTested()) || mesh.triangleCount() >= kTileTriangles)
            continue;
        byMaterial[mesh.material].push_back(b);
    }
    size_t merging = 0;
    for (const auto& [material, batches] : byMaterial) merging += batches.size();
    if (merging < 2) return;

    std::vector<bool> merged(scene.batches.size(), false);
    std::vector<Mesh> tiles;
    for (auto& [material, batches] : byMaterial) {
        std::vector<Candidate> candidates;
        for (size_t b : batches) {
            const MeshBatch& batch = scene.batches[b];
            const Mesh& mesh = scene.meshes[batch.mesh];
            const core::Aabb box = core::transformBounds(core::Mat4(batch.worldFromObject[0]), mesh.osBounds);
            candidates.push_back({box.center(), b, mesh.triangleCount()});
        }
        std::vector<std::span<Candidate>> parts;
        splitIntoTiles(candidates, parts);
        for (const std::span<Candidate> part : parts) {
            Mesh tile;
            tile.material = material;
            tile.name = "tile " + std::to_string(tiles.size()) + " (" + std::to_string(part.size()) + " meshes)";
            for (const Candidate& c : part) {
                const MeshBatch& batch = scene.batches[c.batch];
                // In scene coordinates. A mirrored placement's triangles are kept turned
                // (gltf_read.cpp), so placed they wind counter-clockwise as they are.
                const BakedBatch baked = placed(fullMesh(scene.meshes[batch.mesh]), batch.worldFromObject);
                const auto base = uint32_t(tile.vertices.size());
                tile.vertices.insert(tile.vertices.end(), baked.vertices.begin(), baked.vertices.end());
                for (uint32_t i : baked.indices) tile.indices.push_back(base + i);
                merged[c.batch] = true;
            }
            tile.computeBounds();
            tiles.push_back(std::move(tile));
        }
    }

    // The batches left as they were, in their order, then a batch a tile; the meshes only merged go.
    std::vector<MeshBatch> kept;
    std::vector<uint32_t> batchAt(scene.batches.size(), UINT32_MAX); // a dynamic batch is never merged
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        if (merged[b]) continue;
        batchAt[b] = uint32_t(kept.size());
        kept.push_back(std::move(scene.batches[b]));
    }
    for (Mesh& tile : tiles) {
        scene.meshes.push_back(std::move(tile));
        kept.push_back({uint32_t(scene.meshes.size() - 1), {glm::mat4(1.0f)}, false});
    }
    scene.replaceBatches(std::move(kept), batchAt);
}

} // namespace shadowkit::scene::formats
