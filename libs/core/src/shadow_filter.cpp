#include "shadowkit/core/shadow_filter.h"

#include <charconv>

namespace shadowkit::core {

Status validate(const FilterSettings& f) {
    if (f.kind == ShadowFilter::PcfGrid && (f.taps < 1 || f.taps > 9))
        return fieldError("filter.taps", "pcf grid size must be in [1, 9], got " + std::to_string(f.taps));
    if ((f.kind == ShadowFilter::Poisson || f.kind == ShadowFilter::Pcss) && (f.taps < 1 || f.taps > 32))
        return fieldError("filter.taps", std::string(f.kind == ShadowFilter::Pcss ? "pcss" : "poisson") +
                                             " samples must be in [1, 32], got " + std::to_string(f.taps));
    if (f.kind == ShadowFilter::Msm && (f.taps < 0 || f.taps > 8))
        return fieldError("filter.taps", "msm blur radius must be in [0, 8] texels, got " + std::to_string(f.taps));
    if (!(f.radiusTexels > 0.0f && f.radiusTexels <= 16.0f)) // NaN-safe
        return fieldError("filter.radius", "filter radius must be in (0, 16] texels");
    return Ok{};
}

std::string filterName(const FilterSettings& f) {
    switch (f.kind) {
    case ShadowFilter::Hard:
        return "hard";
    case ShadowFilter::Pcf2:
        return "pcf2";
    case ShadowFilter::PcfGrid:
        return "pcf:" + std::to_string(f.taps);
    case ShadowFilter::Poisson:
        return "poisson:" + std::to_string(f.taps);
    case ShadowFilter::Pcss:
        return f.taps == kPcssTaps ? "pcss" : "pcss:" + std::to_string(f.taps);
    case ShadowFilter::Msm:
        return f.taps == kMsmBlurTexels ? "msm" : "msm:" + std::to_string(f.taps);
    }
    return "unknown";
}

Result<FilterSettings> parseFilter(std::string_view text) {
    const Error bad = fieldError(
        "filter",
        "expected hard, pcf2, pcf:N (N 1-9), poisson:N (N 1-32), pcss[:N] (N 1-32) or msm[:N] (N 0-8), got '" +
            std::string(text) + "'");
    if (text == "hard") return FilterSettings{ShadowFilter::Hard, 1};
    if (text == "pcf2") return FilterSettings{ShadowFilter::Pcf2, 1};
    if (text == "pcss") return FilterSettings{ShadowFilter::Pcss, kPcssTaps, kPcssMaxRadiusTexels};
    if (text == "msm") return FilterSettings{ShadowFilter::Msm, kMsmBlurTexels};
    const size_t colon = text.find(':');
    if (colon == std::string_view::npos) return bad;
    const std::string_view kind = text.substr(0, colon), count = text.substr(colon + 1);
    FilterSettings f;
    if (kind == "pcf")
        f.kind = ShadowFilter::PcfGrid;
    else if (kind == "poisson")
        f.kind = ShadowFilter::Poisson;
    else if (kind == "pcss") {
        f.kind = ShadowFilter::Pcss;
        f.radiusTexels = kPcssMaxRadiusTexels;
    } else if (kind == "msm")
        f.kind = ShadowFilter::Msm;
    else
        return bad;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), f.taps);
    if (ec != std::errc{} || end != count.data() + count.size() || !validate(f)) return bad;
    return f;
}

bool isWideKernel(const FilterSettings& f) {
    return f.kind == ShadowFilter::PcfGrid || f.kind == ShadowFilter::Poisson || f.kind == ShadowFilter::Pcss;
}

} // namespace shadowkit::core
