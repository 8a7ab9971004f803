// Per-pixel comparison of rasterized shadows with ray-traced truth (docs/references.md, evaluation §3).
#pragma once

#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/eval/truth.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::eval {

// What each pixel counted as. The numeric values are written to `class.npy` by
// `shadowkit eval --dump`: keep them stable.
enum class PixelClass : uint8_t {
    NotEvaluated = 0, // sky, or a surface facing away from the light
    LitCorrect = 1,
    ShadowCorrect = 2,
    FalseShadow = 3, // rendered shadowed, truth lit (acne, aliasing that darkens)
    FalseLit = 4,    // rendered lit, truth shadowed (peter-panning, leaks, missed casters)
    Excluded = 5,    // faces the light but raster and ray disagree on the surface (silhouettes)
};

// The figures of docs/references.md, evaluation §3; the JSON report (report.h) uses its snake_case names.
struct Figures {
    int64_t validPx = 0;
    int64_t excludedPx = 0;
    double wrongPct = 0.0;
    double falseShadowPct = 0.0;
    double falseLitPct = 0.0;
    double undersampledPct = 0.0;
    double pixelsPerTexelP50 = 0.0;
    double pixelsPerTexelP95 = 0.0;
    double pixelsPerTexelP99 = 0.0;
};

struct Comparison {
    Figures figures;
    std::vector<PixelClass> classes;   // per pixel, top row first
    std::vector<float> pixelsPerTexel; // per pixel; NaN where not valid
};

struct CompareOptions {
    // Relative view-depth agreement of raster and ray on one instance (EVALUATION.md: 0.5 %). A
    // tree is one instance: at aerial distances 0.5 % spans metres of canopy, so raster and ray
    // can see two different leaves and still "agree" (docs/materials.md, eval --depth-tolerance).
    double depthTolerance = 0.005;
    double shadowThreshold = 0.5; // rendered term below this counts as shadowed
};

// Fails (one line) when the two sets of buffers differ in size. A raster without texel
// Jacobians (texelFromPixel empty: a mask another renderer drew) has no sampling figures: its
// pixels per texel stay NaN and its percentiles 0.
core::Result<Comparison> compare(const core::RasterBuffers& raster, const TruthBuffers& truth,
                                 const CompareOptions& options = {});

// Several lights' comparisons of the same pixels as one: the figures over every (pixel, light)
// pair each light reaches (its valid pixels summed, percentiles over all of them), and per
// pixel the class that matters most — wrong under any light, then shadowed by any, then lit,
// then excluded — with the worst sampling (largest pixels per texel) of the lights. One part
// is returned as it is. Fails for no parts or parts of different sizes.
core::Result<Comparison> combine(std::span<const Comparison* const> parts);

} // namespace shadowkit::eval
