// Which way a face turned towards the light winds in a shadow map, so that a depth pass can
// cull the faces turned away from it under every projection, warped ones included.
//
// OpenGL culls by the winding a triangle shows in window space, not by its facing in the world.
// For a shadow map the two agree only for some matrices: TSM's trapezoid and PSM's
// post-perspective projection show a face turned towards the light clockwise for many views
// (CasterFacingTest), as would any mirrored fit. The winding follows from the matrix alone:
//
//   Let A be the x, y and w rows of clipFromWorld and V_i = (p_i, 1) a triangle's corners. The
//   window-space signed area has the sign of det[A V_0, A V_1, A V_2] / (w_0 w_1 w_2). By the
//   Cauchy–Binet formula det(A [V_0 V_1 V_2]) = k (n · c), with n the triangle's normal (its
//   corners counter-clockwise), c the map's centre of projection — the null vector of A: for
//   the sun, the direction towards it (a point at infinity), whatever the warp, since every warp
//   maps the sun to its own centre of projection — and k a constant of A alone. Every corner a
//   pass rasterises has w > 0 (clipping keeps −w ≤ x ≤ w), so all faces turned towards the light
//   show the same winding, sign(k), and all faces turned away the other.
//
// sign(k) is read off one triangle turned towards the light; its corners need not lie inside the
// map (the determinant is a polynomial identity: no division, no clipping).
#pragma once

#include "shadowkit/core/conventions.h"

namespace shadowkit::core {

/// A triangle's winding in window space (x right, y up): GL_CCW or GL_CW for glFrontFace.
enum class Winding { CounterClockwise, Clockwise };

/// How a triangle whose counter-clockwise side faces the sun (n · wsTowardsLight > 0) winds in
/// the map of `clipFromWorld`, wherever it is rasterised. A depth pass sets this as its front
/// face and culls GL_BACK to leave out the faces turned away from the light. For a matrix that
/// does not map the sun to its centre of projection (not a map of this light), or one so
/// degenerate that the sign is lost, the answer is CounterClockwise.
Winding lightFacingWinding(const Mat4& clipFromWorld, const Vec3& wsTowardsLight);

} // namespace shadowkit::core
