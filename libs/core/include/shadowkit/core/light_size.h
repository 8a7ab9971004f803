// The sun's size, for soft shadows: a disk of angular diameter θ (the real sun 0.53°), seen
// from a receiver through a cone of half-angle θ / 2 around the direction towards it. A blocker
// Δ metres towards the sun hides the part of the cone's cross-section there, a disk of radius
// Δ·tan(θ / 2), that it covers — so the penumbra behind an edge is 2·Δ·tan(θ / 2) wide, and a
// filter that draws it (PCSS, glsl/shadowkit_shadows.glsl) needs tan(θ / 2) and, in a map's own
// texels, how many texels that radius is at the receiver (docs/soft-shadows.md).
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"

namespace shadowkit::core {

/// The real sun's angular diameter in degrees (0.527–0.545° over the year).
inline constexpr double kRealSunAngleDegrees = 0.53;
/// The widest sun accepted: a sun of 20° is already an overcast sky's bright patch.
inline constexpr double kMaxSunAngleDegrees = 20.0;

/// [0, kMaxSunAngleDegrees] degrees, 0 a point; the error's field is "sun_angle".
Status validateSunAngle(double angularDiameterDegrees);

/// tan of the angular *radius*: the penumbra's half-width per metre from blocker to receiver,
/// what the GLSL's SkShadowOptions::lightTanHalfAngle takes (0.004625 for the real sun).
/// Engines that pass a "light size" often confuse diameter and radius; this is the radius.
double tanAngularRadius(double angularDiameterDegrees);

/// PCSS's light size in the map's own texels at wsPoint: the radius in texels of the sun's
/// cone one metre towards the light (multiply by a blocker's distance in metres for the
/// penumbra's half-width), on a plane facing the light, the geometric mean of the ellipse's two
/// axes (wsTexelSize). It changes over a warped map (LiSPSM, TSM, PSM) and from cascade to
/// cascade, so an engine's own PCSS takes it per receiver or at least per map; 0 for a point
/// sun, and 0 where the map's projection degenerates (wsTexelSize's infinite texel). Precondition: the angle validated.
double penumbraTexelsPerMetre(const Mat4& clipFromWorld, int mapSize, const Vec3& wsLightDirection,
                              double angularDiameterDegrees, const Vec3& wsPoint);

} // namespace shadowkit::core
