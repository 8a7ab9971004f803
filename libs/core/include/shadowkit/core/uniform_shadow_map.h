// Uniform (orthographic) shadow maps for a directional light: `standard` and `focused`.
#pragma once

#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Standard: the whole scene box, seen along the light from a view-independent frame.
/// Texel density is constant over the scene, so a large scene gets few texels per metre.
ShadowSetup computeStandardShadowMap(const ShadowSetupInputs& inputs);

/// Focused: the same projection fitted to the focus body B only. Falls back to the
/// standard fit (and says so in `fallbacks`) when the view does not see the scene box.
ShadowSetup computeFocusedShadowMap(const ShadowSetupInputs& inputs);
/// The same with B given (computeFocusBody's result for these inputs, or the same set found
/// another way: cascades cut their splits' bodies from the view's).
ShadowSetup computeFocusedShadowMap(const ShadowSetupInputs& inputs, const ConvexBody& body);

} // namespace shadowkit::core
