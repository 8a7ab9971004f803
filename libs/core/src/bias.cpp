// Depth bias settings.
//
// Based on: Scherzer 2005 §4.2 (constant, slope-scale, linear z, back-side rendering; 2.0/4.0
// as the paper's working slope-scale bias), the shadow-mapping lecture notes (bias basics),
// normal offset (Holbert 2011) and receiver-plane depth bias (Isidoro 2006); full citations
// in docs/references.md.
#include "shadowkit/core/bias.h"

#include <cmath>

namespace shadowkit::core {

Status validate(const BiasSettings& b) {
    if (!(b.slope >= 0.0 && b.slope <= 100.0)) return fieldError("bias.slope", "must be in [0, 100]"); // NaN-safe
    if (!(b.constant >= 0.0 && b.constant <= 1e6)) return fieldError("bias.constant", "must be in [0, 1e6]");
    if (!(b.normalOffset >= 0.0 && b.normalOffset <= 10.0))
        return fieldError("bias.normal_offset", "must be in [0, 10] texels");
    if (!(b.normalOffsetFootprint >= 0.0 && b.normalOffsetFootprint <= 10.0))
        return fieldError("bias.normal_offset_footprint", "must be in [0, 10] texel footprints");
    return Ok{};
}

BiasSettings recommendedBias(Technique technique, DepthLayout, const FilterSettings& filter) {
    // Slope and constant chosen by wrong_pct on the `paper` and `perpendicular` views of the
    // default forest at 2048² (docs/bias-and-filtering.md; `shadowkit compare` over six
    // settings each):
    //   tsm, lispsm, csm (and virtual, whose texels are the smallest): slope 1 / constant 2.
    //     Their receivers are moved off their own triangle by a quarter of the texel's
    //     footprint on it (½ clears the plane exactly; the slope term already clears part of
    //     it) plus a twentieth of a texel along the shading normal: of the rules measured on
    //     the corpus of public models, the forest and 224 files of public suites, the one that
    //     keeps most views within 1.5 x focused + 0.1 points (65 of the corpus's 66, 217 of
    //     the 224 files, against 59 and 204 for the old half texel along the normal, which
    //     lifts a face the sun meets head-on as far as one it grazes, and so lights the ground
    //     at the foot of a caster wherever a warp stretches texels).
    //   psm: 1 / 2 without offset (2.78 / 1.56 % against 2.97 / 1.60 %); the offset hurts
    //     where its far texels are huge.
    //   standard, focused: Scherzer 2005's 2 / 4: a normal offset of half a texel is half a
    //     metre there and detaches shadows (focused perpendicular 2.52 % against 1.85 %).
    // The layout does not change the choice: the linear layout applies the same numbers.
    BiasSettings b;
    switch (technique) {
    case Technique::Tsm:
    case Technique::Lispsm:
    case Technique::Csm:
    case Technique::Virtual:
        b.slope = 1.0;
        b.constant = 2.0;
        b.normalOffset = 0.05;
        b.normalOffsetFootprint = 0.25;
        // The offsets are against the receiver's own surface; where the light grazes it they
        // carry its lookup far enough to leave a distant caster's shadow (the clear-coat card's
        // spheres' rims out of their walls' shadows: `paper` 3.15 % against focused's 1.39).
        // The guard keeps such a receiver shadowed: every view of the corpus within the bound
        // (66 of 66); the forests' figures moved by 0.02 points at most (docs/bias-and-filtering.md).
        b.offsetGuard = true;
        break;
    case Technique::Psm:
        b.slope = 1.0;
        b.constant = 2.0;
        break;
    case Technique::Standard:
    case Technique::Focused:
        break;
    }
    // Kernels wider than the hardware's 2x2 compare taps texels away from the receiver: on a
    // surface sloped in light space they self-shadow unless the reference depth follows the
    // receiver's plane (measured: a 5 x 5 grid gives 0.8 on lit sloped ground; gl tests).
    b.receiverPlane = isWideKernel(filter);
    // Casters two-sided (CasterCull::None), although a closed caster's far side is never the first
    // surface the light meets: under slope-scaled offset it is what bounds the offset of a steep
    // near side. Culled (BackOfClosed), light leaks under the rims of steep surfaces — the
    // conifers' cone layers with the sun overhead: `standard` on `noon` of the golden forest
    // 1.23 % wrong against 1.55 % (docs/performance.md, "Work: samples written per texel").
    b.cull = CasterCull::None;
    return b;
}

} // namespace shadowkit::core
