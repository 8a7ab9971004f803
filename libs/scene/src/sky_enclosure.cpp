// A model shipped inside its sky (sky_enclosure.h): which instances hide the whole sky from the
// rest of the scene, found by rays from the top of the rest towards every sun the sky could hold.
#include "shadowkit/scene/sky_enclosure.h"

#include "shadowkit/core/conventions.h"

#include <glm/gtc/constants.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>

namespace shadowkit::scene {
namespace {

// Towards the sky: elevations from 5° (a sun that low is already a grazing one) to the zenith, and
// round the compass every 15°, half a step off the axes so that no ray runs along a box sky's
// seams or through a sphere's meridians' shared vertices.
std::vector<core::Vec3> skyDirections() {
    std::vector<core::Vec3> directions{{0.0, 1.0, 0.0}}; // the zenith first: most meshes that are no sky leave it open
    for (const double elevationDegrees : {5.0, 15.0, 30.0, 45.0, 60.0, 75.0}) {
        const double elevation = glm::radians(elevationDegrees);
        for (int step = 0; step < 24; ++step) {
            const double azimuth = glm::radians(15.0 * (step + 0.5));
            directions.emplace_back(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                    -std::cos(elevation) * std::cos(azimuth));
        }
    }
    return directions;
}

// A triangle as one corner and its two edges from it, in the scene's coordinates.
struct Triangle {
    core::Vec3 a, ab, ac;
};

std::vector<Triangle> placedTriangles(const Mesh& mesh, const glm::mat4& sceneFromObject) {
    const core::Mat4 m(sceneFromObject);
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.triangleCount());
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const auto at = [&](size_t k) {
            return core::Vec3(m * core::Vec4(core::Vec3(mesh.vertices[mesh.indices[k]].position), 1.0));
        };
        const core::Vec3 a = at(i);
        triangles.push_back({a, at(i + 1) - a, at(i + 2) - a});
    }
    return triangles;
}

// Whether the ray o + t·d, t > 0, meets the triangle, its edges included (Möller & Trumbore
// 1997): a ray through a vertex or an edge two triangles share meets at least one of them.
bool meets(const Triangle& triangle, const core::Vec3& o, const core::Vec3& d) {
    constexpr double kEdge = 1e-9; // barycentric: a ray on a shared edge is not lost between its faces
    const core::Vec3 p = glm::cross(d, triangle.ac);
    const double det = glm::dot(triangle.ab, p);
    if (!(std::abs(det) > 0.0)) return false; // along its plane, or no area
    const core::Vec3 s = o - triangle.a;
    const double u = glm::dot(s, p) / det;
    if (u < -kEdge || u > 1.0 + kEdge) return false;
    const core::Vec3 q = glm::cross(s, triangle.ab);
    const double v = glm::dot(d, q) / det;
    if (v < -kEdge || u + v > 1.0 + kEdge) return false;
    return glm::dot(triangle.ac, q) / det > 0.0;
}

// Whether every ray from the top of `rest` towards the sky meets one of the triangles. Each ray
// walks the whole mesh until it meets a triangle — 605 rays, a few hundred million tests for a
// sky of a quarter of a million triangles — so they run on every core, and the first ray that
// escapes stops the rest (docs/reliability.md, "A model inside its sky", times it).
bool hidesTheSky(const std::vector<Triangle>& triangles, const core::Aabb& rest) {
    static const std::vector<core::Vec3> directions = skyDirections();
    const double top = rest.max.y;
    const core::Vec3 origins[] = {{rest.center().x, top, rest.center().z},
                                  {rest.min.x, top, rest.min.z},
                                  {rest.max.x, top, rest.min.z},
                                  {rest.min.x, top, rest.max.z},
                                  {rest.max.x, top, rest.max.z}};
    // The zenith from the middle first, alone: a mesh that is no sky almost always leaves it open.
    const auto escapes = [&](const core::Vec3& o, const core::Vec3& d) {
        return std::none_of(triangles.begin(), triangles.end(), [&](const Triangle& t) { return meets(t, o, d); });
    };
    if (escapes(origins[0], directions[0])) return false;
    std::atomic<bool> escaped = false;
    const size_t rays = std::size(origins) * directions.size();
    tbb::parallel_for(tbb::blocked_range<size_t>(1, rays), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t ray = range.begin(); ray != range.end() && !escaped.load(std::memory_order_relaxed); ++ray)
            if (escapes(origins[ray / directions.size()], directions[ray % directions.size()]))
                escaped.store(true, std::memory_order_relaxed);
    });
    return !escaped;
}

// Whether `sky` holds `rest` across the ground (x and z) and at the top: what a dome ending at
// the horizon does, whatever reaches below it.
bool holdsFromAbove(const core::Aabb& sky, const core::Aabb& rest) {
    return sky.min.x <= rest.min.x && sky.max.x >= rest.max.x && sky.min.z <= rest.min.z && sky.max.z >= rest.max.z &&
           sky.max.y >= rest.max.y;
}

} // namespace

std::vector<SkyEnclosure> findSkyEnclosures(const Scene& scene) {
    const std::vector<core::Aabb> boxes = scene.instanceBounds();
    std::vector<InstanceRef> refs;
    refs.reserve(boxes.size());
    for (uint32_t b = 0; b < scene.batches.size(); ++b)
        for (uint32_t i = 0; i < scene.batches[b].worldFromObject.size(); ++i) refs.push_back({b, i});

    // Only the largest instance left can be kSkyExtentRatio times the rest across (the rest holds
    // the next largest): the outermost sky first, then the next within it, until the largest is
    // no sky. Each round is one pass over the boxes; the rays run only where a mesh encloses.
    std::vector<bool> left(boxes.size(), true);
    std::vector<SkyEnclosure> skies;
    for (;;) {
        std::optional<size_t> largest;
        for (size_t i = 0; i < boxes.size(); ++i)
            if (left[i] && !boxes[i].isEmpty() && (!largest || boxes[i].diagonal() > boxes[*largest].diagonal()))
                largest = i;
        if (!largest) break;
        const size_t c = *largest;
        const MeshBatch& batch = scene.batches[refs[c].batch];
        if (batch.dynamic) break; // what moves is part of the scene
        core::Aabb rest;
        for (size_t i = 0; i < boxes.size(); ++i)
            if (left[i] && i != c) rest.extend(boxes[i]);
        if (rest.isEmpty() || boxes[c].diagonal() < kSkyExtentRatio * rest.diagonal() ||
            !holdsFromAbove(boxes[c], rest))
            break;
        const Mesh& mesh = scene.meshes[batch.mesh];
        if (!hidesTheSky(placedTriangles(mesh, batch.worldFromObject[refs[c].instance]), rest)) break;
        left[c] = false;
        skies.push_back({refs[c], mesh.name, boxes[c].diagonal(), 0.0});
    }
    // Each sky's rest: the scene without every sky found.
    core::Aabb rest;
    for (size_t i = 0; i < boxes.size(); ++i)
        if (left[i]) rest.extend(boxes[i]);
    for (SkyEnclosure& sky : skies) sky.restMetres = rest.diagonal();
    return skies;
}

std::vector<SkyEnclosure> leaveOutSkyEnclosures(Scene& scene) {
    std::vector<SkyEnclosure> skies = findSkyEnclosures(scene);
    if (skies.empty()) return skies;
    std::vector<std::vector<bool>> dropped(scene.batches.size());
    for (size_t b = 0; b < scene.batches.size(); ++b) dropped[b].assign(scene.batches[b].worldFromObject.size(), false);
    for (const SkyEnclosure& sky : skies) dropped[sky.instance.batch][sky.instance.instance] = true;

    // The batches that keep an instance, in their order. Tracks and deformations move dynamic
    // batches, which are never a sky: replaceBatches asserts that each keeps its batch.
    std::vector<MeshBatch> kept;
    std::vector<uint32_t> batchAt(scene.batches.size(), UINT32_MAX);
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        MeshBatch& batch = scene.batches[b];
        std::vector<glm::mat4> instances;
        for (size_t i = 0; i < batch.worldFromObject.size(); ++i)
            if (!dropped[b][i]) instances.push_back(batch.worldFromObject[i]);
        if (instances.empty()) continue;
        batch.worldFromObject = std::move(instances);
        batchAt[b] = uint32_t(kept.size());
        kept.push_back(std::move(batch));
    }
    scene.replaceBatches(std::move(kept), batchAt);
    return skies;
}

} // namespace shadowkit::scene
