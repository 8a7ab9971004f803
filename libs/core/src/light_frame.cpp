#include "shadowkit/core/light_frame.h"

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"

#include "shadowkit/core/small_vector.h"

#include <algorithm>

namespace shadowkit::core {

LightFrame makeLightFrame(const Vec3& wsLightDirection, const Vec3& wsOrigin,
                          std::initializer_list<Vec3> wsUpCandidates) {
    const Vec3 l = glm::normalize(wsLightDirection);
    SmallVector<Vec3, 8> candidates;
    for (const Vec3& c : wsUpCandidates) candidates.push_back(c);
    // Every direction has a world axis at least 54.7° away from it: the frame never fails.
    for (const Vec3& c : {Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, 1, 0)}) candidates.push_back(c);

    for (size_t i = 0; i < candidates.size(); ++i) {
        const double len = glm::length(candidates[i]);
        if (!(len > 0.0)) continue; // NaN-safe
        const Vec3 c = candidates[i] / len;
        const Vec3 perpendicular = c - glm::dot(c, l) * l;
        if (glm::length(perpendicular) < kParallelSine) continue;
        return {glm::lookAt(wsOrigin, wsOrigin + l, glm::normalize(perpendicular)), static_cast<int>(i)};
    }
    SK_ASSERT(false, "makeLightFrame(): no up vector found (light direction not finite?)");
    return {};
}

Mat4 fitOrthographic(const Mat4& lightFromWorld, std::span<const Vec3> wsPoints) {
    SK_ASSERT(!wsPoints.empty(), "fitOrthographic(): needs at least one point");
    Aabb ls;
    for (const Vec3& p : wsPoints) ls.extend(Vec3(lightFromWorld * Vec4(p, 1.0)));

    // Widen zero extents (a point, a flat sheet seen edge-on) to keep 1/(max-min) finite.
    const double magnitude = std::max({glm::length(ls.extent()), glm::length(ls.center()), 1.0});
    const double minExtent = 1e-9 * magnitude;
    for (int axis = 0; axis < 3; ++axis) {
        const double grow = 0.5 * std::max(0.0, minExtent - (ls.max[axis] - ls.min[axis]));
        ls.min[axis] -= grow;
        ls.max[axis] += grow;
    }
    // The light looks down -Z: the point nearest the light has the largest z.
    return orthoZeroToOne(ls.min.x, ls.max.x, ls.min.y, ls.max.y, -ls.max.z, -ls.min.z);
}

} // namespace shadowkit::core
