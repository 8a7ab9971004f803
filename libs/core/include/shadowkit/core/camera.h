// Perspective camera: the viewer whose frustum the shadow map is focused on.
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/plane.h"
#include "shadowkit/core/result.h"

#include <array>

namespace shadowkit::core {

/// The farthest from the world's origin an eye or a scene's geometry may lie, in metres: ten times
/// the largest world offset the programs take (1e12 m), so any scene moved that far still fits.
/// Nothing beyond is resolvable in the float a GPU draws with, and Embree, given a ray origin past
/// 1.8e18 m, aborts the program rather than fail.
inline constexpr double kMaxWorldMetres = 1e13;

/// A symmetric perspective camera: eye, direction, up, vertical field of view, aspect, near and far.
struct PerspectiveCamera {
    Vec3 wsEye{0.0, 1.8, 0.0};        ///< the eye, world space
    Vec3 wsDirection{0.0, 0.0, -1.0}; ///< viewing direction; any length > 0
    Vec3 wsUp{0.0, 1.0, 0.0};         ///< need not be orthogonal to the direction
    double fovYDegrees = 60.0;        ///< vertical field of view, (0, 180)
    double aspect = 16.0 / 9.0;       ///< width / height, > 0
    double zNear = 0.5;               ///< metres, > 0
    double zFar = 500.0;              ///< metres, > zNear

    /// Checks every field; the message names the field and what is wrong.
    Status validate() const;

    /// GL look-at: the camera looks down -Z in view space.
    Mat4 viewFromWorld() const;
    /// Perspective projection with clip depth in [0,1] (near -> 0, far -> 1).
    Mat4 clipFromView() const;
    /// clipFromView() · viewFromWorld().
    Mat4 clipFromWorld() const { return clipFromView() * viewFromWorld(); }

    /// World-space corners: 0-3 on the near plane, 4-7 on the far plane, each quad in the
    /// order (-x,-y), (+x,-y), (+x,+y), (-x,+y) of the image.
    std::array<Vec3, 8> wsFrustumCorners() const;
    /// World-space planes with outward normals, in the order near, far, left, right,
    /// bottom, top. A point is inside the frustum when every signedDistance is <= 0.
    std::array<Plane, 6> wsFrustumPlanes() const;
};

/// The camera `frames` frames after `now` if it goes on moving as it moved from `before` to
/// `now`: the same rigid motion repeated — a screw, a turn about one axis and a slide along it
/// (Chasles) — so that a turntable's camera goes on round its circle and a turning one turns
/// on, where extrapolating the eye and the direction each along a straight line sends an
/// orbit's eye off on its tangent and never turns a direction past 90°. Whole or fractional
/// frames, >= 0; field of view, aspect and depth range are `now`'s.
PerspectiveCamera extrapolatedCamera(const PerspectiveCamera& before, const PerspectiveCamera& now, double frames);

/// Perspective matrix for clip depth [0,1], looking down -Z (right-handed view space).
Mat4 perspectiveZeroToOne(double fovYRadians, double aspect, double zNear, double zFar);
/// Orthographic matrix for clip depth [0,1]: x in [l,r], y in [b,t], view depth -z in [n,f].
Mat4 orthoZeroToOne(double l, double r, double b, double t, double n, double f);

} // namespace shadowkit::core
