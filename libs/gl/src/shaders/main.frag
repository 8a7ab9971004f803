// Diffuse sun + local lights + ambient + exponential distance fog; each light masked by its
// shadow test.
in vec3 wsPosition;
in vec3 wsNormal;
in vec3 vAlbedo;
flat in uint vSurfaceId;
flat in float vLodError;

layout(location = 0) out vec4 outColor;

// The eye-space blurred shadow mask (Scherzer 2005 §4.3), when readBlurredMask says so.
layout(binding = SK_SHADOW_MASK_UNIT) uniform sampler2D shadowMask;

// Split colouring (Dimitrov 2007, Figure 3-2): red, green, blue, yellow, ...
const vec3 kCascadeTint[8] = vec3[](vec3(1.0, 0.35, 0.35), vec3(0.35, 1.0, 0.35), vec3(0.4, 0.5, 1.0),
    vec3(1.0, 1.0, 0.3), vec3(1.0, 0.4, 1.0), vec3(0.3, 1.0, 1.0), vec3(1.0, 0.7, 0.3), vec3(0.8, 0.8, 0.8));

// eval::aliasingMapImage's ramp (dark blue → green → yellow) over log2 pixels per texel in
// [-6, 6]: the same picture as `eval --aliasing-map`, live.
vec3 aliasingColor(float pixelsPerTexel) {
    const vec3 stops[5] = vec3[](vec3(68, 1, 84), vec3(59, 82, 139), vec3(33, 145, 140), vec3(94, 201, 98), vec3(253, 231, 37));
    const float t = clamp((log2(max(pixelsPerTexel, 1e-9)) + 6.0) / 12.0, 0.0, 1.0) * 4.0;
    const int i = min(3, int(t));
    return mix(stops[i], stops[i + 1], t - float(i)) / 255.0;
}

// Largest singular value of d(pixel)/d(texel) = 1 / smallest singular value of the
// Jacobian d(texel)/d(pixel) (core::pixelsPerTexel).
float pixelsPerTexel(vec2 dTexelDx, vec2 dTexelDy) {
    const float s = dot(dTexelDx, dTexelDx) + dot(dTexelDy, dTexelDy);
    const float det = dTexelDx.x * dTexelDy.y - dTexelDx.y * dTexelDy.x;
    const float smallest = sqrt(max(0.0, 0.5 * (s - sqrt(max(0.0, s * s - 4.0 * det * det)))));
    return smallest > 0.0 ? 1.0 / smallest : 1e9;
}

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    if (aliasingOverlay != 0) {
        // The texel of the map serving this pixel, differentiated per pixel (uniform flow).
        const vec4 t = shadowTexture(sunMapOf(wsPosition), wsPosition);
        const vec2 texel = t.xy / t.w * mapTexels;
        outColor = vec4(aliasingColor(pixelsPerTexel(dFdxFine(texel), dFdyFine(texel))), 1.0);
        SK_DISCARD_UNCOVERED(baseColor);
        return;
    }
    const vec3 n = gl_FrontFacing ? normalize(wsNormal) : -normalize(wsNormal); // double-sided: the side seen
    const vec3 l = wsTowardsLight.xyz;
    const float nDotL = max(dot(n, l), 0.0);
    const vec3 dwsdx = dFdx(wsPosition), dwsdy = dFdy(wsPosition); // uniform control flow
    float lit = 0.0;
    if (sunLights != 0 && nDotL > 0.0)
        lit = readBlurredMask != 0 ? texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0).r
                                   : shadowTerm(receiverLookup(wsPosition, vLodError), n, dwsdx, dwsdy);
    vec3 albedo = vAlbedo * baseColor.rgb;
    if (cascadeColors != 0) albedo *= kCascadeTint[sunMapOf(wsPosition) % 8];
    vec3 color = albedo * (ambientRadiance.rgb + sunRadiance.rgb * nDotL * lit + localLighting(wsPosition, n));
    const float fog = exp(-fogColorDensity.a * distance(wsPosition, wsEye.xyz));
    color = mix(fogColorDensity.rgb, color, fog);
    outColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
    SK_DISCARD_UNCOVERED(baseColor);
}
