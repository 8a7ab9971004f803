// Spot and point lights in the camera passes: their lighting, with their shadows from the installed
// lookup (glsl/shadowkit_local_shadows.glsl) over the maps and uniforms local_light_maps.glsl
// declares; both come before this file.

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

// The installed lookup's view of this frame's lights and options.
SkLocalShadowOptions localShadowOptions() {
    return SkLocalShadowOptions(localSlopeBiasTexels, localNormalOffsetTexels, localConstantBiasMetres, filterKind,
                                filterTaps, poissonRadiusTexels);
}

// 1 lit, 0 shadowed, by point light i's cube (layer i of the cube array).
float pointShadow(int i, vec3 ws, vec3 n) {
    const float range = pointPositionRange[i].w;
    const SkLocalLight l = SkLocalLight(pointPositionRange[i].xyz, lightRadius[i].x, vec2(1.0 / range, 0.0),
                                        pointRadianceTexel[i].w, i);
    return skPointShadow(l, localShadowOptions(), ws, n);
}

float spotShadow(int i, vec3 ws, vec3 n) {
    const float range = spotPositionRange[i].w;
    const SkLocalLight l = SkLocalLight(spotPositionRange[i].xyz, lightRadius[i].y, vec2(1.0 / range, 0.0),
                                        spotRadianceTexel[i].w, i);
    return skSpotShadow(l, spotTextureFromWorld[i], localShadowOptions(), ws, n);
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
    vec3 p, dx, dy; // (x, y, divisor) of the point and of the two steps: (u, v) = xy / divisor
    if (light >= pointCount) {
        const mat4 m = spotTextureFromWorld[light - pointCount];
        p = (m * vec4(ws, 1.0)).xyw;
        dx = (m * vec4(dwsdx, 0.0)).xyw;
        dy = (m * vec4(dwsdy, 0.0)).xyw;
    } else { // a face's (sc, tc, |ma|) to (s, t) = ½ (sc, tc) / |ma| + ½, still linear in d
        const vec3 d = ws - pointPositionRange[light].xyz;
        const mat3 textureFromFace = mat3(0.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.5, 0.5, 1.0);
        p = textureFromFace * cubeFaceCoords(d, d);
        dx = textureFromFace * cubeFaceCoords(d, dwsdx);
        dy = textureFromFace * cubeFaceCoords(d, dwsdy);
    }
    texelFromPixel = size * vec4((dx.xy * p.z - p.xy * dx.z), (dy.xy * p.z - p.xy * dy.z)) / (p.z * p.z);
    return p.xy / p.z * size;
}
