// The main pass: the shaded frame (shade.glsl), the sun masked by its shadow test.
in vec3 wsPosition;
in vec3 wsNormal;
in vec3 vAlbedo;
flat in uint vSurfaceId;
flat in float vLodError;

layout(location = 0) out vec4 outColor;

// The eye-space blurred shadow mask (Scherzer 2005 §4.3), when readBlurredMask says so.
layout(binding = SK_SHADOW_MASK_UNIT) uniform sampler2D shadowMask;

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    if (aliasingOverlay != 0) {
        outColor = aliasingOverlayColor(wsPosition);
        SK_DISCARD_UNCOVERED(baseColor);
        return;
    }
    const vec3 n = gl_FrontFacing ? normalize(wsNormal) : -normalize(wsNormal); // double-sided: the side seen
    const float nDotL = max(dot(n, wsTowardsLight.xyz), 0.0);
    const vec3 dwsdx = dFdx(wsPosition), dwsdy = dFdy(wsPosition); // uniform control flow
    float lit = 0.0;
    if (sunLights != 0 && nDotL > 0.0)
        lit = readBlurredMask != 0 ? texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0).r
                                   : shadowTerm(receiverLookup(wsPosition, vLodError), n, dwsdx, dwsdy);
    outColor = shadedColor(vAlbedo * baseColor.rgb, wsPosition, n, nDotL, lit);
    SK_DISCARD_UNCOVERED(baseColor);
}
