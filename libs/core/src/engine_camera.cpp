#include "shadowkit/core/engine_camera.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace shadowkit::core {

namespace {

constexpr const char* kProjectionField = "camera.clip_from_view";

double largestEntry(const Mat4& m) {
    double largest = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) largest = std::max(largest, std::abs(m[c][r]));
    return largest;
}

// The view-space (x, y) whose clip x/y over w are (ndcX, ndcY) at view depth z, where
// clip w there is w: solves the 2 × 2 block of x and y (rows x, y; columns x, y).
Vec2 viewXYAt(const Mat4& m, double ndcX, double ndcY, double z, double w) {
    const glm::dmat2 xy(m[0][0], m[0][1], m[1][0], m[1][1]);
    const Vec2 rhs(ndcX * w - m[2][0] * z - m[3][0], ndcY * w - m[2][1] * z - m[3][1]);
    return glm::inverse(xy) * rhs;
}

} // namespace

Result<RecognisedProjection> recogniseProjection(const Mat4& m, ClipDepthRange clipDepth, ViewHandedness handedness) {
    if (!isFinite(m)) return fieldError(kProjectionField, "must be finite");
    const double eps = 1e-12 * largestEntry(m);
    // Rows of the matrix (glm indexes [column][row]): clip w and clip z as functions of the view point.
    const Vec4 wRow(m[0][3], m[1][3], m[2][3], m[3][3]);
    const Vec4 zRow(m[0][2], m[1][2], m[2][2], m[3][2]);
    if (std::abs(wRow.x) > eps || std::abs(wRow.y) > eps)
        return fieldError(kProjectionField,
                          "clip w depends on view x or y: not a perspective or orthographic projection");
    if (std::abs(zRow.x) > eps || std::abs(zRow.y) > eps)
        return fieldError(kProjectionField, "clip depth depends on view x or y (an oblique near plane): not supported");
    if (std::abs(m[0][0] * m[1][1] - m[1][0] * m[0][1]) <= eps * eps)
        return fieldError(kProjectionField, "maps view x and y onto a line: not a projection");

    RecognisedProjection p;
    const double lo = clipDepth == ClipDepthRange::ZeroToOne ? 0.0 : -1.0, hi = 1.0;
    if (std::abs(wRow.z) > eps && std::abs(wRow.w) <= eps) {
        // Perspective: w = c·z. The view axis is where w > 0, z = forwardZ · d at distance d;
        // depth over w is then ndc(d) = a + k / d, increasing with d (k < 0) or reversed (k > 0).
        p.forwardZ = wRow.z > 0.0 ? 1.0 : -1.0;
        const double c = std::abs(wRow.z);
        const double a = zRow.z * p.forwardZ / c, k = zRow.w / c;
        if (std::abs(k) <= eps) return fieldError(kProjectionField, "clip depth over w does not change with distance");
        p.reversedZ = k > 0.0;
        const double nearValue = p.reversedZ ? hi : lo, farValue = p.reversedZ ? lo : hi;
        p.zNear = k / (nearValue - a);
        if (!(p.zNear > 0.0) || !std::isfinite(p.zNear))
            return fieldError(kProjectionField,
                              "its near plane is not in front of the eye (is the clip depth range right?)");
        // ndc(d) tends to a: the far value is reached only if a lies beyond it.
        const double beyond = p.reversedZ ? farValue - a : a - farValue;
        p.infiniteFar = !(beyond > 1e-9 * std::max(1.0, std::abs(a)));
        p.zFar = p.infiniteFar ? INFINITY : k / (farValue - a);
        if (!(p.zFar > p.zNear)) return fieldError(kProjectionField, "its far plane is not beyond its near plane");
        // x/d and y/d are linear in 1/d, so their extremes over [near, far] are at the two ends
        // (far = the limit of large d for an infinite projection).
        p.left = p.bottom = INFINITY;
        p.right = p.top = -INFINITY;
        for (double d : {p.zNear, p.infiniteFar ? INFINITY : p.zFar}) {
            for (const Vec2 ndc : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)}) {
                // At d = inf use the limit of (x, y) / d: the translation column drops out.
                const Vec2 slope = std::isinf(d) ? glm::inverse(glm::dmat2(m[0][0], m[0][1], m[1][0], m[1][1])) *
                                                       (ndc * c - Vec2(m[2][0], m[2][1]) * p.forwardZ)
                                                 : viewXYAt(m, ndc.x, ndc.y, p.forwardZ * d, c * d) / d;
                p.left = std::min(p.left, slope.x), p.right = std::max(p.right, slope.x);
                p.bottom = std::min(p.bottom, slope.y), p.top = std::max(p.top, slope.y);
            }
        }
    } else if (std::abs(wRow.z) <= eps && wRow.w > eps) {
        // Orthographic: w constant, depth linear in d.
        p.orthographic = true;
        p.forwardZ = handedness == ViewHandedness::RightHanded ? -1.0 : 1.0;
        const double c = wRow.w;
        const double a = zRow.z * p.forwardZ / c, b = zRow.w / c;
        if (std::abs(a) <= eps) return fieldError(kProjectionField, "clip depth does not change with distance");
        p.reversedZ = a < 0.0;
        p.zNear = ((p.reversedZ ? hi : lo) - b) / a;
        p.zFar = ((p.reversedZ ? lo : hi) - b) / a;
        p.left = p.bottom = INFINITY;
        p.right = p.top = -INFINITY;
        for (double d : {p.zNear, p.zFar}) {
            for (const Vec2 ndc : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)}) {
                const Vec2 xy = viewXYAt(m, ndc.x, ndc.y, p.forwardZ * d, c);
                p.left = std::min(p.left, xy.x), p.right = std::max(p.right, xy.x);
                p.bottom = std::min(p.bottom, xy.y), p.top = std::max(p.top, xy.y);
            }
        }
    } else {
        return fieldError(kProjectionField,
                          "not a perspective (clip w = ±z) or orthographic (clip w constant > 0) projection");
    }
    const double width = p.right - p.left, height = p.top - p.bottom;
    p.offCentre = std::abs(p.left + p.right) > 1e-9 * width || std::abs(p.bottom + p.top) > 1e-9 * height;
    return p;
}

Result<PerspectiveCamera> cameraFromMatrices(const EngineCamera& in) {
    const Mat4& view = in.viewFromWorld;
    if (!isFinite(view)) return fieldError("camera.view_from_world", "must be finite");
    const Mat3 rotation(view);
    const Mat3 gram = glm::transpose(rotation) * rotation;
    bool rigid = std::abs(view[0][3]) + std::abs(view[1][3]) + std::abs(view[2][3]) + std::abs(view[3][3] - 1.0) < 1e-9;
    // Engines that hold their matrices in float (OGRE's Real) round each entry of a rotation
    // to 6e-8 of it; the Gram matrix's entries then drift by a few 1e-7, and more where the
    // engine composed the rotation from a quaternion. 1e-5 takes those and still refuses a
    // scale of 1.00001 (2e-5 on the diagonal).
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) rigid = rigid && std::abs(gram[c][r] - (c == r ? 1.0 : 0.0)) < 1e-5;
    if (!rigid)
        return fieldError("camera.view_from_world",
                          "must be rigid (a rotation and a translation, no scale or projection)");

    Result<RecognisedProjection> recognised = recogniseProjection(in.clipFromView, in.clipDepth, in.handedness);
    if (!recognised) return recognised.errorInfo();
    const RecognisedProjection& p = *recognised;
    if (std::isnan(in.shadowDistance) || !(in.shadowDistance > 0.0))
        return fieldError("camera.shadow_distance", "must be > 0 metres");
    const double zFar = std::min(p.zFar, in.shadowDistance);
    if (!std::isfinite(zFar))
        return fieldError("camera.shadow_distance", "must be finite when the projection's far plane is infinite");
    if (!(zFar > p.zNear))
        return fieldError("camera.shadow_distance",
                          "must lie beyond the near plane (" + std::to_string(p.zNear) + " m)");

    // worldFromView of a rigid transform: the transposed rotation and the eye.
    const Mat3 worldFromViewRotation = glm::transpose(rotation);
    const Vec3 wsEye = -(worldFromViewRotation * Vec3(view[3]));
    const Vec3 vsForward(0.0, 0.0, p.forwardZ);

    PerspectiveCamera camera;
    camera.wsDirection = worldFromViewRotation * vsForward;
    camera.wsUp = worldFromViewRotation * Vec3(0.0, 1.0, 0.0);
    double halfWidth = 0.0, halfHeight = 0.0; // at distance 1 from the eye
    if (!p.orthographic) {
        camera.wsEye = wsEye;
        halfWidth = std::max(std::abs(p.left), std::abs(p.right));
        halfHeight = std::max(std::abs(p.bottom), std::abs(p.top));
        camera.zNear = p.zNear;
        camera.zFar = zFar;
    } else {
        // Back along the axis by D = depth / overscan: the far cross-section of a frustum whose
        // near one is the box's is then (D + depth) / D = 1 + overscan times as wide.
        const double depth = zFar - p.zNear, back = depth / kOrthographicOverscan;
        const Vec3 vsEye(0.5 * (p.left + p.right), 0.5 * (p.bottom + p.top), p.forwardZ * (p.zNear - back));
        camera.wsEye = wsEye + worldFromViewRotation * vsEye;
        halfWidth = 0.5 * (p.right - p.left) / back;
        halfHeight = 0.5 * (p.top - p.bottom) / back;
        camera.zNear = back;
        camera.zFar = back + depth;
    }
    camera.fovYDegrees = glm::degrees(2.0 * std::atan(halfHeight));
    camera.aspect = halfWidth / halfHeight;
    if (Status s = camera.validate(); !s)
        return fieldError(kProjectionField, "gives no usable frustum (" + s.error() + ")");
    return camera;
}

} // namespace shadowkit::core
