// Light models. A directional light (the sun) is a direction of travel only.
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"

namespace shadowkit::core {

/// The sun: a direction only, world space.
struct DirectionalLight {
    Vec3 wsDirection{0.0, -1.0, 0.0}; ///< unit vector, direction the light travels (sun -> scene)

    /// Fails (naming the input) for a zero-length or non-finite direction.
    static Result<DirectionalLight> fromDirection(const Vec3& wsTravel);
    /// From sun angles in degrees (conventions.h): elevation in [-90, 90], any azimuth.
    static Result<DirectionalLight> fromSunAngles(double elevationDegrees, double azimuthDegrees);

    /// The direction from the scene towards the sun.
    Vec3 wsTowardsLight() const { return -wsDirection; }
};

// A surface faces a light when N·L > 0 — to within the rounding of the file's numbers. A face
// parallel to the light's rays (a box's side under a sun straight across it) comes out of a
// rotated model matrix in float at N·L of ±1e-7 or so (glTF's sample AnimatedMorphCube: 8.1e-8
// over its whole front face), which then decided the test for 61–64 % of a view's scored pixels
// although their light, N·L of the sun's irradiance, is the same lit or shadowed. So N·L ≤ 1e-6
// (0.00006° from grazing, ten times that rounding) is not facing: neither scored nor lit by the
// truth (eval), nor sampled by the sampling model (sampling_error.h), whose prediction must be
// of the pixels eval measures. The forests' curved surfaces have no pixel below it on any
// standard view (1e-4 took 18 of the blob forest's 588,189 `aerial` pixels and moved that view's
// pixels_per_texel_p99 by 0.3 %).
inline constexpr double kFacingCosine = 1e-6;
inline bool facesLight(const Vec3& wsNormal, const Vec3& wsTowardsLight) {
    return glm::dot(wsNormal, wsTowardsLight) > kFacingCosine; // false for a NaN normal too
}

/// Compass azimuth of a horizontal direction (conventions.h): 0 = -Z, 90 = +X, in degrees.
double azimuthDegreesOf(const Vec3& wsDirection);

} // namespace shadowkit::core
