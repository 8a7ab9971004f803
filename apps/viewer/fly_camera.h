// The viewer's camera: a position and a heading (yaw about +Y, pitch above the horizon),
// moved in its own frame — the usual "fly" camera of scene viewers.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/conventions.h"

namespace shadowkit::viewer {

struct FlyCamera {
    core::Vec3 wsEye{0.0};
    double yawDegrees = 0.0;   // compass: 0 looks along −Z, 90 along +X (core/conventions.h)
    double pitchDegrees = 0.0; // (−89, 89)
    double metresPerSecond = 10.0;

    // Heading from a view direction (any length > 0).
    static FlyCamera looking(const core::Vec3& wsEye, const core::Vec3& wsDirection);
    core::Vec3 wsDirection() const;
    // Moves by (right, up, forward) in units of metresPerSecond × seconds; up is world up.
    void move(const core::Vec3& rightUpForward, double seconds);
    // Turns by mouse motion in pixels (0.2° per pixel; pitch clamped short of the poles).
    void turn(double dxPixels, double dyPixels);
    // Orbits `wsTarget` by mouse motion (0.2° per pixel), keeping the distance and looking at it.
    void orbit(double dxPixels, double dyPixels, const core::Vec3& wsTarget);
    // Looks at the box's centre from above and in front of it, far enough to see it whole.
    void frame(const core::Aabb& wsBounds, double fovYDegrees);
};

} // namespace shadowkit::viewer
