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
const vec3 kCascadeTint[SK_MAX_CASCADES] = vec3[](vec3(1.0, 0.35, 0.35), vec3(0.35, 1.0, 0.35), vec3(0.4, 0.5, 1.0),
    vec3(1.0, 1.0, 0.3), vec3(1.0, 0.4, 1.0), vec3(0.3, 1.0, 1.0), vec3(1.0, 0.7, 0.3), vec3(0.8, 0.8, 0.8));

void main() {
    const vec3 n = normalize(wsNormal);
    const vec3 l = wsTowardsLight.xyz;
    const float nDotL = max(dot(n, l), 0.0);
    const vec3 dwsdx = dFdx(wsPosition), dwsdy = dFdy(wsPosition); // uniform control flow
    float lit = 0.0;
    if (sunLights != 0 && nDotL > 0.0)
        lit = readBlurredMask != 0 ? texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0).r
                                   : shadowTerm(receiverLookup(wsPosition, vLodError), n, dwsdx, dwsdy);
    vec3 albedo = vAlbedo;
    if (cascadeColors != 0) albedo *= kCascadeTint[cascadeOf(viewDepthOf(wsPosition))];
    vec3 color = albedo * (ambientRadiance.rgb + sunRadiance.rgb * nDotL * lit + localLighting(wsPosition, n));
    const float fog = exp(-fogColorDensity.a * distance(wsPosition, wsEye.xyz));
    color = mix(fogColorDensity.rgb, color, fog);
    outColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
