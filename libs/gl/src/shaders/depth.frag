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
#endif

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
#ifdef SK_LINEAR_DEPTH
    const float d = dot(linearDepthFromWorld, vec4(wsPosition, 1.0));
    const float slope = max(abs(dFdx(d)), abs(dFdy(d))); // glPolygonOffset's "m"
    gl_FragDepth = d + slopeBias * slope + constantBias;
#ifdef SK_CHECK_CONSERVATIVE_DEPTH // tests: conservative_depth_check.glsl
    skCountConservativeDepth(gl_FragDepth, gl_FragCoord.z, 1.0 / length(linearDepthFromWorld.xyz));
#endif
#endif
    SK_DISCARD_UNCOVERED(baseColor);
}
