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

/// Compass azimuth of a horizontal direction (conventions.h): 0 = -Z, 90 = +X, in degrees.
double azimuthDegreesOf(const Vec3& wsDirection);

} // namespace shadowkit::core
