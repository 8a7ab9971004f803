// shadowkit_local_shadows.glsl: the receiver half of shadowkit's spot and point light shadows, for
// GLSL 4.50. Append it after shadowkit_shadows.glsl, whose filter kinds, per-pixel rotation and
// golden-angle turn it uses. The project's own renderer uses exactly this file (its local_lights.glsl
// passes its uniform block's fields to the functions below); it declares no uniforms.
//
// The maps (seed 003; core/local_lights.h: computeSpotShadowSetup, computePointShadowSetup) are
// perspective views from the light — one for a spot light, a point light's six 90° faces as one
// cube — and each texel stores the distance to the light, written per fragment (no slope bias: the
// lookup applies every bias in metres, as a local light's texel grows with its distance):
//   stored = distance(ws, light) · storedFromDistance.x + storedFromDistance.y
// with one mapping for all six faces of a cube (its lookups cross faces): core::storedFromDistance,
// distance / range, (1 / range, 0), as shadowkit's renderer stores it; or for a reversed-Z engine
// 1 − distance / range, (−1 / range, 1), compared with GL_GEQUAL: a negative scale turns the
// comparison with the mapping, nothing else.
//
// The engine names its maps, defined before this file (a lone map is layer 0 of a one-layer array):
//   #define SK_SPOT_MAPS     mySpotMaps     // sampler2DArrayShadow, GL_COMPARE_REF_TO_TEXTURE
//   #define SK_SPOT_DEPTHS   mySpotDepths   // the same texture as a sampler2DArray, no comparison,
//                                           // GL_NEAREST: PCSS's blocker search reads the distances
//   #define SK_POINT_MAPS    myPointMaps    // samplerCubeArrayShadow, as the spot maps
//   #define SK_POINT_DEPTHS  myPointDepths  // samplerCubeArray, as the spot depths
// skSpotShadow is compiled when SK_SPOT_MAPS is defined, skPointShadow when SK_POINT_MAPS is;
// without a kind's depths its SK_FILTER_PCSS takes the hard test.
#ifndef SK_SHADOWS_GLSL
#error "shadowkit_local_shadows.glsl: append it after shadowkit_shadows.glsl"
#endif

// One local light's map as its lookup needs it.
struct SkLocalLight {
    vec3 wsPosition;         // the light (ShadowSetup::wsLightPosition)
    float radius;            // metres: a sphere of light for PCSS's penumbrae; 0 a point, the hard test
    vec2 storedFromDistance; // stored = distance · x + y (above)
    float texelPerMetre;     // a texel's world size per metre of distance: core::texelSizePerMetre
    int layer;               // the spot map's array layer, or the point light's cube in the cube array
};

// The biases (core::LocalBias, core/local_lights.h: 1.5, 0.5 and 0.005 by default) and the filter.
struct SkLocalShadowOptions {
    float slopeBiasTexels;    // distance reduced by this × texel size × tan(angle to the light)
    float normalOffsetTexels; // receiver moved along its normal by this × texel size where the light grazes it
    float constantBiasMetres; // and its distance reduced by this
    int filterKind;           // SK_FILTER_PCSS (with a radius and the depths named): soft; else hard
    int filterTaps;           // PCSS's blocker-search and filter taps
    float poissonRadiusTexels; // PCSS's widest filter, in texels at the receiver's distance
};

// The biased lookup point and its reference distance in metres. A texel at distance d from the
// lamp spans t = d × texelPerMetre across the ray, and a plane whose normal n makes an angle θ with
// the ray spans t·tanθ of distance across it: the reference is shortened by slope × t × tanθ plus
// the constant. Up to tanθ = 3.2 (cos θ = 0.3, 72.5° from the normal); past it the distance taken
// would grow without bound and light whatever stands on the receiver, so the receiver is moved off
// its own surface instead, along n by normalOffset × t, faded in from cos θ = 0.3 to 0.15 — a plane
// through the lamp itself (cos θ ≈ 0) has no depth slope left to bias. A face the lamp meets more
// squarely is not moved: a move along its normal carries its lookup t·sinθ sideways and shifts every
// shadow cast on it — the ground round the trees under a lamp, whose shadows it pulled towards the
// lamp (docs/local-lights.md, "Bias in metres").
vec4 skLocalBiasedReceiver(SkLocalLight l, SkLocalShadowOptions o, vec3 ws, vec3 n) {
    const vec3 toLight = l.wsPosition - ws;
    const float texel = length(toLight) * l.texelPerMetre;
    const float cosAngle = dot(n, toLight) / max(length(toLight), 1e-6);
    const float grazing = 1.0 - smoothstep(0.15, 0.3, cosAngle);
    const vec3 moved = ws + n * (o.normalOffsetTexels * grazing * texel);
    const float clampedCos = clamp(cosAngle, 0.3, 1.0);
    const float tanAngle = sqrt(1.0 - clampedCos * clampedCos) / clampedCos;
    return vec4(moved, distance(moved, l.wsPosition) - o.slopeBiasTexels * texel * tanAngle - o.constantBiasMetres);
}

// The spot map's (u, v) of a world point, clamped: skSpotShadow looks up only receivers the map
// holds (skSpotMapHolds), so only a filter's offsets step past its border.
vec2 skSpotUv(mat4 textureFromWorld, vec3 ws) {
    const vec4 t = textureFromWorld * vec4(ws, 1.0);
    return clamp(t.xy / t.w, 0.0, 1.0);
}

// The light's map at world point q: compared with a reference distance (1 lit, 0 shadowed), and
// the distance it stores. A point light's cube is looked up along q's direction from the light;
// textureFromWorld is the spot map's (EngineShadowView::textureFromWorld), unused for a point light.
float skLocalCompare(bool point, SkLocalLight l, mat4 textureFromWorld, vec3 q, float referenceMetres) {
    const float reference = referenceMetres * l.storedFromDistance.x + l.storedFromDistance.y;
#ifdef SK_POINT_MAPS
    if (point) return texture(SK_POINT_MAPS, vec4(q - l.wsPosition, float(l.layer)), reference);
#endif
#ifdef SK_SPOT_MAPS
    if (!point) return texture(SK_SPOT_MAPS, vec4(skSpotUv(textureFromWorld, q), float(l.layer), reference));
#endif
    return 1.0;
}
float skLocalMetres(SkLocalLight l, float stored) {
    return (stored - l.storedFromDistance.y) / l.storedFromDistance.x;
}
float skLocalStoredMetres(bool point, SkLocalLight l, mat4 textureFromWorld, vec3 q) {
#ifdef SK_POINT_DEPTHS
    if (point) return skLocalMetres(l, texture(SK_POINT_DEPTHS, vec4(q - l.wsPosition, float(l.layer))).r);
#endif
#ifdef SK_SPOT_DEPTHS
    if (!point) return skLocalMetres(l, texture(SK_SPOT_DEPTHS, vec3(skSpotUv(textureFromWorld, q), float(l.layer))).r);
#endif
    return 3.0e38; // no depths named: nothing in front (skLocalShadow does not search then)
}
bool skLocalDepthsNamed(bool point) {
#ifdef SK_POINT_DEPTHS
    if (point) return true;
#endif
#ifdef SK_SPOT_DEPTHS
    if (!point) return true;
#endif
    return false;
}

// PCSS (Fernando 2005) for a lamp of radius R, a sphere at the light, in a map that stores the
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
// As for the sun (shadowkit_shadows.glsl's skPcss): the search counts a tap as a blocker only
// inside its cone (ρ ≤ R (d − s) / s), at radii growing linearly from the receiver's own texel;
// the filter is a Vogel disk; both take o.filterTaps taps, the filter stops at
// o.poissonRadiusTexels texels of the map at the receiver's distance and the search at half a
// texel a tap (as the sun's).
float skLocalPcss(bool point, SkLocalLight l, mat4 textureFromWorld, SkLocalShadowOptions o, vec3 ws, vec3 n) {
    const vec4 r = skLocalBiasedReceiver(l, o, ws, n);
    const vec3 p = r.xyz;
    const vec3 toLight = l.wsPosition - p;
    const float d = length(toLight);
    const float bias = d - r.w; // metres the biases take off the receiver's distance
    const vec3 axis = toLight / d;
    const vec3 e1 = normalize(cross(axis, abs(axis.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0)));
    const vec3 e2 = cross(axis, e1);
    const float widest = o.poissonRadiusTexels * d * l.texelPerMetre;
    // The reference distance of tap q: along its ray from the lamp to the receiver's tangent plane.
    const float planeDistance = dot(p - l.wsPosition, n);
    const int taps = max(o.filterTaps, 1);
    const float angle = skPixelAngle();

    // 1. Blockers between the lamp's surface and the receiver whose cones hold the tap.
    const float search = min(d - l.radius, min(0.5 * float(taps) * d * l.texelPerMetre, widest));
    float blockerDistance = 0.0, blockers = 0.0;
    vec2 direction = vec2(cos(angle), sin(angle));
    for (int k = 0; k < taps; ++k, direction = kSkGoldenTurn * direction) {
        const float rho = float(k) / float(taps) * search;
        const vec3 q = p + rho * (direction.x * e1 + direction.y * e2);
        const vec3 ray = normalize(q - l.wsPosition);
        const float along = dot(ray, n) < -1e-4 ? planeDistance / dot(ray, n) : d;
        const float s = skLocalStoredMetres(point, l, textureFromWorld, q);
        if (s < along - bias && rho * s <= l.radius * (d - s)) {
            blockerDistance += s;
            blockers += 1.0;
        }
    }
    if (blockers == 0.0) return 1.0;

    // 2. Percentage-closer filtering over the cone's disk at the blockers' mean distance.
    const float s = blockerDistance / blockers;
    const float kernel = min(l.radius * (d - s) / max(s, 1e-4), widest);
    float lit = 0.0;
    direction = vec2(cos(angle), sin(angle));
    for (int k = 0; k < taps; ++k, direction = kSkGoldenTurn * direction) {
        const vec3 q = p + sqrt((float(k) + 0.5) / float(taps)) * kernel * (direction.x * e1 + direction.y * e2);
        const vec3 ray = normalize(q - l.wsPosition);
        const float along = dot(ray, n) < -1e-4 ? planeDistance / dot(ray, n) : d;
        lit += skLocalCompare(point, l, textureFromWorld, q, along - bias);
    }
    return lit / float(taps);
}

// 1 lit, 0 shadowed: the hard test, or PCSS under a lamp of some radius.
float skLocalShadow(bool point, SkLocalLight l, mat4 textureFromWorld, SkLocalShadowOptions o, vec3 ws, vec3 n) {
    if (o.filterKind == SK_FILTER_PCSS && l.radius > 0.0 && skLocalDepthsNamed(point))
        return skLocalPcss(point, l, textureFromWorld, o, ws, n);
    const vec4 r = skLocalBiasedReceiver(l, o, ws, n);
    return skLocalCompare(point, l, textureFromWorld, r.xyz, r.w);
}

#ifdef SK_SPOT_MAPS
// Whether the spot map holds the receiver ws: in front of the light (w > 0) and inside the map's
// square, or within a texel past its edge (a receiver on the edge of what the map spans, moved by
// its bias, still reads the edge, as the lookup clamps it). A spot's map holds every receiver the
// camera sees in its cone, so one it does not hold the light does not reach; a point light's one
// map aimed at part of what the camera sees (core::computePointAimedMapSetup, holdsPartOfView)
// leaves out receivers the lamp does light, and those get no shadow from it — as its set-up says —
// rather than the clamped edge's, or behind the lamp (w < 0) a texel of the mirrored image.
bool skSpotMapHolds(mat4 textureFromWorld, vec3 ws) {
    const vec4 t = textureFromWorld * vec4(ws, 1.0);
    if (!(t.w > 0.0)) return false;
    const vec2 margin = 1.0 / vec2(textureSize(SK_SPOT_MAPS, 0).xy), uv = t.xy / t.w;
    return all(greaterThanEqual(uv, -margin)) && all(lessThanEqual(uv, 1.0 + margin));
}

// A spot light's shadow at a receiver ws with unit normal n facing the light (the caller decides
// what the cone and range reach: the map only says what is hidden; a receiver outside the map is
// lit, skSpotMapHolds). textureFromWorld: the spot's EngineShadowView::textureFromWorld, whose
// (x, y) / w is the map's (u, v). A point light's one map (SHADOWKIT_LIGHT_POINT_ONE_MAP,
// _AIMED_MAP) is looked up here too.
float skSpotShadow(SkLocalLight l, mat4 textureFromWorld, SkLocalShadowOptions o, vec3 ws, vec3 n) {
    if (!skSpotMapHolds(textureFromWorld, ws)) return 1.0;
    return skLocalShadow(false, l, textureFromWorld, o, ws, n);
}
#endif

#ifdef SK_POINT_MAPS
// A point light's shadow at a receiver ws with unit normal n facing the light, from its cube.
float skPointShadow(SkLocalLight l, SkLocalShadowOptions o, vec3 ws, vec3 n) {
    return skLocalShadow(true, l, mat4(1.0), o, ws, n);
}
#endif
