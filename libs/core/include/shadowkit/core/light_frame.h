// Light space for a directional light: the orientation of the shadow map's texel grid.
#pragma once

#include "shadowkit/core/conventions.h"

#include <initializer_list>
#include <span>

namespace shadowkit::core {

/// An orthonormal frame looking along the light: light space's axes and origin.
struct LightFrame {
    Mat4 lightFromWorld{1.0}; ///< rigid: world to light space, looking down −Z along the light
    /// Index into the candidate list of the "up" actually used (0 = the preferred one).
    int upCandidateUsed = 0;
};

/// Below this sine of the angle between a candidate "up" and the light, the candidate is
/// treated as parallel to the light and the next one is tried (0.06°: the projected
/// vector is still exact in double, but its direction would spin with tiny view changes).
inline constexpr double kParallelSine = 1e-3;

/// A look-at along `wsLightDirection` from `wsOrigin`. Light-space +Y is the first
/// candidate's component perpendicular to the light that is not (nearly) zero; the world
/// axes are tried last, so the frame is always defined, even when every candidate is
/// parallel or anti-parallel to the light.
LightFrame makeLightFrame(const Vec3& wsLightDirection, const Vec3& wsOrigin,
                          std::initializer_list<Vec3> wsUpCandidates);

/// x/y bounds and depth range of points in light space, mapped to the clip cube by an
/// orthographic projection (depth 0 nearest the light). Degenerate (zero-width) extents
/// are widened to a minimum so the matrix stays finite.
Mat4 fitOrthographic(const Mat4& lightFromWorld, std::span<const Vec3> wsPoints);

} // namespace shadowkit::core
