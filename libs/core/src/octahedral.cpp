// The hemi-octahedral map (octahedral.h; Cigolle et al. 2014, §3.6).
#include "shadowkit/core/octahedral.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace shadowkit::core {

glm::vec2 hemiOctahedralFromDirection(glm::vec3 direction) {
    if (!(std::isfinite(direction.x) && std::isfinite(direction.y) && std::isfinite(direction.z))) return {0.5f, 0.5f};
    if (direction.y < 0.0f) {
        // Below the horizon: seen from the horizon in the same azimuth.
        direction.y = 0.0f;
        if (direction.x == 0.0f && direction.z == 0.0f) direction.x = 1.0f;
    }
    const float l1 = std::abs(direction.x) + direction.y + std::abs(direction.z);
    if (!(l1 > 0.0f)) return {0.5f, 0.5f};
    const float x = direction.x / l1, z = direction.z / l1;
    return {std::clamp(0.5f * (x + z) + 0.5f, 0.0f, 1.0f), std::clamp(0.5f * (x - z) + 0.5f, 0.0f, 1.0f)};
}

glm::vec3 directionFromHemiOctahedral(glm::vec2 uv) {
    auto clamped = [](float t) { return std::isfinite(t) ? std::clamp(t, 0.0f, 1.0f) : 0.5f; };
    const float u = 2.0f * clamped(uv.x) - 1.0f, v = 2.0f * clamped(uv.y) - 1.0f;
    const float x = 0.5f * (u + v), z = 0.5f * (u - v);
    const float y = std::max(0.0f, 1.0f - std::abs(x) - std::abs(z));
    return glm::normalize(glm::vec3(x, y, z));
}

} // namespace shadowkit::core
