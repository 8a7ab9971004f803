// What a far level covers against what the full tree covers, seen orthographically: a
// rasteriser of CloudSources written apart from the bakers (billboard_cloud.h,
// octahedral_impostor.h) so that the two cannot share a mistake. Shared by their tests.
#pragma once

#include "shadowkit/scene/billboard_cloud.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::scene::testing {

// An orthographic view along `direction`: `cells` × `cells` cells over a square of `side`
// object metres centred at `centre`, each the fraction of its 16 × 16 samples that some
// triangle covers (alpha-tested triangles where the atlas's alpha at the sample passes 0.5).
struct View {
    glm::vec3 direction, centre;
    float side;
    int cells;
};

inline std::vector<double> coverageSeen(const View& view, std::span<const CloudSource> sources) {
    constexpr int kSub = 16;
    const int n = view.cells * kSub;
    const glm::vec3 d = glm::normalize(view.direction);
    const glm::vec3 helper = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, d)), v = glm::cross(d, u);
    auto toSample = [&](glm::vec3 p) {
        const glm::vec3 r = p - view.centre;
        return (glm::vec2(glm::dot(r, u), glm::dot(r, v)) / view.side + 0.5f) * float(n);
    };
    std::vector<uint8_t> covered(size_t(n) * size_t(n), 0);
    for (const CloudSource& source : sources)
        for (size_t t = 0; t + 2 < source.indices.size(); t += 3) {
            const Vertex* corner[3];
            glm::vec2 q[3];
            for (int c = 0; c < 3; ++c) {
                corner[c] = &source.mesh->vertices[source.indices[t + size_t(c)]];
                q[c] = toSample(corner[c]->position);
            }
            const float area = (q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (q[1].y - q[0].y);
            if (std::abs(area) < 1e-9f) continue;
            const glm::vec2 lo = glm::min(q[0], glm::min(q[1], q[2])), hi = glm::max(q[0], glm::max(q[1], q[2]));
            for (int y = std::max(0, int(lo.y)); y <= std::min(n - 1, int(hi.y)); ++y)
                for (int x = std::max(0, int(lo.x)); x <= std::min(n - 1, int(hi.x)); ++x) {
                    const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
                    const float b1 = ((p.x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (p.y - q[0].y)) / area;
                    const float b2 = ((q[1].x - q[0].x) * (p.y - q[0].y) - (p.x - q[0].x) * (q[1].y - q[0].y)) / area;
                    if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
                    if (source.texture) {
                        const Image& atlas = *source.texture;
                        const glm::vec2 uv = (1 - b1 - b2) * corner[0]->uv + b1 * corner[1]->uv + b2 * corner[2]->uv;
                        const int tx = std::clamp(int(uv.x * float(atlas.width)), 0, atlas.width - 1);
                        const int ty = std::clamp(int(uv.y * float(atlas.height)), 0, atlas.height - 1);
                        if (atlas.pixel(tx, ty)[3] < 128) continue;
                    }
                    covered[size_t(y) * size_t(n) + size_t(x)] = 1;
                }
        }
    std::vector<double> cells(size_t(view.cells) * size_t(view.cells), 0.0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            cells[size_t(y / kSub) * size_t(view.cells) + size_t(x / kSub)] +=
                covered[size_t(y) * size_t(n) + size_t(x)];
    for (double& c : cells) c /= kSub * kSub;
    return cells;
}

// Fractional intersection over union: Σ min / Σ max.
inline double iou(const std::vector<double>& a, const std::vector<double>& b) {
    double common = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) common += std::min(a[i], b[i]), either += std::max(a[i], b[i]);
    return either > 0 ? common / either : 1.0;
}
inline double sum(const std::vector<double>& a) {
    double s = 0;
    for (const double x : a) s += x;
    return s;
}

} // namespace shadowkit::scene::testing
