#include "shadowkit/core/wireframe.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace shadowkit::core {

std::vector<Edge> clipVolumeEdges(const Mat4& clipFromWorld) {
    const Mat4 worldFromClip = glm::inverse(clipFromWorld);
    if (!isFinite(worldFromClip)) return {};
    // Corner i has x = bit 0, y = bit 1, depth = bit 2 (0: near, 1: far).
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const Vec4 ws = worldFromClip * Vec4((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : 0.0, 1.0);
        if (!(std::abs(ws.w) > 1e-12) || !isFinite(ws)) return {};
        corners[static_cast<size_t>(i)] = Vec3(ws) / ws.w;
    }
    std::vector<Edge> edges;
    for (int i = 0; i < 8; ++i)
        for (const int bit : {1, 2, 4})
            if (!(i & bit)) edges.emplace_back(corners[static_cast<size_t>(i)], corners[static_cast<size_t>(i | bit)]);
    return edges;
}

std::vector<Edge> bodyEdges(const ConvexBody& body) {
    std::vector<Edge> edges;
    if (body.isEmpty()) return edges;
    const Aabb box = body.bounds();
    const double eps =
        1e-9 * std::max(1.0, glm::length(box.max - box.min)); // shared points are copies: equal or nearly
    auto same = [&](const Vec3& a, const Vec3& b) { return glm::length(a - b) <= eps; };
    for (size_t f = 0; f < body.faceCount(); ++f) {
        const std::span<const Vec3> face = body.face(f);
        for (size_t i = 0; i < face.size(); ++i) {
            const Vec3& a = face[i];
            const Vec3& b = face[(i + 1) % face.size()];
            bool seen = false;
            for (const Edge& e : edges)
                seen = seen || (same(e.first, b) && same(e.second, a)) || (same(e.first, a) && same(e.second, b));
            if (!seen) edges.emplace_back(a, b);
        }
    }
    return edges;
}

} // namespace shadowkit::core
