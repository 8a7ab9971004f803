#version 450 core
// Diffuse sun + ambient + exponential distance fog; the sun term is masked by a hard
// shadow-map test through hardware depth comparison (sampler2DShadow, GL_LEQUAL).
in vec3 wsPosition;
in vec3 wsNormal;
in vec3 vAlbedo;
in vec4 csShadow;

layout(std140, binding = 0) uniform Frame {
    mat4 clipFromWorld;
    mat4 shadowClipFromWorld;
    vec4 wsEye;
    vec4 wsTowardsLight;
    vec4 sunRadiance;
    vec4 ambientRadiance;
    vec4 fogColorDensity;
};

layout(binding = 0) uniform sampler2DShadow shadowMap;

layout(location = 0) out vec4 outColor;

float shadowTerm() {
    const vec3 ndc = csShadow.xyz / csShadow.w;
    const vec2 ts = ndc.xy * 0.5 + 0.5;
    // Outside the map nothing is known to occlude: lit. (Focused maps cover every
    // visible receiver, so this only happens off the focus body.)
    if (csShadow.w <= 0.0 || any(lessThan(ts, vec2(0.0))) || any(greaterThan(ts, vec2(1.0)))) return 1.0;
    // Depth clamp in the shadow pass stores casters in front of the near plane at 0.
    return texture(shadowMap, vec3(ts, clamp(ndc.z, 0.0, 1.0)));
}

void main() {
    const vec3 n = normalize(wsNormal);
    const vec3 l = wsTowardsLight.xyz;
    const float nDotL = max(dot(n, l), 0.0);
    const float lit = nDotL > 0.0 ? shadowTerm() : 0.0;
    vec3 color = vAlbedo * (ambientRadiance.rgb + sunRadiance.rgb * nDotL * lit);
    const float fog = exp(-fogColorDensity.a * distance(wsPosition, wsEye.xyz));
    color = mix(fogColorDensity.rgb, color, fog);
    outColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
