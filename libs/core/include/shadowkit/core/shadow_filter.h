// Shadow-map filters: how many depth comparisons make up one pixel's shadow term.
#pragma once

#include "shadowkit/core/result.h"

#include <string>
#include <string_view>

namespace shadowkit::core {

/// The numeric values are the codes the GL shaders switch on (gl's shader prelude defines
/// them from this enum): keep them stable.
/// The values are fixed: glsl/shadowkit_shadows.glsl's SK_FILTER_* repeat them for engines.
enum class ShadowFilter {
    Hard = 0,    ///< one depth comparison (what the evaluation's truth is compared with by default)
    Pcf2 = 1,    ///< hardware 2x2 percentage-closer filtering (GL_LINEAR compare; Scherzer 2005's filter)
    PcfGrid = 2, ///< N x N comparisons one texel apart, averaged
    Poisson = 3, ///< N comparisons on a Poisson disk, rotated per pixel
    Pcss = 4,    ///< percentage-closer soft shadows (Fernando 2005): a blocker search, then a kernel as wide as
                 ///< the penumbra of a light of the frame's size, both on the map's local footprint
    Msm = 5,     ///< moment shadow maps (Peters & Klein 2015): four moments per texel, prefiltered by a blur
                 ///< of N texels' radius, one filtered lookup and the Hamburger 4MSM bound
};

/// The shadow lookup filter: hard, 2×2 hardware PCF, N×N PCF or a rotated Poisson disk, and its kernel size.
struct FilterSettings {
    ShadowFilter kind = ShadowFilter::Hard; ///< which filter
    int taps = 1;              ///< PcfGrid: N of N x N, [1, 9]; Poisson, Pcss: samples, [1, 32]; Msm: blur radius
                               ///< in texels, [0, 8]; else unused
    float radiusTexels = 1.5f; ///< Poisson: disk radius; Pcss: the widest filter and search; in texels, (0, 16]
};

/// PCSS's defaults: taps of the blocker search and of the filter each, and the widest filter in
/// texels; the search reaches half a texel a tap, 8 for 16. Under the real sun a blocker 10 m up
/// casts a penumbra of 4.6 cm radius, 15 texels of the 2048² cascade serving `paper`'s ground 5 m
/// ahead: a cap of 8 drew those penumbrae at a third of their width (docs/soft-shadows.md).
/// Virtual pages cap the filter at 8, which their guard band holds (gl's renderer).
inline constexpr int kPcssTaps = 16;
inline constexpr float kPcssMaxRadiusTexels = 16.0f;
/// MSM's default prefilter: a Gaussian blur of this radius in texels (σ = radius / 2).
inline constexpr int kMsmBlurTexels = 2;

/// Checks the ranges above; the error's field is "filter.taps" or "filter.radius".
Status validate(const FilterSettings& filter);

/// The text form used by the CLI, configuration files and reports: "hard", "pcf2",
/// "pcf:N" (N x N grid), "poisson:N" (N samples), "pcss" or "pcss:N" (N samples), "msm" or "msm:N"
/// (N texels of blur).
std::string filterName(const FilterSettings& filter);
/// Parses the text form and validates it; the error's field is "filter".
Result<FilterSettings> parseFilter(std::string_view text);

/// Kernels that take taps texels away from the receiver (N x N, Poisson), unlike the
/// hardware's 2x2: on a receiver sloped in light space they need receiver-plane depth bias.
bool isWideKernel(const FilterSettings& filter);

} // namespace shadowkit::core
