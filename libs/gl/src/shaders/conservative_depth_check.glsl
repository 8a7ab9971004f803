// Tests only (program.h's CheckingConservativeDepth): put before the fragment stage's sources while
// a check lives, so the passes that write their depth and promise layout(depth_greater) — the
// sun's linear layout (depth.frag), the local lights (local_depth.frag) — count how well they keep it.
#define SK_CHECK_CONSERVATIVE_DEPTH 1
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 0) uniform atomic_uint skCheckedFragments;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 4) uniform atomic_uint skBrokenPromises;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 8) uniform atomic_uint skWithinAMetre;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 12) uniform atomic_uint skWithinFiveMetres;

// One fragment: the depth it wrote against the depth it was rasterised at, both as the depth test
// sees them (clamped to [0, 1] under depth clamping), `metresPerDepth` the map's metres per unit of
// stored depth. A promise broken by more than a few ulps is a bug; a bound within m metres of the
// written depth lets the early test reject a fragment more than m metres behind a stored caster
// (the bound's use).
void skCountConservativeDepth(float writtenDepth, float rasterisedDepth, float metresPerDepth) {
    const float written = clamp(writtenDepth, 0.0, 1.0), rasterised = clamp(rasterisedDepth, 0.0, 1.0);
    const float metres = (written - rasterised) * metresPerDepth;
    atomicCounterIncrement(skCheckedFragments);
    if (rasterised > written + 1e-6) atomicCounterIncrement(skBrokenPromises);
    if (metres <= 1.0) atomicCounterIncrement(skWithinAMetre);
    if (metres <= 5.0) atomicCounterIncrement(skWithinFiveMetres);
}
#line 1
