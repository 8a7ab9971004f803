// Stores the distance to the light over its range (seed 003: linear distance, the same unit
// on every face), exact per fragment. No bias here: the lookup applies it in metres. The vertex
// stages rasterise a bound of it (skLocalConservativeClipZ), so the depth written is never less
// and early depth tests may reject covered fragments before they are shaded.
in vec3 wsPosition;
layout(depth_greater) out float gl_FragDepth;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH // tests (program.h's CheckingConservativeDepth), as depth.frag's
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 0) uniform atomic_uint skCheckedFragments;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 4) uniform atomic_uint skBrokenPromises;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 8) uniform atomic_uint skWithinAMetre;
layout(binding = SK_CONSERVATIVE_DEPTH_CHECK_BINDING, offset = 12) uniform atomic_uint skWithinFiveMetres;
#endif

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    gl_FragDepth = distance(wsPosition, wsLightInvRange.xyz) * wsLightInvRange.w;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH
    const float written = clamp(gl_FragDepth, 0.0, 1.0), rasterised = clamp(gl_FragCoord.z, 0.0, 1.0);
    const float metres = (written - rasterised) / wsLightInvRange.w;
    atomicCounterIncrement(skCheckedFragments);
    if (rasterised > written + 1e-6) atomicCounterIncrement(skBrokenPromises);
    if (metres <= 1.0) atomicCounterIncrement(skWithinAMetre);
    if (metres <= 5.0) atomicCounterIncrement(skWithinFiveMetres);
#endif
    SK_DISCARD_UNCOVERED(baseColor);
}
