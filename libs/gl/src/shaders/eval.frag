// Evaluation pass: the per-pixel buffers the ray-traced comparison needs (core::RasterBuffers).
// Its shaded variant (SK_EVAL_SHADED 1, the sun's test only) also writes the main pass's colour
// (shade.glsl), so an evaluation that wants the picture draws the camera's view once.
in vec3 wsPosition;
in vec3 wsNormal;
in vec3 vAlbedo;
flat in uint vSurfaceId;
flat in float vLodError;

layout(location = 0) out float outShadowTerm;
layout(location = 1) out uint outSurfaceId;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec4 outNormal;
layout(location = 4) out vec2 outTexel;
layout(location = 5) out vec4 outTexelFromPixel;
#if SK_EVAL_SHADED
layout(location = 6) out vec4 outColor;
#endif

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    const vec3 dwsdx = dFdx(wsPosition), dwsdy = dFdy(wsPosition); // uniform control flow
    const vec3 n = gl_FrontFacing ? normalize(wsNormal) : -normalize(wsNormal); // double-sided: the side seen
    outSurfaceId = vSurfaceId;
    outViewDepth = viewDepthOf(wsPosition);
    // The drawn triangle's own plane (the truth's geometric normal, on the shading normal's
    // side): the plane the texel derivatives below follow, so a sampling prediction from
    // this read-back (core::receiverSamples) looks at the same surface eval measures.
    vec3 face = normalize(cross(dwsdx, dwsdy));
    if (dot(face, n) < 0.0) face = -face;
    outNormal = vec4(face, 0.0);
    vec2 texel;
    if (evalLight >= 0) {
        // A local light's map test, and the texel of its map with the analytic Jacobian.
        outShadowTerm = localShadowTerm(evalLight, wsPosition, n);
        vec4 texelFromPixel;
        outTexel = localTexel(evalLight, wsPosition, localMapTexels, dFdxFine(wsPosition), dFdyFine(wsPosition), texelFromPixel);
        outTexelFromPixel = vec4(texelFromPixel.xy, -texelFromPixel.zw); // rows run down, as below
        SK_DISCARD_UNCOVERED(baseColor);
        return;
    } else {
        // The maps' test alone, without N·L (also the mask the eye-space blur starts from).
        outShadowTerm = shadowTerm(receiverLookup(wsPosition, vLodError), n, dwsdx, dwsdy);
        // Texel position in the map that serves this pixel.
        const vec4 t = shadowTexture(sunMapOf(wsPosition), wsPosition);
        texel = t.xy / t.w * mapTexels;
#if SK_EVAL_SHADED
        // main.frag's colour from the same test (without the blurred mask: a frame with the
        // eye-space blur draws the two passes apart).
        const float nDotL = max(dot(n, wsTowardsLight.xyz), 0.0);
        const float lit = sunLights != 0 && nDotL > 0.0 ? outShadowTerm : 0.0;
        outColor = aliasingOverlay != 0 ? aliasingOverlayColor(wsPosition)
                                        : shadedColor(vAlbedo * baseColor.rgb, wsPosition, n, nDotL, lit);
#endif
    }
    outTexel = texel;
    // Screen derivatives of the texel position (fine: per pixel, not per 2x2 quad).
    // GL's y runs up; negate so the second column is the derivative along image rows (down).
    outTexelFromPixel = vec4(dFdxFine(texel), -dFdyFine(texel));
    SK_DISCARD_UNCOVERED(baseColor);
}
