#include "shadowkit/core/visible_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowkit::core {

std::optional<Vec2> visibleDepthRange(std::span<const float> viewDepth) {
    float lo = std::numeric_limits<float>::infinity(), hi = 0.0f;
    for (const float d : viewDepth) {
        if (!(d > 0.0f) || !std::isfinite(d)) continue; // NaN-safe: sky, background, garbage
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    if (!(hi > 0.0f)) return std::nullopt;
    if (!(hi > lo)) hi = std::nextafter(lo, std::numeric_limits<float>::infinity()); // one depth: a thin slab
    return Vec2(lo, hi);
}

} // namespace shadowkit::core
