// Plane n·x + d = 0 with a unit normal n. The half-space a plane keeps is n·x + d <= 0:
// the normal points *out* of the region it bounds, matching the face normals of
// ConvexBody.
#pragma once

#include "shadowkit/core/conventions.h"

namespace shadowkit::core {

/// A plane n·p + d = 0, the normal pointing out of the half space it bounds.
struct Plane {
    Vec3 normal{0.0, 1.0, 0.0}; ///< unit, pointing out of the kept half-space
    double d = 0.0;             ///< offset: n·p + d = 0 on the plane

    /// Plane through `point` with outward normal `n` (need not be unit length).
    static Plane fromPointNormal(const Vec3& point, const Vec3& n) {
        const Vec3 unit = glm::normalize(n);
        return {unit, -glm::dot(unit, point)};
    }
    /// Signed distance: negative inside the kept half-space, positive outside.
    double signedDistance(const Vec3& p) const { return glm::dot(normal, p) + d; }
};

} // namespace shadowkit::core
