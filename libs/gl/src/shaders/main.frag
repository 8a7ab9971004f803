// Diffuse sun + ambient + exponential distance fog; the sun term masked by the shadow test.
in vec3 wsPosition;
in vec3 wsNormal;
in vec3 vAlbedo;
flat in uint vSurfaceId;
in vec4 csShadow;

layout(location = 0) out vec4 outColor;

void main() {
    const vec3 n = normalize(wsNormal);
    const vec3 l = wsTowardsLight.xyz;
    const float nDotL = max(dot(n, l), 0.0);
    const float lit = nDotL > 0.0 ? shadowTerm(csShadow, wsPosition) : 0.0;
    vec3 color = vAlbedo * (ambientRadiance.rgb + sunRadiance.rgb * nDotL * lit);
    const float fog = exp(-fogColorDensity.a * distance(wsPosition, wsEye.xyz));
    color = mix(fogColorDensity.rgb, color, fog);
    outColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
