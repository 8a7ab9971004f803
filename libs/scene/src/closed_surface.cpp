#include "shadowkit/scene/closed_surface.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace shadowkit::scene {
namespace {

uint64_t edgeKey(uint32_t from, uint32_t to) { return (uint64_t(from) << 32) | to; }

// Union-find over welded vertex indices: which shell each corner belongs to.
struct Shells {
    std::vector<uint32_t> parent;
    explicit Shells(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t root(uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    }
    void join(uint32_t a, uint32_t b) { parent[root(a)] = root(b); }
};

} // namespace

bool boundsSolid(const Mesh& mesh, std::span<const uint32_t> indices) {
    if (indices.empty() || indices.size() % 3 != 0 || mesh.vertices.empty()) return false;
    for (const uint32_t i : indices)
        if (i >= mesh.vertices.size()) return false;
    // Each index replaced by the first vertex at the same position.
    std::vector<uint32_t> welded(indices.size());
    meshopt_generateShadowIndexBuffer(welded.data(), indices.data(), indices.size(), &mesh.vertices[0].position,
                                      mesh.vertices.size(), sizeof(glm::vec3), sizeof(Vertex));

    std::vector<std::array<uint32_t, 3>> triangles;
    triangles.reserve(welded.size() / 3);
    for (size_t t = 0; t < welded.size(); t += 3) {
        const std::array<uint32_t, 3> tri{welded[t], welded[t + 1], welded[t + 2]};
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue; // no area
        triangles.push_back(tri);
    }
    if (triangles.empty()) return false;

    // Watertight and oriented: each directed edge once, and its reverse once.
    std::vector<uint64_t> edges;
    edges.reserve(triangles.size() * 3);
    for (const auto& tri : triangles)
        for (int k = 0; k < 3; ++k) edges.push_back(edgeKey(tri[k], tri[(k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    for (const uint64_t e : edges)
        if (!std::binary_search(edges.begin(), edges.end(), edgeKey(uint32_t(e), uint32_t(e >> 32)))) return false;

    // Every shell encloses a positive volume: V = Σ a · (b × c) / 6 over its triangles, the
    // corners taken from a common origin (any origin gives a closed shell the same volume; one
    // inside the mesh's box keeps the products small).
    Shells shells(mesh.vertices.size());
    for (const auto& tri : triangles) shells.join(tri[0], tri[1]), shells.join(tri[1], tri[2]);
    const glm::dvec3 origin = glm::dvec3(mesh.vertices[triangles[0][0]].position);
    std::vector<double> volume(mesh.vertices.size(), 0.0);
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& tri : triangles) {
        std::array<glm::dvec3, 3> p;
        for (int k = 0; k < 3; ++k) {
            p[k] = glm::dvec3(mesh.vertices[tri[k]].position) - origin;
            lo = glm::min(lo, p[k]), hi = glm::max(hi, p[k]);
        }
        volume[shells.root(tri[0])] += glm::dot(p[0], glm::cross(p[1], p[2])) / 6.0;
    }
    // A flat shell (a two-sided card) encloses nothing; its rounding must not count as volume.
    const double extent = glm::length(hi - lo);
    const double flat = 1e-9 * extent * extent * extent;
    for (const auto& tri : triangles)
        if (!(volume[shells.root(tri[0])] > flat)) return false;
    return true;
}

} // namespace shadowkit::scene
