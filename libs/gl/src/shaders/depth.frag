// Hyperbolic layout: depth comes from the fixed-function stage and polygon offset
// supplies the bias. This variant does not touch gl_FragDepth at all: a shader that writes
// it on any path (even gl_FragCoord.z) turns off early and hierarchical depth tests for every
// fragment, and the shadow pass's time follows texels times overdraw (measured on an NVIDIA
// H200: 11.5 → 6.2 ms for TSM over 100,000 trees, the same figures to the last digit).
// Linear layout (SK_LINEAR_DEPTH; Martin & Tan 2004; Scherzer 2005 §4.2): the stored depth
// is the distance along the light, computed here per fragment. Writing it per vertex instead
// (z = d·w) would be interpolated linearly in the *warped* map, which is wrong inside every
// large triangle and shows as acne; per fragment it is exact, and the bias is applied by hand
// since polygon offset does not act on gl_FragDepth. The rasterised depth is then only a bound
// of the written one (depth_pass.glsl's skConservativeClipZ), kept so early depth tests still work.
in vec3 wsPosition;
#ifdef SK_LINEAR_DEPTH
// The written depth is never less than the rasterised one (depth.vert makes the rasterised depth a
// lower bound: skConservativeClipZ), so the GL may test the rasterised depth early and reject a
// covered fragment before it is shaded; without the promise any depth write turns those tests off.
layout(depth_greater) out float gl_FragDepth;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH // tests (program.h's CheckingConservativeDepth)
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 0) uniform atomic_uint skCheckedFragments;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 4) uniform atomic_uint skBrokenPromises;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 8) uniform atomic_uint skWithinAMetre;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 12) uniform atomic_uint skWithinFiveMetres;
#endif
#endif

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
#ifdef SK_LINEAR_DEPTH
    const float d = dot(linearDepthFromWorld, vec4(wsPosition, 1.0));
    const float slope = max(abs(dFdx(d)), abs(dFdy(d))); // glPolygonOffset's "m"
    gl_FragDepth = d + slopeBias * slope + constantBias;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH
    // Both as the depth test sees them: clamped to [0, 1] under depth clamping. A promise broken by
    // more than a few ulps is a bug; a bound within m metres of the written depth lets the early
    // test reject a fragment more than m metres behind a stored caster (the bound's use).
    const float written = clamp(gl_FragDepth, 0.0, 1.0), rasterised = clamp(gl_FragCoord.z, 0.0, 1.0);
    const float metres = (written - rasterised) / length(linearDepthFromWorld.xyz);
    atomicCounterIncrement(skCheckedFragments);
    if (rasterised > written + 1e-6) atomicCounterIncrement(skBrokenPromises);
    if (metres <= 1.0) atomicCounterIncrement(skWithinAMetre);
    if (metres <= 5.0) atomicCounterIncrement(skWithinFiveMetres);
#endif
#endif
    SK_DISCARD_UNCOVERED(baseColor);
}
