// Cascaded shadow maps (parallel-split shadow maps).
#pragma once

#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

// Checks CascadeOptions (validate(CascadeOptions)), then against the camera and map size:
// explicit splits must run from near to far, stabilisation needs an even map size.
Status validateCascades(const ShadowSetupInputs& inputs);

// One shadow view per split, each with `split` = [start, end] of the view depth it serves
// (start reaches back over the blend band), fitted to that slice's own focus body.
// Precondition: validateCascades succeeded.
ShadowSetup computeCascades(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
