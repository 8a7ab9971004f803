// The hard shadow-map test through hardware depth comparison (sampler2DArrayShadow,
// GL_LEQUAL), one array layer per map; cascades picked by view depth (seed 002).
layout(binding = 0) uniform sampler2DArrayShadow shadowMap;

float viewDepthOf(vec3 ws) { return dot(ws - wsEye.xyz, wsViewForward.xyz); }

// The map serving this view depth: the first whose range ends beyond it.
int cascadeOf(float viewDepth) {
    const int maps = int(shadowParams.y);
    for (int i = 0; i < maps - 1; ++i)
        if (viewDepth <= cascadeRange[i].y) return i;
    return maps - 1;
}

// Shadow clip coordinates are computed per fragment from the interpolated world position:
// exact under the perspective divide of warped maps, and the map is chosen per fragment.
vec4 shadowClip(int map, vec3 ws) { return shadowClipFromWorld[map] * vec4(ws, 1.0); }

float mapTerm(int map, vec3 ws) {
    const vec4 cs = shadowClip(map, ws);
    const vec3 ndc = cs.xyz / cs.w;
    const vec2 ts = ndc.xy * 0.5 + 0.5;
    // Outside the map nothing is known to occlude: lit. (Focused maps cover every
    // visible receiver, so this only happens off the focus body.)
    if (cs.w <= 0.0 || any(lessThan(ts, vec2(0.0))) || any(greaterThan(ts, vec2(1.0)))) return 1.0;
    // The reference depth in the map's layout. Depth clamp in the shadow pass stores
    // casters in front of the near plane at 0.
    const float depth = shadowParams.z > 0.5 ? dot(shadowLinearDepthFromWorld[map], vec4(ws, 1.0)) : ndc.z;
    return texture(shadowMap, vec4(ts, float(map), clamp(depth, 0.0, 1.0)));
}

// With a blend band, the end of each split overlaps the start of the next: there the two
// maps' terms are mixed linearly in view depth, hiding the seam.
float shadowTerm(vec3 ws) {
    const float viewDepth = viewDepthOf(ws);
    const int map = cascadeOf(viewDepth);
    float term = mapTerm(map, ws);
    if (map + 1 < int(shadowParams.y) && viewDepth > cascadeRange[map + 1].x) {
        const float t = (viewDepth - cascadeRange[map + 1].x) / max(cascadeRange[map].y - cascadeRange[map + 1].x, 1e-6);
        term = mix(term, mapTerm(map + 1, ws), clamp(t, 0.0, 1.0));
    }
    return term;
}
