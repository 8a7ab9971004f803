#include "shadowkit/core/camera.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace shadowkit::core {

namespace {

// A number as a reader writes it: 14.4, 0, 1e+06 (std::to_string gives 14.434341, 0.000000).
std::string shortNumber(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return text;
}

} // namespace

Status PerspectiveCamera::validate() const {
    if (!isFinite(wsEye)) return makeError("camera eye: must be finite");
    if (glm::length(wsEye) > kMaxWorldMetres) return makeError("camera eye: at most 1e13 m from the origin");
    if (!isFinite(wsDirection) || glm::length(wsDirection) < 1e-12)
        return makeError("camera direction: must be a finite, non-zero vector");
    if (!isFinite(wsUp) || glm::length(wsUp) < 1e-12) return makeError("camera up: must be a finite, non-zero vector");
    if (glm::length(glm::cross(glm::normalize(wsDirection), glm::normalize(wsUp))) < 1e-6)
        return makeError("camera up: must not be parallel to the view direction");
    if (!(fovYDegrees > 0.0 && fovYDegrees < 180.0)) // NaN-safe
        return makeError("camera fov: must be in (0, 180) degrees, got " + shortNumber(fovYDegrees));
    if (!(aspect > 0.0 && std::isfinite(aspect))) return makeError("camera aspect: must be > 0");
    if (!(zNear > 0.0 && std::isfinite(zNear))) return makeError("camera near: must be > 0, got " + shortNumber(zNear));
    if (!(zFar > zNear && std::isfinite(zFar)))
        return makeError("camera near/far: near must be < far (near " + shortNumber(zNear) + ", far " +
                         shortNumber(zFar) + ")");
    return Ok{};
}

Mat4 PerspectiveCamera::viewFromWorld() const {
    return glm::lookAt(wsEye, wsEye + glm::normalize(wsDirection), glm::normalize(wsUp));
}

Mat4 PerspectiveCamera::clipFromView() const {
    return perspectiveZeroToOne(glm::radians(fovYDegrees), aspect, zNear, zFar);
}

namespace {

// The view space's axes in the world, as viewFromWorld's lookAt builds them: columns right, up
// and forward (orthonormal, right-handed), the rotation of the rigid worldFromView.
Mat3 cameraFrame(const PerspectiveCamera& c) {
    const Vec3 forward = glm::normalize(c.wsDirection);
    const Vec3 right = glm::normalize(glm::cross(forward, glm::normalize(c.wsUp)));
    return Mat3(right, glm::cross(right, forward), forward);
}

} // namespace

std::array<Vec3, 8> PerspectiveCamera::wsFrustumCorners() const {
    // A view point (x, y, −z) is wsEye + x·right + y·up + z·forward (cameraFrame) — no general
    // 4 × 4 inverse, which every set-up paid for here.
    const Mat3 frame = cameraFrame(*this);
    const Vec3 right = frame[0], up = frame[1], forward = frame[2];
    const double ty = std::tan(0.5 * glm::radians(fovYDegrees));
    const double tx = ty * aspect;
    std::array<Vec3, 8> corners;
    const double depths[2] = {zNear, zFar};
    const double signs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int plane = 0; plane < 2; ++plane) {
        const double z = depths[plane];
        for (int i = 0; i < 4; ++i)
            corners[static_cast<size_t>(plane * 4 + i)] =
                wsEye + (signs[i][0] * tx * z) * right + (signs[i][1] * ty * z) * up + z * forward;
    }
    return corners;
}

std::array<Plane, 6> PerspectiveCamera::wsFrustumPlanes() const {
    // Built from the corners rather than from the matrix rows so that huge far/near
    // ratios do not cancel catastrophically in the row sums.
    const auto c = wsFrustumCorners();
    const Vec3 forward = glm::normalize(wsDirection);
    const Vec3 inside = 0.5 * (c[0] + c[6]);
    auto planeThrough = [&](const Vec3& a, const Vec3& b, const Vec3& p) {
        Vec3 n = glm::cross(b - a, p - a);
        if (glm::dot(n, inside - a) > 0.0) n = -n; // orient outwards
        return Plane::fromPointNormal(a, n);
    };
    return {
        Plane::fromPointNormal(c[0], -forward), // near
        Plane::fromPointNormal(c[4], forward),  // far
        planeThrough(wsEye, c[4], c[7]),        // left
        planeThrough(wsEye, c[5], c[6]),        // right
        planeThrough(wsEye, c[4], c[5]),        // bottom
        planeThrough(wsEye, c[7], c[6]),        // top
    };
}

PerspectiveCamera extrapolatedCamera(const PerspectiveCamera& before, const PerspectiveCamera& now, double frames) {
    // One frame's motion x -> R·x + t, R = F_now · F_beforeᵀ (the frames' rotation), t = e_now −
    // R·e_before. Chasles: it is a turn by θ about an axis line through c (direction a) and a
    // slide s·a along it; repeated k times it turns by k·θ about the same line and slides k·s·a:
    //   e_k = R_kθ · (e_now − c) + c + k·s·a,
    // where, with t⊥ = t − s·a, the axis point nearest the origin solves (I − R)·c = t⊥:
    //   c = ½ · (t⊥ + cot(θ/2) · a × t⊥).
    // Below a microradian's turn per frame the motion is a slide, e_k = e_now + k·t.
    const Mat3 turn = cameraFrame(now) * glm::transpose(cameraFrame(before));
    const Vec3 t = now.wsEye - turn * before.wsEye;
    glm::dquat q = glm::normalize(glm::quat_cast(turn));
    if (q.w < 0.0) q = -q; // the short way round: θ in [0, π]
    const double theta = glm::angle(q);
    PerspectiveCamera out = now;
    if (!(theta > 1e-6)) {
        out.wsEye = now.wsEye + frames * t;
        return out;
    }
    const Vec3 axis = glm::normalize(glm::axis(q));
    const double slide = glm::dot(t, axis);
    const Vec3 across = t - slide * axis;
    const Vec3 wsAxisPoint = 0.5 * (across + glm::cross(axis, across) / std::tan(0.5 * theta));
    const Mat3 turnOn = glm::mat3_cast(glm::angleAxis(frames * theta, axis));
    out.wsEye = turnOn * (now.wsEye - wsAxisPoint) + wsAxisPoint + frames * slide * axis;
    out.wsDirection = turnOn * now.wsDirection;
    out.wsUp = turnOn * now.wsUp;
    return out;
}

Mat4 perspectiveZeroToOne(double fovYRadians, double aspect, double zNear, double zFar) {
    //  | f/a  0   0            0          |   f = cot(fov/2)
    //  | 0    f   0            0          |   z_clip/w = far(z_view - near)/((far-near)(-z_view))
    //  | 0    0   far/(n-f)    nf/(n-f)   |   -> 0 at -near, 1 at -far
    //  | 0    0  -1            0          |
    const double f = 1.0 / std::tan(0.5 * fovYRadians);
    Mat4 m(0.0);
    m[0][0] = f / aspect;
    m[1][1] = f;
    m[2][2] = zFar / (zNear - zFar);
    m[2][3] = -1.0;
    m[3][2] = zNear * zFar / (zNear - zFar);
    return m;
}

Mat4 orthoZeroToOne(double l, double r, double b, double t, double n, double f) {
    Mat4 m(1.0);
    m[0][0] = 2.0 / (r - l);
    m[1][1] = 2.0 / (t - b);
    m[2][2] = -1.0 / (f - n); // view depth is -z
    m[3][0] = -(r + l) / (r - l);
    m[3][1] = -(t + b) / (t - b);
    m[3][2] = -n / (f - n);
    return m;
}

} // namespace shadowkit::core
