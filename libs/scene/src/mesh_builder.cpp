#include "shadowkit/scene/mesh_builder.h"

#include "shadowkit/core/conventions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace shadowkit::scene {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

struct Appender {
    Mesh& mesh;
    glm::mat4 m;
    glm::mat3 n = glm::transpose(glm::inverse(glm::mat3(m)));

    uint32_t vertex(const glm::vec3& p, const glm::vec3& normal, const glm::vec3& albedo, glm::vec2 uv = {}) {
        mesh.vertices.push_back({glm::vec3(m * glm::vec4(p, 1.0f)), glm::normalize(n * normal), albedo, uv});
        return static_cast<uint32_t>(mesh.vertices.size() - 1);
    }
    void triangle(uint32_t a, uint32_t b, uint32_t c) { mesh.indices.insert(mesh.indices.end(), {a, b, c}); }
};

// Point i of `segments` round a circle; i = segments is point 0 exactly (not cos/sin of 2π in
// float, 1.7e-7 off), so a side's seam meets itself and its caps: the solid is watertight.
glm::vec3 ring(int i, int segments, float radius, float y) {
    const float a = kTwoPi * static_cast<float>(i % segments) / static_cast<float>(segments);
    return {radius * std::cos(a), y, -radius * std::sin(a)};
}

// A closed fan at height y facing `up` (+1) or down (-1).
void addDisc(Appender& out, int segments, float radius, float y, float up, const glm::vec3& albedo) {
    const uint32_t centre = out.vertex({0, y, 0}, {0, up, 0}, albedo);
    const uint32_t first = static_cast<uint32_t>(out.mesh.vertices.size());
    for (int i = 0; i < segments; ++i) out.vertex(ring(i, segments, radius, y), {0, up, 0}, albedo);
    for (int i = 0; i < segments; ++i) {
        const uint32_t a = first + static_cast<uint32_t>(i), b = first + static_cast<uint32_t>((i + 1) % segments);
        if (up > 0)
            out.triangle(centre, a, b);
        else
            out.triangle(centre, b, a);
    }
}

} // namespace

void addCylinder(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
                 const glm::vec3& albedo) {
    Appender out{mesh, objectFromPart};
    const uint32_t first = static_cast<uint32_t>(mesh.vertices.size());
    for (int i = 0; i <= segments; ++i) {
        const glm::vec3 dir = ring(i, segments, 1.0f, 0.0f);
        out.vertex(dir * radius, dir, albedo);
        out.vertex(dir * radius + glm::vec3(0, height, 0), dir, albedo);
    }
    for (uint32_t i = 0; i < static_cast<uint32_t>(segments); ++i) {
        const uint32_t b0 = first + 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
        out.triangle(b0, b1, t1);
        out.triangle(b0, t1, t0);
    }
    addDisc(out, segments, radius, 0.0f, -1.0f, albedo);
    addDisc(out, segments, radius, height, 1.0f, albedo);
}

void addCone(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
             const glm::vec3& albedo) {
    Appender out{mesh, objectFromPart};
    const float slope = radius / height; // the side normal tilts up by atan(r/h)
    const uint32_t first = static_cast<uint32_t>(mesh.vertices.size());
    for (int i = 0; i <= segments; ++i) {
        const glm::vec3 dir = ring(i, segments, 1.0f, 0.0f);
        const glm::vec3 normal = glm::normalize(dir + glm::vec3(0, slope, 0));
        out.vertex(dir * radius, normal, albedo);
        // One apex vertex per segment so each side triangle gets its own smooth normal.
        const glm::vec3 mid = ring(2 * i + 1, 2 * segments, 1.0f, 0.0f);
        out.vertex({0, height, 0}, glm::normalize(mid + glm::vec3(0, slope, 0)), albedo);
    }
    for (uint32_t i = 0; i < static_cast<uint32_t>(segments); ++i) {
        const uint32_t b0 = first + 2 * i, apex = b0 + 1, b1 = b0 + 2;
        out.triangle(b0, b1, apex);
    }
    addDisc(out, segments, radius, 0.0f, -1.0f, albedo);
}

void addIcosphere(Mesh& mesh, const glm::mat4& objectFromPart, int subdivisions, float radius,
                  const glm::vec3& albedo) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> points = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                     {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<uint32_t, 3>> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (glm::vec3& p : points) p = glm::normalize(p);
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.try_emplace(key, static_cast<uint32_t>(points.size()));
            if (inserted) points.push_back(glm::normalize(points[a] + points[b]));
            return it->second;
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& tri : tris) {
            const uint32_t ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
            next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
        }
        tris = std::move(next);
    }
    Appender out{mesh, objectFromPart};
    const uint32_t first = static_cast<uint32_t>(mesh.vertices.size());
    for (const glm::vec3& p : points) out.vertex(p * radius, p, albedo);
    for (const auto& tri : tris) out.triangle(first + tri[0], first + tri[1], first + tri[2]);
}

void addBox(Mesh& mesh, const glm::mat4& objectFromPart, const glm::vec3& halfExtent, const glm::vec3& albedo) {
    Appender out{mesh, objectFromPart};
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 normal(0.0f);
            normal[axis] = sign;
            // Two tangents with u × v = normal, so the quad winds counter-clockwise outside.
            const glm::vec3 u = glm::vec3(normal.y, normal.z, normal.x);
            const glm::vec3 v = glm::cross(normal, u);
            const glm::vec3 c = normal * halfExtent;
            const glm::vec3 du = u * halfExtent, dv = v * halfExtent;
            const uint32_t a = out.vertex(c - du - dv, normal, albedo);
            const uint32_t b = out.vertex(c + du - dv, normal, albedo);
            const uint32_t d = out.vertex(c + du + dv, normal, albedo);
            const uint32_t e = out.vertex(c - du + dv, normal, albedo);
            out.triangle(a, b, d);
            out.triangle(a, d, e);
        }
    }
}

void addCard(Mesh& mesh, const glm::mat4& objectFromPart, glm::vec2 uvMin, glm::vec2 uvMax, const glm::vec3& albedo) {
    Appender out{mesh, objectFromPart};
    const glm::vec3 facing(0, 0, 1);
    const uint32_t a = out.vertex({-0.5f, 0, 0}, facing, albedo, uvMin);
    const uint32_t b = out.vertex({0.5f, 0, 0}, facing, albedo, {uvMax.x, uvMin.y});
    const uint32_t c = out.vertex({0.5f, 1, 0}, facing, albedo, uvMax);
    const uint32_t d = out.vertex({-0.5f, 1, 0}, facing, albedo, {uvMin.x, uvMax.y});
    out.triangle(a, b, c);
    out.triangle(a, c, d);
}

void orderQuadsHighestFirst(std::span<const Vertex> vertices, std::vector<uint32_t>& indices) {
    constexpr size_t kQuad = 6;
    SK_ASSERT(indices.size() % kQuad == 0, "orderQuadsHighestFirst(): not whole quads");
    std::vector<std::pair<float, size_t>> heights; // the sum of the six corners' heights, the quad
    for (size_t q = 0; q < indices.size() / kQuad; ++q) {
        float height = 0.0f;
        for (size_t i = 0; i < kQuad; ++i) height += vertices[indices[kQuad * q + i]].position.y;
        heights.emplace_back(height, q);
    }
    std::stable_sort(heights.begin(), heights.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<uint32_t> ordered;
    ordered.reserve(indices.size());
    for (const auto& [height, q] : heights)
        ordered.insert(ordered.end(), indices.begin() + std::ptrdiff_t(kQuad * q),
                       indices.begin() + std::ptrdiff_t(kQuad * q + kQuad));
    indices = std::move(ordered);
}

} // namespace shadowkit::scene
