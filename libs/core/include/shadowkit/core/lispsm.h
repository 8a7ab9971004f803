// Light space perspective shadow maps (LiSPSM).
#pragma once

#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Warps the focused map with a perspective frustum P whose axis is the view direction
/// made perpendicular to the light, so that texels concentrate near the viewer.
/// `views[0].warp` reports n, f, d, gamma_degrees and uniform (1 when the warp fell back
/// to the focused uniform map). Inputs must be validated (computeShadowSetup does it).
ShadowSetup computeLispsm(const ShadowSetupInputs& inputs);
/// The same with B given (see computeFocusedShadowMap).
ShadowSetup computeLispsm(const ShadowSetupInputs& inputs, const ConvexBody& body);

/// Ratio n / d above which the warp is replaced by the uniform map it converges to: the
/// texel density then varies by (1 + d/n)² < 0.2 % across the map, below anything the
/// evaluation can see, while the warp's coefficients (≈ n²/d) would start to lose digits.
inline constexpr double kLispsmUniformRatio = 1000.0;
/// Below this sin γ the view is treated as exactly parallel to the light (no warp axis).
inline constexpr double kLispsmParallelSine = 1e-12;

} // namespace shadowkit::core
