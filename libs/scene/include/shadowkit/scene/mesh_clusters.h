// Spatial clusters of a large mesh's triangles, so that a pass seeing a small part of one
// instance — a virtual shadow map's page over a kilometre of terrain — draws only that part.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::scene {

struct TriangleCluster {
    uint32_t firstIndex = 0; // into the index buffer the triangles were reordered in
    uint32_t indexCount = 0;
    core::Aabb osBounds; // object-space bounds of its triangles
};

// Reorders the triangles of `indices` (a triangle list over `mesh`'s vertices, `firstIndex` its
// start in the whole buffer) along a Morton curve of their centroids in the mesh's box, and
// cuts them into clusters of at most `trianglesPerCluster` consecutive triangles: neighbours in
// space become neighbours in the buffer, so each cluster's box is small. The same triangles,
// each with its vertices in the same order: only which triangle comes first changes.
std::vector<TriangleCluster> clusterTriangles(const Mesh& mesh, std::span<uint32_t> indices, uint32_t firstIndex,
                                              uint32_t trianglesPerCluster);

} // namespace shadowkit::scene
