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
    vec4 lightRadius[SK_MAX_LOCAL_LIGHTS]; // x: point light i's radius, y: spot light i's (metres; PCSS)
};

layout(binding = SK_SPOT_MAP_UNIT) uniform sampler2DArrayShadow spotMaps;
layout(binding = SK_POINT_MAP_UNIT) uniform samplerCubeArrayShadow pointMaps;
// The same maps' stored distances / range, for PCSS's blocker search.
layout(binding = SK_SPOT_DEPTH_UNIT) uniform sampler2DArray spotDepths;
layout(binding = SK_POINT_DEPTH_UNIT) uniform samplerCubeArray pointDepths;

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

// The spot map's texture coordinates of a world point.
vec2 spotUv(int i, vec3 ws) {
    const vec4 cs = spotClipFromWorld[i] * vec4(ws, 1.0);
    return cs.xy / cs.w * 0.5 + 0.5;
}

// Light `i`'s map (a point's cube, or a spot's layer) at the world point `q`: the comparison with
// a reference distance, and the stored distance itself (both in metres / range).
float localCompare(bool point, int i, vec3 q, float reference) {
    if (point) return texture(pointMaps, vec4(q - pointPositionRange[i].xyz, float(i)), reference);
    // The map spans every receiver the camera sees in the cone; only offsets step past its border.
    return texture(spotMaps, vec4(clamp(spotUv(i, q), 0.0, 1.0), float(i), reference));
}
float localStored(bool point, int i, vec3 q) {
    if (point) return texture(pointDepths, vec4(q - pointPositionRange[i].xyz, float(i))).r;
    return texture(spotDepths, vec3(clamp(spotUv(i, q), 0.0, 1.0), float(i))).r;
}

// PCSS (Fernando 2005) for a lamp of radius R, a sphere at wsLight, in a map that stores the
// distance from the light (every spot map and cube face alike).
//
// A receiver a distance d from the lamp sees it through a cone; a distance s from the lamp the
// cone's cross-section has radius R (d − s) / d, and a blocker there hides the lamp in the
// proportion of that disk it covers. The map is a perspective view from the lamp, so a point s
// from it at lateral offset ρ_s lies on the ray through the receiver's plane (⟂ the ray to the lamp)
// at ρ = ρ_s d / s: in that plane the cone of blockers s away is a disk of radius R (d − s) / s, the
// classic PCSS penumbra. The taps are world points of that plane, looked up by their own rays, so
// the kernel is right on any face, across cube faces and in any spot's projection without a
// Jacobian; each tap's reference is where its ray meets the receiver's tangent plane (the
// receiver-plane bias in world space) less the receiver's own bias.
//
// As for the sun (glsl/shadowkit_shadows.glsl's skPcss): the search counts a tap as a blocker only
// inside its cone (ρ ≤ R (d − s) / s), at radii growing linearly from the receiver's own texel;
// the filter is a Vogel disk; both take filterTaps taps, the filter stops at poissonRadiusTexels
// texels of the map at the receiver's distance and the search at half a texel a tap (as the sun's).
float localPcss(bool point, int i, vec3 ws, vec3 n, vec3 wsLight, float range, float radius, float texelPerMetre) {
    const vec4 r = biasedReceiver(ws, n, wsLight, texelPerMetre);
    const vec3 p = r.xyz;
    const vec3 toLight = wsLight - p;
    const float d = length(toLight);
    const float bias = d - r.w; // metres the biases take off the receiver's distance
    const vec3 axis = toLight / d;
    const vec3 e1 = normalize(cross(axis, abs(axis.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0)));
    const vec3 e2 = cross(axis, e1);
    const float widest = poissonRadiusTexels * d * texelPerMetre;
    // The reference distance of tap q: along its ray from the lamp to the receiver's tangent plane.
    const float planeDistance = dot(p - wsLight, n);
    const int taps = max(filterTaps, 1);
    const float angle = skPixelAngle();

    // 1. Blockers between the lamp's surface and the receiver whose cones hold the tap.
    const float search = min(d - radius, min(0.5 * float(max(filterTaps, 1)) * d * texelPerMetre, widest));
    float blockerDistance = 0.0, blockers = 0.0;
    vec2 direction = vec2(cos(angle), sin(angle));
    for (int k = 0; k < taps; ++k, direction = kSkGoldenTurn * direction) {
        const float rho = float(k) / float(taps) * search;
        const vec3 q = p + rho * (direction.x * e1 + direction.y * e2);
        const vec3 ray = normalize(q - wsLight);
        const float along = dot(ray, n) < -1e-4 ? planeDistance / dot(ray, n) : d;
        const float s = localStored(point, i, q) * range;
        if (s < along - bias && rho * s <= radius * (d - s)) {
            blockerDistance += s;
            blockers += 1.0;
        }
    }
    if (blockers == 0.0) return 1.0;

    // 2. Percentage-closer filtering over the cone's disk at the blockers' mean distance.
    const float s = blockerDistance / blockers;
    const float kernel = min(radius * (d - s) / max(s, 1e-4), widest);
    float lit = 0.0;
    direction = vec2(cos(angle), sin(angle));
    for (int k = 0; k < taps; ++k, direction = kSkGoldenTurn * direction) {
        const vec3 q = p + sqrt((float(k) + 0.5) / float(taps)) * kernel * (direction.x * e1 + direction.y * e2);
        const vec3 ray = normalize(q - wsLight);
        const float along = dot(ray, n) < -1e-4 ? planeDistance / dot(ray, n) : d;
        lit += localCompare(point, i, q, (along - bias) / range);
    }
    return lit / float(taps);
}

// 1 lit, 0 shadowed, by point light i's cube (layer i of the cube array).
float pointShadow(int i, vec3 ws, vec3 n) {
    if (filterKind == SK_FILTER_PCSS && lightRadius[i].x > 0.0)
        return localPcss(true, i, ws, n, pointPositionRange[i].xyz, pointPositionRange[i].w, lightRadius[i].x,
                         pointRadianceTexel[i].w);
    const vec4 r = biasedReceiver(ws, n, pointPositionRange[i].xyz, pointRadianceTexel[i].w);
    return localCompare(true, i, r.xyz, r.w / pointPositionRange[i].w);
}

float spotShadow(int i, vec3 ws, vec3 n) {
    if (filterKind == SK_FILTER_PCSS && lightRadius[i].y > 0.0)
        return localPcss(false, i, ws, n, spotPositionRange[i].xyz, spotPositionRange[i].w, lightRadius[i].y,
                         spotRadianceTexel[i].w);
    const vec4 r = biasedReceiver(ws, n, spotPositionRange[i].xyz, spotRadianceTexel[i].w);
    return localCompare(false, i, r.xyz, r.w / spotPositionRange[i].w);
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
