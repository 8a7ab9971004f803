// How far a shadow lookup reads from its receiver's texel: what receiver masks dilate by and
// what a virtual page's guard band must hold, for each filter.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::gl {

// In map texels: the filter's footprint, the normal offset (in texels' world size), and two for
// rounding and for the shift of simplified receivers' lookups.
double lookupReachTexels(const core::FilterSettings& filter, const core::BiasSettings& bias);

// A virtual page's guard band: the texels around it that a lookup in the page may read.
int guardTexelsFor(const core::FilterSettings& filter, const core::BiasSettings& bias);

// The filter the lookups of a set-up take: `filter`, its PCSS kernel capped on virtual pages
// (kPcssVirtualMaxRadiusTexels in lookup_reach.cpp says why).
core::FilterSettings lookupFilterFor(const core::ShadowSetup& setup, core::FilterSettings filter);

} // namespace shadowkit::gl
