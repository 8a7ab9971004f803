#include "lookup_reach.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::gl {

double lookupReachTexels(const core::FilterSettings& filter, const core::BiasSettings& bias) {
    double reach = 0.0;
    switch (filter.kind) {
    case core::ShadowFilter::Hard:
        reach = 0.0;
        break;
    case core::ShadowFilter::Pcf2:
        reach = 1.0;
        break;
    case core::ShadowFilter::PcfGrid:
        reach = 0.5 * (filter.taps - 1) + 1.0;
        break;
    case core::ShadowFilter::Poisson:
    case core::ShadowFilter::Pcss: // its widest kernel and search
        reach = filter.radiusTexels + 1.0;
        break;
    case core::ShadowFilter::Msm: // the moments' blur radius, then a bilinear lookup
        reach = filter.taps + 1.0;
        break;
    }
    // The footprint offset moves a receiver at most k (|a_u| + |a_v|) along its normal: 2k texels.
    return reach + std::abs(bias.normalOffset) + 2.0 * std::abs(bias.normalOffsetFootprint) + 2.0;
}

int guardTexelsFor(const core::FilterSettings& filter, const core::BiasSettings& bias) {
    return static_cast<int>(std::ceil(lookupReachTexels(filter, bias)));
}

namespace {

// PCSS's widest filter on virtual pages. Their guard band holds it: a band for 8 texels leaves a
// pool of 16 M texels 726 pages of 128² (the hard test's 934), one for 16 only 594, fewer than
// `noon` and `aerial` ask for (675 and 760: with 16, 114 and 175 pages fell back to coarser
// levels and `aerial`'s soft_mae rose by a quarter). The finest level's texels are about a pixel,
// where 8 texels hold a 20 m tree's penumbra under the real sun.
constexpr float kPcssVirtualMaxRadiusTexels = 8.0f;

} // namespace

core::FilterSettings lookupFilterFor(const core::ShadowSetup& setup, core::FilterSettings filter) {
    if (setup.clipmap && filter.kind == core::ShadowFilter::Pcss)
        filter.radiusTexels = std::min(filter.radiusTexels, kPcssVirtualMaxRadiusTexels);
    return filter;
}

} // namespace shadowkit::gl
