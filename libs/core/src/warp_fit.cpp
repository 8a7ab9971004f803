#include "shadowkit/core/warp_fit.h"

#include "shadowkit/core/aabb.h"

#include <algorithm>

namespace shadowkit::core {

Mat4 fitToClipCube(const Mat4& preClipFromLight, std::span<const Vec3> lsPoints) {
    SK_ASSERT(!lsPoints.empty(), "fitToClipCube(): needs at least one point");
    Aabb ndc;
    for (const Vec3& p : lsPoints) {
        const Vec4 c = preClipFromLight * Vec4(p, 1.0);
        SK_ASSERT(c.w > 0.0, "fitToClipCube(): a point lies behind the projection centre");
        ndc.extend(Vec3(c) / c.w);
    }
    const double magnitude = std::max({glm::length(ndc.extent()), glm::length(ndc.center()), 1.0});
    for (int axis = 0; axis < 3; ++axis) { // widen zero extents so the scale stays finite
        const double grow = 0.5 * std::max(0.0, 1e-9 * magnitude - (ndc.max[axis] - ndc.min[axis]));
        ndc.min[axis] -= grow;
        ndc.max[axis] += grow;
    }
    Mat4 fit(1.0);
    for (int axis = 0; axis < 2; ++axis) { // x, y -> [-1, 1]
        fit[axis][axis] = 2.0 / (ndc.max[axis] - ndc.min[axis]);
        fit[3][axis] = -(ndc.max[axis] + ndc.min[axis]) / (ndc.max[axis] - ndc.min[axis]);
    }
    fit[2][2] = 1.0 / (ndc.max.z - ndc.min.z); // depth -> [0, 1]
    fit[3][2] = -ndc.min.z / (ndc.max.z - ndc.min.z);
    return fit * preClipFromLight;
}

} // namespace shadowkit::core
