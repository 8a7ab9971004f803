// The shadow-map lookup: depth comparison through the hardware (sampler2DArrayShadow,
// GL_LEQUAL), one array layer per map, cascades picked by view depth (Dimitrov 2007), with the
// receiver-side biases (normal offset, receiver-plane depth bias) and the filters of
// RenderSettings (hard, 2x2 hardware PCF, N x N PCF, rotated Poisson disk).
layout(binding = SK_SHADOW_MAP_UNIT) uniform sampler2DArrayShadow shadowMap;

float viewDepthOf(vec3 ws) { return dot(ws - wsEye.xyz, wsViewForward.xyz); }

// Where a receiver looks itself up: a simplified surface lies up to `lodError` metres off
// the true one, which the map holds, so it is moved that far towards the light — never
// behind its own surface (no self-shadowing), at most a fraction of a pixel from it (the
// level was chosen so). Exactly `ws` for full meshes (lodError 0).
vec3 receiverLookup(vec3 ws, float lodError) { return ws + wsTowardsLight.xyz * lodError; }

// The map serving this view depth: the first whose range ends beyond it.
int cascadeOf(float viewDepth) {
    for (int i = 0; i < mapCount - 1; ++i)
        if (viewDepth <= cascadeRange[i].y) return i;
    return mapCount - 1;
}

// Shadow clip coordinates are computed per fragment from the interpolated world position:
// exact under the perspective divide of warped maps, and the map is chosen per fragment.
vec4 shadowClip(int map, vec3 ws) { return shadowClipFromWorld[map] * vec4(ws, 1.0); }

// d(map coordinates)/d(world) along a world-space step, by the chain rule through the
// projective divide: d(P.xyz / P.w) = (dP.xyz − ndc · dP.w) / P.w with dP = M (step, 0).
// Screen derivatives of the world position come from uniform control flow (see callers),
// so this works inside the per-map branches where dFdx itself would be undefined.
vec3 mapStep(int map, vec4 cs, vec3 wsStep, vec3 ws) {
    const vec4 dP = shadowClipFromWorld[map] * vec4(wsStep, 0.0);
    vec3 d = (dP.xyz - cs.xyz / cs.w * dP.w) / cs.w;
    d.xy *= 0.5; // ndc -> texture coordinates
    if (linearLayout != 0) d.z = dot(shadowLinearDepthFromWorld[map].xyz, wsStep);
    return d;
}

// Hash-based rotation angle per pixel for the Poisson disk (blue-ish noise is not needed:
// the rotation only has to break up the fixed pattern).
float pixelAngle() { return 6.2831853 * fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453); }

const vec2 kPoisson[32] = vec2[](
    vec2(-0.975402, -0.0711386), vec2(-0.920347, -0.41142), vec2(-0.883908, 0.217872), vec2(-0.884518, 0.568041),
    vec2(-0.811945, 0.90521), vec2(-0.792474, -0.779962), vec2(-0.614856, 0.386578), vec2(-0.580859, -0.208777),
    vec2(-0.53795, 0.716666), vec2(-0.515427, 0.0899991), vec2(-0.454634, -0.707938), vec2(-0.420942, 0.991272),
    vec2(-0.261147, 0.588488), vec2(-0.211219, 0.114841), vec2(-0.146336, -0.259194), vec2(-0.139439, -0.888668),
    vec2(0.0116886, 0.326395), vec2(0.0380566, 0.625477), vec2(0.0625935, -0.50853), vec2(0.125584, 0.0469069),
    vec2(0.169469, -0.997253), vec2(0.320597, 0.291055), vec2(0.359172, -0.633717), vec2(0.435713, -0.250832),
    vec2(0.507797, -0.916562), vec2(0.545763, 0.730216), vec2(0.56859, 0.11655), vec2(0.743156, -0.505173),
    vec2(0.736442, -0.189734), vec2(0.843562, 0.357036), vec2(0.865413, -0.795735), vec2(0.872393, 0.750194));

float mapTerm(int map, vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    const float size = mapTexels;
    vec4 cs = shadowClip(map, ws);
    if (normalOffsetTexels > 0.0) {
        // Normal offset: move the receiver off its surface by K texels' world size. A texel's
        // world size is 1/size over the gradient of the texture coordinate; take the longer
        // of the two axes so the offset is enough in both.
        const vec3 gx = mapStep(map, cs, vec3(1, 0, 0), ws), gy = mapStep(map, cs, vec3(0, 1, 0), ws);
        const vec3 gz = mapStep(map, cs, vec3(0, 0, 1), ws);
        const float gradU = length(vec3(gx.x, gy.x, gz.x)), gradV = length(vec3(gx.y, gy.y, gz.y));
        ws += n * (normalOffsetTexels / (size * max(min(gradU, gradV), 1e-12)));
        cs = shadowClip(map, ws);
    }
    const vec3 ndc = cs.xyz / cs.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    // Outside the map nothing is known to occlude: lit. (Focused maps cover every
    // visible receiver, so this only happens off the focus body.)
    if (cs.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    // The reference depth in the map's layout. Depth clamp in the shadow pass stores
    // casters in front of the near plane at 0.
    float depth = linearLayout != 0 ? dot(shadowLinearDepthFromWorld[map], vec4(ws, 1.0)) : ndc.z;

    // Receiver plane: depth as a function of (u, v) on the receiver's plane, from the screen
    // derivatives of (u, v, depth) (Isidoro 2006): dz/duv = J⁻ᵀ (dz/dx, dz/dy).
    vec2 dDepthDuv = vec2(0.0);
    if (receiverPlane != 0) {
        const vec3 dx = mapStep(map, cs, dwsdx, ws), dy = mapStep(map, cs, dwsdy, ws);
        const float det = dx.x * dy.y - dx.y * dy.x;
        if (abs(det) > 1e-20) dDepthDuv = vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
    }
    const int taps = filterTaps;
    if (filterKind == SK_FILTER_GRID || filterKind == SK_FILTER_POISSON) {
        float sum = 0.0;
        const int count = filterKind == SK_FILTER_GRID ? taps * taps : taps;
        const float angle = pixelAngle();
        const mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
        for (int i = 0; i < count; ++i) {
            const vec2 offsetTexels = filterKind == SK_FILTER_GRID ? vec2(i % taps, i / taps) - 0.5 * float(taps - 1)
                                                                   : rotation * kPoisson[i] * poissonRadiusTexels;
            const vec2 tapUv = uv + offsetTexels / size;
            const float tapDepth = depth + dot(dDepthDuv, offsetTexels / size);
            sum += texture(shadowMap, vec4(tapUv, float(map), clamp(tapDepth, 0.0, 1.0)));
        }
        return sum / float(count);
    }
    if (filterKind == SK_FILTER_HARD && receiverPlane != 0) {
        // Hard test: compare at the texel centre the sample falls in, on the receiver plane.
        const vec2 centre = (floor(uv * size) + 0.5) / size;
        depth += dot(dDepthDuv, centre - uv);
    }
    // SK_FILTER_PCF2: the sampler's GL_LINEAR filter does the 2x2 PCF in hardware.
    return texture(shadowMap, vec4(uv, float(map), clamp(depth, 0.0, 1.0)));
}

// With a blend band, the end of each split overlaps the start of the next: there the two
// maps' terms are mixed linearly in view depth, hiding the seam. `dwsdx`, `dwsdy`: screen
// derivatives of ws, taken by the caller in uniform control flow.
float shadowTerm(vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    const float viewDepth = viewDepthOf(ws);
    const int map = cascadeOf(viewDepth);
    float term = mapTerm(map, ws, n, dwsdx, dwsdy);
    if (map + 1 < mapCount && viewDepth > cascadeRange[map + 1].x) {
        const float t = (viewDepth - cascadeRange[map + 1].x) / max(cascadeRange[map].y - cascadeRange[map + 1].x, 1e-6);
        term = mix(term, mapTerm(map + 1, ws, n, dwsdx, dwsdy), clamp(t, 0.0, 1.0));
    }
    return term;
}
