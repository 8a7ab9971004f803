// Framing a scene that has no ground to stand on (a loaded file, any size): the camera looks at
// the centre of the scene's bounds from a compass direction and a pitch, back just far enough
// for every corner to be in the picture. The still views frame a loaded scene so
// (views.cpp), and so do camera paths whose keys were written for another scene (camera_path.cpp).
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/scene/scene.h"

namespace shadowkit::scene {

// A framing's pitch is the view's or 30° down if that is steeper: a model seen level from
// its side shows its shadows edge-on, or not at all where it has no ground under it.
inline constexpr double kFramingMaxPitchDegrees = -30.0;

struct Framing {
    core::Vec3 eye;       // in the bounds' coordinates
    core::Vec3 direction; // unit, at the pitch used (at most kFramingMaxPitchDegrees)
    double pitchRadians = 0.0;
    double zNear = 0.0, zFar = 0.0; // around the bounds, with a margin
    // Exponential fog, 1/m: e^-0.3 of the light left at the far plane, whatever the scene's
    // size: depth for the eye, hardly a veil.
    double fogDensity = 0.0;
};

// Whether views and paths frame this scene rather than stand on its ground: it has no
// heightfield (a loaded file) and something to frame (`localBounds`, Scene::localBounds(), which
// the caller has at hand: it walks every instance).
inline bool isFramed(const Scene& scene, const core::Aabb& localBounds) {
    return !scene.terrain && !localBounds.isEmpty();
}

// What a framing looks at: the scene's bounds, unless a few of its placed vertices reach far
// beyond the rest — a ground quad or a sea kilometres wide round a town of 150 m (Godot's truck
// town: 12 of its 100,000 vertices span 2 km) — when the box of the rest: the vertices inside
// twice the box of the middle 98 % along each axis, where that box's diagonal is under a
// quarter of the bounds' (kFramedPartShare). Deterministic; a bounded sample of the vertices.
inline constexpr double kFramedPartShare = 0.25;
core::Aabb framedBounds(const Scene& scene, const core::Aabb& localBounds);

// Precondition: bounds not empty; aspect > 0, fovYDegrees in (0, 180).
Framing frameBounds(const core::Aabb& bounds, double azimuthRadians, double pitchRadians, double fovYDegrees,
                    double aspect);

} // namespace shadowkit::scene
