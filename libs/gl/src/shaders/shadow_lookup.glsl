// The hard shadow-map test through hardware depth comparison (sampler2DShadow, GL_LEQUAL).
layout(binding = 0) uniform sampler2DShadow shadowMap;

vec3 shadowNdc(vec4 cs) { return cs.xyz / cs.w; }

float shadowTerm(vec4 cs, vec3 ws) {
    const vec3 ndc = shadowNdc(cs);
    const vec2 ts = ndc.xy * 0.5 + 0.5;
    // Outside the map nothing is known to occlude: lit. (Focused maps cover every
    // visible receiver, so this only happens off the focus body.)
    if (cs.w <= 0.0 || any(lessThan(ts, vec2(0.0))) || any(greaterThan(ts, vec2(1.0)))) return 1.0;
    // The reference depth in the map's layout. Depth clamp in the shadow pass stores
    // casters in front of the near plane at 0.
    const float depth = shadowDepthLayout.x > 0.5 ? dot(shadowLinearDepthFromWorld, vec4(ws, 1.0)) : ndc.z;
    return texture(shadowMap, vec3(ts, clamp(depth, 0.0, 1.0)));
}
