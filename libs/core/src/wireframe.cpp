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
    for (const auto& [a, b] : body.edges()) edges.emplace_back(a, b);
    return edges;
}

} // namespace shadowkit::core
