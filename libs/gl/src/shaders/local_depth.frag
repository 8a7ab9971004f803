// Stores the distance to the light over its range (seed 003: linear distance, the same unit
// on every face), exact per fragment. No bias here: the lookup applies it in metres. The vertex
// stages rasterise a bound of it (skLocalConservativeClipZ), so the depth written is never less
// and early depth tests may reject covered fragments before they are shaded.
in vec3 wsPosition;
layout(depth_greater) out float gl_FragDepth;

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    gl_FragDepth = distance(wsPosition, wsLightInvRange.xyz) * wsLightInvRange.w;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH // tests: conservative_depth_check.glsl
    skCountConservativeDepth(gl_FragDepth, gl_FragCoord.z, 1.0 / wsLightInvRange.w);
#endif
    SK_DISCARD_UNCOVERED(baseColor);
}
