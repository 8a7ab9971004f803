// Uniform (orthographic) shadow maps for a directional light: `standard` and `focused`.
#pragma once

#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Standard: the whole scene box, seen along the light from a view-independent frame.
/// Texel density is constant over the scene, so a large scene gets few texels per metre.
ShadowSetup computeStandardShadowMap(const ShadowSetupInputs& inputs);

/// Focused: the same projection fitted to the focus body B only. Falls back to the
/// standard fit (and says so in `fallbacks`) when the view does not see the scene box.
ShadowSetup computeFocusedShadowMap(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
