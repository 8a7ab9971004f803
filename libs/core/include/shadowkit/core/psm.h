// Perspective shadow maps (PSM).
#pragma once

#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// The shadow map is taken in the camera's post-perspective space, where the view's own
/// foreshortening has been applied: near objects are large, so they get many texels.
/// `views[0].lightFromWorld` is the virtual (slid-back) camera's view matrix and
/// `clipFromLight` its post-perspective transform followed by the light's projection
/// there. `warp` reports slide_back, near, light_w (the light's homogeneous w in
/// post-perspective space: > 0 ahead of the viewer, < 0 behind, 0 parallel to the view
/// plane) and inverted (1 when the depth order is reversed for a light behind the viewer).
ShadowSetup computePsm(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
