// Trapezoidal shadow maps (TSM).
#pragma once

#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Bounds the view's footprint in the light's (orthographic) post-perspective space by a
/// trapezoid along the view's centre line and maps it to the square with a 2-D projective
/// transform, so the near end of the view gets most of the map. `warp` reports lambda
/// (trapezoid height), delta (focus distance from the top line, both in light NDC units)
/// and eta (distance of the projection point Q beyond the top line).
ShadowSetup computeTsm(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
