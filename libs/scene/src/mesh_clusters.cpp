#include "shadowkit/scene/mesh_clusters.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace shadowkit::scene {
namespace {

// 10 bits of each coordinate interleaved: a position's place on the Z-order curve.
uint32_t spread10(uint32_t v) {
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

} // namespace

std::vector<TriangleCluster> clusterTriangles(const Mesh& mesh, std::span<uint32_t> indices, uint32_t firstIndex,
                                              uint32_t trianglesPerCluster) {
    const size_t triangles = indices.size() / 3;
    if (triangles == 0 || trianglesPerCluster == 0) return {};
    const core::Aabb& box = mesh.osBounds;
    // One scale for every axis (the box's longest side): a flat mesh — terrain — then orders by
    // its two long axes, not by height noise stretched to the same range.
    const core::Vec3 size = box.max - box.min;
    const core::Vec3 extent(std::max({size.x, size.y, size.z, 1e-12}));
    std::vector<uint32_t> code(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        core::Vec3 centroid(0.0);
        for (int k = 0; k < 3; ++k) centroid += core::Vec3(mesh.vertices[indices[3 * t + size_t(k)]].position);
        const core::Vec3 unit = glm::clamp((centroid / 3.0 - box.min) / extent, 0.0, 1.0);
        code[t] = spread10(uint32_t(unit.x * 1023.0)) | spread10(uint32_t(unit.y * 1023.0)) << 1 |
                  spread10(uint32_t(unit.z * 1023.0)) << 2;
    }
    std::vector<uint32_t> order(triangles);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
    const std::vector<uint32_t> original(indices.begin(), indices.end());
    for (size_t t = 0; t < triangles; ++t)
        for (size_t k = 0; k < 3; ++k) indices[3 * t + k] = original[3 * size_t(order[t]) + k];

    std::vector<TriangleCluster> clusters;
    for (size_t first = 0; first < triangles; first += trianglesPerCluster) {
        const size_t count = std::min<size_t>(trianglesPerCluster, triangles - first);
        TriangleCluster c{firstIndex + uint32_t(3 * first), uint32_t(3 * count), {}};
        for (size_t i = 3 * first; i < 3 * (first + count); ++i)
            c.osBounds.extend(core::Vec3(mesh.vertices[indices[i]].position));
        clusters.push_back(c);
    }
    return clusters;
}

} // namespace shadowkit::scene
