// Cascaded shadow maps (parallel-split shadow maps).
#pragma once

#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Checks CascadeOptions against the camera and the map size (what validate(CascadeOptions)
/// cannot): explicit splits must run from near to far, stabilisation needs an even map size.
/// computeShadowSetup runs both.
Status validateCascades(const ShadowSetupInputs& inputs);

/// One shadow view per split, each with `split` = [start, end] of the view depth it serves
/// (start reaches back over the blend band), fitted to that slice's own focus body.
/// Precondition: validateCascades succeeded.
ShadowSetup computeCascades(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
