// Spot and point lights in the camera passes: their lighting and their shadow lookups
// (local_shadows.h). Included after frame.glsl. The C++ side is LocalLightsUniforms in
// uniforms.h. Maps store distance / range; the bias is applied here, in metres (a local
// light's texel grows with distance, so a constant in texels would be wrong everywhere else):
// the receiver moves along its normal by localNormalOffsetTexels texels' world size at its distance,
// and its distance shrinks by localSlopeBiasTexels × texel size × tan(angle to the light) plus
// localConstantBiasMetres — the slope-scaled bias in distance units.
layout(std140, binding = SK_LOCAL_LIGHTS_BINDING) uniform LocalLights {
    vec4 pointPositionRange[SK_MAX_LOCAL_LIGHTS];
    vec4 pointRadianceTexel[SK_MAX_LOCAL_LIGHTS]; // rgb, w: texel size per metre of distance
    vec4 spotPositionRange[SK_MAX_LOCAL_LIGHTS];
    vec4 spotAxisCosHalf[SK_MAX_LOCAL_LIGHTS];
    vec4 spotRadianceTexel[SK_MAX_LOCAL_LIGHTS];
    mat4 spotClipFromWorld[SK_MAX_LOCAL_LIGHTS];
    int pointCount;
    int spotCount;
    int evalLight; // eval pass: -1 the sun, else points first, then spots
    int sunLights;
    float localSlopeBiasTexels;
    float localNormalOffsetTexels;
    float localConstantBiasMetres;
    float localMapTexels; // texels per side of every spot map and cube face
};

layout(binding = SK_SPOT_MAP_UNIT) uniform sampler2DArrayShadow spotMaps;
layout(binding = SK_POINT_MAP_UNIT) uniform samplerCubeArrayShadow pointMaps;

// A local light's reach at a receiver: inside its range (and cone), facing it. Truth uses
// the same test (eval::litAt), so only the map decides where the two differ.
bool pointReaches(int i, vec3 ws, vec3 n) {
    const vec3 toLight = pointPositionRange[i].xyz - ws;
    return length(toLight) <= pointPositionRange[i].w && dot(n, toLight) > 0.0;
}
bool spotReaches(int i, vec3 ws, vec3 n) {
    const vec3 toLight = spotPositionRange[i].xyz - ws;
    const float d = length(toLight);
    return d <= spotPositionRange[i].w && dot(n, toLight) > 0.0 && dot(-toLight, spotAxisCosHalf[i].xyz) >= spotAxisCosHalf[i].w * d;
}

// The biased lookup point (moved along n) and its reference distance.
vec4 biasedReceiver(vec3 ws, vec3 n, vec3 wsLight, float texelPerMetre) {
    const float texel = distance(ws, wsLight) * texelPerMetre;
    const vec3 moved = ws + n * (localNormalOffsetTexels * texel);
    const vec3 toLight = wsLight - moved;
    const float d = length(toLight);
    const float cosAngle = clamp(dot(n, toLight) / max(d, 1e-6), 0.1, 1.0); // tan at most ~10
    const float tanAngle = sqrt(1.0 - cosAngle * cosAngle) / cosAngle;
    return vec4(moved, d - localSlopeBiasTexels * texel * tanAngle - localConstantBiasMetres);
}

// 1 lit, 0 shadowed, by point light i's cube (layer i of the cube array).
float pointShadow(int i, vec3 ws, vec3 n) {
    const vec4 r = biasedReceiver(ws, n, pointPositionRange[i].xyz, pointRadianceTexel[i].w);
    return texture(pointMaps, vec4(r.xyz - pointPositionRange[i].xyz, float(i)), r.w / pointPositionRange[i].w);
}

// The spot map's texture coordinates of a world point.
vec2 spotUv(int i, vec3 ws) {
    const vec4 cs = spotClipFromWorld[i] * vec4(ws, 1.0);
    return cs.xy / cs.w * 0.5 + 0.5;
}

float spotShadow(int i, vec3 ws, vec3 n) {
    const vec4 r = biasedReceiver(ws, n, spotPositionRange[i].xyz, spotRadianceTexel[i].w);
    // The map spans every receiver the camera sees in the cone; only the normal offset can
    // step past its border.
    const vec2 uv = clamp(spotUv(i, r.xyz), 0.0, 1.0);
    return texture(spotMaps, vec4(uv, float(i), r.w / spotPositionRange[i].w));
}

// The map's test of local light `light` (points first, then spots) alone, for the
// evaluation: the truth decides which pixels the light reaches (eval::underLight), as it
// decides which face the sun.
float localShadowTerm(int light, vec3 ws, vec3 n) {
    return light < pointCount ? pointShadow(light, ws, n) : spotShadow(light - pointCount, ws, n);
}

// Falloff to zero at the range: inverse square, windowed (smooth at the range).
float localAttenuation(float d, float range) {
    const float x = d / range;
    const float window = clamp(1.0 - x * x * x * x, 0.0, 1.0);
    return window * window / max(d * d, 0.25);
}

// Radiance all local lights bring to a receiver, shadows included.
vec3 localLighting(vec3 ws, vec3 n) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < pointCount; ++i) {
        if (!pointReaches(i, ws, n)) continue;
        const vec3 toLight = pointPositionRange[i].xyz - ws;
        const float d = length(toLight);
        sum += pointRadianceTexel[i].rgb * (dot(n, toLight) / d) * localAttenuation(d, pointPositionRange[i].w) *
               pointShadow(i, ws, n);
    }
    for (int i = 0; i < spotCount; ++i) {
        if (!spotReaches(i, ws, n)) continue;
        const vec3 toLight = spotPositionRange[i].xyz - ws;
        const float d = length(toLight);
        // Soft edge over the outer tenth of the cone's cosine range.
        const float cosAxis = dot(-toLight / d, spotAxisCosHalf[i].xyz), cosHalf = spotAxisCosHalf[i].w;
        const float edge = smoothstep(cosHalf, cosHalf + 0.1 * (1.0 - cosHalf), cosAxis);
        sum += spotRadianceTexel[i].rgb * (dot(n, toLight) / d) * localAttenuation(d, spotPositionRange[i].w) * edge *
               spotShadow(i, ws, n);
    }
    return sum;
}

// (sc, tc, |ma|) of a vector `d` on the cube face that direction `pick` selects (OpenGL 4.5
// §8.13, Table 8.19): linear in d for a fixed face, so it also maps steps.
vec3 cubeFaceCoords(vec3 pick, vec3 d) {
    const vec3 a = abs(pick);
    if (a.x >= a.y && a.x >= a.z) return pick.x >= 0.0 ? vec3(-d.z, -d.y, d.x) : vec3(d.z, -d.y, -d.x);
    if (a.y >= a.z) return pick.y >= 0.0 ? vec3(d.x, d.z, d.y) : vec3(d.x, -d.z, -d.y);
    return pick.z >= 0.0 ? vec3(d.x, -d.y, d.z) : vec3(-d.x, -d.y, -d.z);
}

// Texel coordinates of a receiver in local light `light`'s map (a cube face's own (s, t) for a
// point light), and their derivatives along two world steps (the pixel's screen derivatives
// of ws), by the chain rule through the divide: d(p / q) = (dp·q − p·dq) / q². Analytic, so a
// pixel quad straddling two cube faces still gets its own face's Jacobian.
vec2 localTexel(int light, vec3 ws, float size, vec3 dwsdx, vec3 dwsdy, out vec4 texelFromPixel) {
    vec3 p, dx, dy; // (x, y, divisor) of the point and of the two steps
    if (light >= pointCount) {
        const mat4 m = spotClipFromWorld[light - pointCount];
        p = (m * vec4(ws, 1.0)).xyw;
        dx = (m * vec4(dwsdx, 0.0)).xyw;
        dy = (m * vec4(dwsdy, 0.0)).xyw;
    } else {
        const vec3 d = ws - pointPositionRange[light].xyz;
        p = cubeFaceCoords(d, d);
        dx = cubeFaceCoords(d, dwsdx);
        dy = cubeFaceCoords(d, dwsdy);
    }
    const float scale = 0.5 * size; // NDC to texels
    texelFromPixel = scale * vec4((dx.xy * p.z - p.xy * dx.z), (dy.xy * p.z - p.xy * dy.z)) / (p.z * p.z);
    return (p.xy / p.z * 0.5 + 0.5) * size;
}
