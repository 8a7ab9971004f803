// The winding of light-facing triangles in a shadow map (the derivation is in the header).
#include "shadowkit/core/caster_facing.h"

namespace shadowkit::core {

Winding lightFacingWinding(const Mat4& clipFromWorld, const Vec3& wsTowardsLight) {
    // A unit right triangle through the world origin with its counter-clockwise normal
    // along wsTowardsLight: corners 0, u, v with u × v = towards.
    const Vec3 towards = glm::normalize(wsTowardsLight);
    const Vec3 helper = std::abs(towards.y) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    const Vec3 u = glm::normalize(glm::cross(helper, towards));
    const Vec3 v = glm::cross(towards, u);
    // det[A V_0, A V_1, A V_2] = det[A V_0, A (V_1 − V_0), A (V_2 − V_0)]: the edges' columns are
    // taken directly, so a map far from the world's origin does not cancel them away.
    const Vec4 columns[3] = {Vec4(0, 0, 0, 1), Vec4(u, 0), Vec4(v, 0)};
    glm::dmat3 xyw(0.0); // columns: x, y and w of the corner and the two edges
    for (int i = 0; i < 3; ++i) {
        const Vec4 cs = clipFromWorld * columns[i];
        xyw[i] = glm::dvec3(cs.x, cs.y, cs.w);
    }
    const double k = glm::determinant(xyw);
    return k < 0.0 ? Winding::Clockwise : Winding::CounterClockwise;
}

} // namespace shadowkit::core
