// shadowkit_shadows.glsl: the receiver half of shadowkit's shadow maps, for GLSL 4.50 (and
// 4.30 with sampler2DArrayShadow). The project's own renderer uses exactly this file; an
// engine appends it to its fragment shader source after `#version` and its own declarations
// (GLSL has no #include of its own; concatenate, or use your engine's include mechanism).
// It declares no uniforms: everything comes in through the arguments and the accessors below.
//
// What it does, per fragment (see docs/engine-integration.md):
//   - the lookup of one map in a sampler2DArrayShadow layer (a lone 2-D map is layer 0 of a
//     one-layer array), with the comparison in the sampler (GL_TEXTURE_COMPARE_MODE
//     GL_COMPARE_REF_TO_TEXTURE; GL_LEQUAL, or GL_GEQUAL for reversed-Z maps with
//     SK_SHADOW_REVERSED_Z defined: see skStoredDepth);
//   - the reference depth in the map's layout: z / w of textureFromWorld (hyperbolic) or the
//     linear row linearDepthFromWorld (TSM's linear depth, Martin & Tan 2004, and LiSPSM's
//     per-fragment linear depth, Scherzer 2005 §4.2);
//   - the receiver-side biases: normal offset by a number of texels' world size and by a share
//     of the texel's footprint on the receiver's triangle, the offset guard (a receiver behind
//     another caster keeps its shadow where the offset would carry its lookup out), and
//     receiver-plane depth bias (Isidoro 2006) from the screen derivatives of the position;
//   - the filters: hard, 2 × 2 hardware PCF, N × N PCF, rotated Poisson disk, and PCSS (soft
//     shadows of a sun of a given angular size, its kernel on each map's local footprint);
//   - cascades: split selection by view depth (Dimitrov 2007) and blending across a band;
//   - virtual shadow maps: the clipmap level by the pixel's footprint, the page table's
//     indirection into the physical page atlas, every filter inside the page's guard band;
//   - partial occlusion by leaves: opacity layers beside fixed maps and virtual pages, with
//     SK_SHADOW_OPACITY defined and shadowkit_foliage_opacity.glsl appended after this file (that
//     file says what to name).
//
// Inputs, all from the core (output_conventions.h, shadowkit_c.h):
//   textureFromWorld       EngineShadowView::textureFromWorld / shadowkit_view.texture_from_world
//   linearDepthFromWorld   EngineShadowView::linearDepthFromWorld (linear layout only)
//   SkShadowOptions        map size, layout, BiasSettings (recommendedBias), FilterSettings
//   splits                 ShadowView::split, for cascades (view depth [start, end] per map)
// The screen derivatives dwsdx / dwsdy = dFdx / dFdy of the world position must be taken by
// the caller in uniform control flow (before any branch on shadowing).
//
// For cascades the caller names its own storage with three accessors, defined before this
// file (the arrays stay where they are: no copies of uniform arrays into locals):
//   #define SK_SHADOW_TEXTURE_FROM_WORLD(i)        myTextureFromWorld[i]
//   #define SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(i)   myLinearDepthFromWorld[i]
//   #define SK_SHADOW_SPLIT(i)                     mySplits[i].xy
// skCascadedShadow is compiled only when SK_SHADOW_SPLIT is defined.
//
// PCSS reads the stored depths as well as comparing them: name a sampler2DArray of the same
// texture (a sampler object with GL_TEXTURE_COMPARE_MODE GL_NONE, GL_NEAREST) before this file,
//   #define SK_SHADOW_DEPTHS                       myShadowDepths
// Without it SK_FILTER_PCSS takes the hard lookup.
//
// MSM reads the maps' prefiltered moments (z, z², z³, z⁴) of depth, in a sampler2DArray of RGBA32F
// with GL_LINEAR filtering laid out as the depth maps (layer per map; the engine computes and blurs
// them after its shadow pass), named before the file:
//   #define SK_SHADOW_MOMENTS                      myShadowMoments
// Without it SK_FILTER_MSM takes the hard lookup.
//
// For virtual shadow maps (core/virtual_clipmap.h, docs/virtual-shadow-maps.md) the levels'
// textureFromWorld and the page table's cell of each level's first page (core::pageTableCellOf
// of its ClipmapLevel's firstPageX, firstPageY: the table is addressed toroidally) come through
// two accessors, and skVirtualShadow is compiled when the first is defined:
//   #define SK_VIRTUAL_LEVEL_FROM_WORLD(i)         myLevelTextureFromWorld[i]
//   #define SK_VIRTUAL_LEVEL_TABLE_ORIGIN(i)       myLevelTableOrigin[i].xy

// Files appended after this one (shadowkit_foliage_opacity.glsl) check that it came first.
#define SK_SHADOWS_GLSL 1

#ifndef SK_FILTER_HARD
// Filter kinds: the values of shadowkit::core::ShadowFilter.
#define SK_FILTER_HARD 0    // one comparison (GL_NEAREST)
#define SK_FILTER_PCF2 1    // the sampler's GL_LINEAR: 2 × 2 PCF in hardware
#define SK_FILTER_GRID 2    // N × N comparisons one texel apart
#define SK_FILTER_POISSON 3 // N comparisons on a Poisson disk rotated per pixel
#define SK_FILTER_PCSS 4    // percentage-closer soft shadows: blocker search, then a penumbra-wide disk
#define SK_FILTER_MSM 5     // moment shadow maps: one filtered lookup of four moments of depth
#endif

// The receiver-plane reference's margin towards the light, in texels of the receiver's depth
// slope (skShadowMapIn): more than a rasteriser's sub-texel error, far less than a texel.
#ifndef SK_RECEIVER_PLANE_MARGIN
#define SK_RECEIVER_PLANE_MARGIN 0.015625
#endif
// The offset guard (skOffsetGuard), chosen on the corpus of public models, the public suites and
// the forests (docs/bias-and-filtering.md, "The offset guard"): a caster counts as another's, not
// the receiver's own surface, when it lies nearer the light than the receiver by more than
// SK_OFFSET_GUARD_SLOPE_TEXELS texels of the receiver's own depth slope; the guard looks only
// where the light grazes the receiver's triangle, |f·ℓ| below SK_OFFSET_GUARD_GRAZING, and where
// the offsets moved the lookup SK_OFFSET_GUARD_MOVED_TEXELS texels or more along u or v.
#ifndef SK_OFFSET_GUARD_SLOPE_TEXELS
#define SK_OFFSET_GUARD_SLOPE_TEXELS 8.0
#endif
#ifndef SK_OFFSET_GUARD_GRAZING
#define SK_OFFSET_GUARD_GRAZING 0.15
#endif
#ifndef SK_OFFSET_GUARD_MOVED_TEXELS
#define SK_OFFSET_GUARD_MOVED_TEXELS 0.25
#endif

struct SkShadowOptions {
    float mapTexels;          // texels per side of the map(s)
    bool linearDepth;         // the maps store dot(linearDepthFromWorld, (p, 1))
    float normalOffsetTexels; // BiasSettings::normalOffset: receiver moved along its normal
    bool receiverPlane;       // BiasSettings::receiverPlane
    int filterKind;           // SK_FILTER_*
    int filterTaps;           // N of the grid, Poisson and PCSS filters
    float poissonRadiusTexels; // Poisson: the disk's radius; PCSS: its widest kernel; in texels
    float lightTanHalfAngle;   // PCSS: tan of the sun's angular radius (0.53° across: 0.004625); 0: a point
    float normalOffsetFootprint; // BiasSettings::normalOffsetFootprint: receiver moved along its triangle's
                                 // normal by this × its texel's footprint across the light on that normal
    bool offsetGuard;            // BiasSettings::offsetGuard: a receiver behind a caster in its own texel
                                 // stays shadowed where the normal offsets carry its lookup across the map
};

// Reversed-Z maps (OutputConventions::reversedZ: the light's near side stored as 1, compared with
// GL_GEQUAL): define SK_SHADOW_REVERSED_Z before this file. The lookup's arithmetic takes depth as
// growing away from the light — PCSS's blocker distances, the receiver plane's margin, the offset
// guard's margin, the moments' order — so it works in d, the depth from the light's near side:
// where a map's matrices enter (skShadowMapIn, skFoliageTransmittanceIn) their depth rows become
// d's (skDepthFromLight), and where a map is compared or its depths read, d becomes what is stored
// (skStoredDepth; 1 − d, its own inverse). A GL_GEQUAL comparison of 1 − d against the stored
// 1 − d_map passes where d ≤ d_map: the lit test of the ordinary map. Without the define both are
// the identity. Moments (SK_SHADOW_MOMENTS) and opacity layers are the engine's own passes: they
// hold d's moments and d in either case.
#ifdef SK_SHADOW_REVERSED_Z
float skStoredDepth(float d) { return 1.0 - d; }
// textureFromWorld's depth row z becomes w − z, so z / w becomes 1 − z / w.
mat4 skDepthFromLight(mat4 textureFromWorld) {
    for (int c = 0; c < 4; ++c) textureFromWorld[c].z = textureFromWorld[c].w - textureFromWorld[c].z;
    return textureFromWorld;
}
vec4 skDepthFromLight(vec4 linearDepthFromWorld) { return vec4(0.0, 0.0, 0.0, 1.0) - linearDepthFromWorld; }
#else
float skStoredDepth(float d) { return d; }
mat4 skDepthFromLight(mat4 textureFromWorld) { return textureFromWorld; }
vec4 skDepthFromLight(vec4 linearDepthFromWorld) { return linearDepthFromWorld; }
#endif

// (u, v, depth) of a world point: textureFromWorld's xy / w and the reference depth.
vec3 skShadowCoordinates(mat4 textureFromWorld, vec4 linearDepthFromWorld, bool linearDepth, vec3 ws, out vec4 t) {
    t = textureFromWorld * vec4(ws, 1.0);
    return vec3(t.xy / t.w, linearDepth ? dot(linearDepthFromWorld, vec4(ws, 1.0)) : t.z / t.w);
}

// d(u, v, depth)/d(world) along a world-space step, by the chain rule through the projective
// divide: d(T.xyz / T.w) = (dT.xyz − (T.xyz / T.w) dT.w) / T.w with dT = M (step, 0). Takes the
// caller's derivatives, so it works inside the per-map branches where dFdx would be undefined.
vec3 skShadowStep(mat4 textureFromWorld, vec4 linearDepthFromWorld, bool linearDepth, vec4 t, vec3 wsStep) {
    const vec4 dT = textureFromWorld * vec4(wsStep, 0.0);
    vec3 d = (dT.xyz - t.xyz / t.w * dT.w) / t.w;
    if (linearDepth) d.z = dot(linearDepthFromWorld.xyz, wsStep);
    return d;
}

// The map's gradients at a receiver, ∇u, ∇v and ∇depth in world space: the columns of the
// result (the rows of the Jacobian J of (u, v, depth)), from skShadowStep along the world axes.
mat3 skMapGradients(mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec4 t) {
    const vec3 sx = skShadowStep(textureFromWorld, linearDepthFromWorld, o.linearDepth, t, vec3(1, 0, 0));
    const vec3 sy = skShadowStep(textureFromWorld, linearDepthFromWorld, o.linearDepth, t, vec3(0, 1, 0));
    const vec3 sz = skShadowStep(textureFromWorld, linearDepthFromWorld, o.linearDepth, t, vec3(0, 0, 1));
    return mat3(vec3(sx.x, sy.x, sz.x), vec3(sx.y, sy.y, sz.y), vec3(sx.z, sy.z, sz.z));
}

// How far a receiver at t (skShadowCoordinates' t) moves before the lookup: BiasSettings' two
// normal offsets, in world units. `n` is its unit (shading) normal, `dwsdx` and `dwsdy` two steps
// across its drawn triangle (the screen derivatives of its position).
//  - normalOffsetTexels K: K texels' world size along n. A texel's world size is 1 / mapTexels
//    over the gradient of the texture coordinate; the shorter gradient (the longer texel axis)
//    makes the offset enough along both — whatever the receiver's slope, so a face turned to the
//    light moves as far as one along it.
//  - normalOffsetFootprint k: k (|a_u·f| + |a_v·f|) along f, the drawn triangle's own normal on
//    the light's side, a_u and a_v the world steps of one texel in u and in v at constant depth (across
//    the light). The texel a receiver reads holds its triangle's depth at the texel's centre, up
//    to half a step in u and in v away; along the light that plane lies |s·f| / (f·l) nearer than
//    the receiver after a step s, and a move δ along f puts the receiver δ / (f·l) nearer along
//    the light. So δ = ½ (|a_u·f| + |a_v·f|) clears its own plane anywhere in the texel (k = ½;
//    the slope-scaled offset covers the rasteriser's rounding), and δ = 0 for a face turned to
//    the light where the depth runs along it (orthographic maps, the linear layout): its shadows
//    do not move. The triangle's plane, not the shading normal's, is what the texel holds: on a
//    curved, coarsely tessellated surface the two differ by the facets' angle.
//    With J the rows ∇u, ∇v, ∇depth, the steps are J⁻¹'s first two columns over mapTexels:
//    a_u = (∇v × ∇depth) / (det J · mapTexels), a_v = (∇depth × ∇u) / (det J · mapTexels).
//    `g` is skMapGradients at the receiver (the overload below takes it from t), passed in so a
//    caller that needs the gradients again (the offset guard) computes them once.
vec3 skNormalOffset(mat3 g, SkShadowOptions o, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    const vec3 gradU = g[0], gradV = g[1], gradDepth = g[2];
    vec3 offset = vec3(0.0);
    if (o.normalOffsetTexels > 0.0)
        offset += n * (o.normalOffsetTexels / (o.mapTexels * max(min(length(gradU), length(gradV)), 1e-12)));
    if (o.normalOffsetFootprint > 0.0) {
        const vec3 stepU = cross(gradV, gradDepth), stepV = cross(gradDepth, gradU); // × det J
        const float signedDet = dot(gradU, stepU), det = abs(signedDet);
        // The triangle's normal on the side the light comes from: (u, v) hold along the light's
        // rays, ∇u × ∇v, along which the depth grows (its dot with ∇depth is det J) away from the
        // light, whatever the warp. Not the shading normal's side: a file whose normals point
        // into a face (a cube exported with its sides' normals along y) would move its lit
        // receivers into their own surface.
        vec3 face = cross(dwsdx, dwsdy);
        face = dot(face, face) > 0.0 ? normalize(face) : n; // a pixel seeing its triangle edge-on: n
        if (dot(face, cross(gradU, gradV)) * signedDet > 0.0) face = -face;
        // A map whose depth does not vary across the receiver's point (det 0) has no texel there.
        if (det > 0.0)
            offset += face * (o.normalOffsetFootprint * (abs(dot(stepU, face)) + abs(dot(stepV, face))) /
                              (det * o.mapTexels));
    }
    return offset;
}

vec3 skNormalOffset(mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec4 t, vec3 n, vec3 dwsdx,
                    vec3 dwsdy) {
    return skNormalOffset(skMapGradients(textureFromWorld, linearDepthFromWorld, o, t), o, n, dwsdx, dwsdy);
}

// A rotation angle per pixel for the Poisson disk: it only has to break up the fixed pattern.
float skPixelAngle() { return 6.2831853 * fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453); }

const vec2 kSkPoisson[32] = vec2[](
    vec2(-0.975402, -0.0711386), vec2(-0.920347, -0.41142), vec2(-0.883908, 0.217872), vec2(-0.884518, 0.568041),
    vec2(-0.811945, 0.90521), vec2(-0.792474, -0.779962), vec2(-0.614856, 0.386578), vec2(-0.580859, -0.208777),
    vec2(-0.53795, 0.716666), vec2(-0.515427, 0.0899991), vec2(-0.454634, -0.707938), vec2(-0.420942, 0.991272),
    vec2(-0.261147, 0.588488), vec2(-0.211219, 0.114841), vec2(-0.146336, -0.259194), vec2(-0.139439, -0.888668),
    vec2(0.0116886, 0.326395), vec2(0.0380566, 0.625477), vec2(0.0625935, -0.50853), vec2(0.125584, 0.0469069),
    vec2(0.169469, -0.997253), vec2(0.320597, 0.291055), vec2(0.359172, -0.633717), vec2(0.435713, -0.250832),
    vec2(0.507797, -0.916562), vec2(0.545763, 0.730216), vec2(0.56859, 0.11655), vec2(0.743156, -0.505173),
    vec2(0.736442, -0.189734), vec2(0.843562, 0.357036), vec2(0.865413, -0.795735), vec2(0.872393, 0.750194));

// The golden angle, 2.39996 rad, as a rotation: tap i + 1 of a Vogel disk is tap i turned by it
// (PCSS's filter taps here and the lamps' in the renderer's local_lights.glsl).
const mat2 kSkGoldenTurn = mat2(-0.7373688, 0.6754903, -0.6754903, -0.7373688);

// The sun's disk at a receiver as a map sees it (skPcss's comment, below, has the geometry): uvFromDisk
// takes metres in the plane ⟂ ℓ to (u, v), depthPerMetre is the depth's fall per metre towards
// the light, metresPerTexel a texel's size along the disk's longer axis in the map. False for a
// degenerate map (no footprint, or depth not changing towards the light).
bool skSunDiskInMap(mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec4 t, out mat2 uvFromDisk,
                    out float depthPerMetre, out float metresPerTexel) {
    const mat3 g = skMapGradients(textureFromWorld, linearDepthFromWorld, o, t);
    const vec3 gradU = g[0], gradV = g[1], gradDepth = g[2];
    vec3 towardsLight = cross(gradU, gradV);
    depthPerMetre = dot(gradDepth, towardsLight);
    uvFromDisk = mat2(0.0);
    metresPerTexel = 0.0;
    if (!(abs(depthPerMetre) > 1e-30 * length(towardsLight))) return false;
    towardsLight *= -sign(depthPerMetre) / length(towardsLight); // depth falls towards the light
    depthPerMetre = -dot(gradDepth, towardsLight);

    // The ellipse: (u, v) per metre along an orthonormal basis of the plane ⟂ ℓ; its longer axis
    // is uvFromDisk's larger singular value.
    const vec3 e1 = normalize(cross(towardsLight, abs(towardsLight.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0)));
    const vec3 e2 = cross(towardsLight, e1);
    uvFromDisk = mat2(dot(gradU, e1), dot(gradV, e1), dot(gradU, e2), dot(gradV, e2));
    const float a = dot(uvFromDisk[0], uvFromDisk[0]), b = dot(uvFromDisk[0], uvFromDisk[1]);
    const float c = dot(uvFromDisk[1], uvFromDisk[1]);
    const float uvPerMetre = sqrt(0.5 * (a + c) + sqrt(0.25 * (a - c) * (a - c) + b * b));
    metresPerTexel = 1.0 / (o.mapTexels * max(uvPerMetre, 1e-30));
    return true;
}

#ifdef SK_SHADOW_DEPTHS
// Percentage-closer soft shadows (Fernando 2005), the kernel on the map's local footprint.
//
// The sun is a disk of angular radius α. A receiver sees it through a cone of half-angle α
// around ℓ, the direction towards the light; a distance Δ towards the light the cone's
// cross-section is a disk of radius Δ·tan α, and blockers there hide the sun in the proportion
// of that disk they cover. So for blockers at one distance the lit fraction is percentage-closer
// filtering over that disk, and Fernando's two steps find Δ (the blockers' mean distance, from a
// search over the widest disk that can matter) and then filter.
//
// The disk lies in the world, perpendicular to ℓ. The map's (u, v) is a projective function of
// the world, so in the map the disk is an ellipse whose axes are the local Jacobian d(u, v)/d(world)
// restricted to that plane: for warped maps (PSM, LiSPSM, TSM) it changes over the map, and a
// kernel of so many texels everywhere would be wrong by the warp's ratio. ℓ is the direction in
// which (u, v) stays put, ∇u × ∇v. Along it every sun map keeps its footprint — PSM's too, whose
// sun may be a point light in post-perspective space: a (u, v) = (N_u, N_v) / w constant along ℓ
// for every receiver forces ∂w/∂ℓ = 0 — so the ellipse at the receiver is the ellipse at the
// blocker, and depth is linear along it: Δ = (d_receiver − d_blocker) / |∂d/∂ℓ|.
//
// The search counts a tap as a blocker only where its depth puts it inside the receiver's cone
// (ρ ≤ Δ·tan α, ρ the tap's distance off the axis in metres): a caster the search reaches but that
// hides none of the sun does not pull the mean. A blocker's cone is as narrow as it is near, so
// the search's taps lie at radii growing linearly from the axis itself (dense where the near
// blockers must be found: the first tap is the receiver's own texel), not uniformly in area. The
// filter's taps are a Vogel disk (golden-angle spiral, uniform in area for any count), as the sun
// is. Both turn per pixel and take o.filterTaps taps; the filter is capped at o.poissonRadiusTexels
// texels along the ellipse's longer axis (a virtual page's guard band holds that), the search at
// half a texel a tap (8 texels for 16): a far blocker is found near the axis as well as at its
// cone's rim, and taps spread wider than that missed contact shadows (docs/soft-shadows.md).
// `t`, `uv`, `depth`: the receiver's coordinates after the normal offset; dDepthDuv its plane.
float skPcss(sampler2DArrayShadow maps, int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o,
             vec4 atlasFromMap, vec4 t, vec2 uv, float depth, vec2 dDepthDuv) {
    mat2 uvFromDisk;
    float depthPerMetre, metresPerTexel;
    // Degenerate maps (no footprint, or depth not changing towards the light): the hard lookup.
    if (!skSunDiskInMap(textureFromWorld, linearDepthFromWorld, o, t, uvFromDisk, depthPerMetre, metresPerTexel))
        return texture(maps, vec4(uv * atlasFromMap.xy + atlasFromMap.zw, float(layer), skStoredDepth(clamp(depth, 0.0, 1.0))));
    const float widestMetres = o.poissonRadiusTexels * metresPerTexel;

    // Vogel disk: tap i at radius sqrt((i + ½) / N), each turned by the golden angle from the last.
    const float angle = skPixelAngle();
    const int taps = max(o.filterTaps, 1);

    // 1. Blockers anywhere up to the map's near plane (depth 0) that the cone can reach, the taps
    // half a texel apart along their spiral's radius at most.
    const float searchMetres = min(depth / depthPerMetre * o.lightTanHalfAngle,
                                   min(0.5 * float(taps) * metresPerTexel, widestMetres));
    float blockerMetres = 0.0, blockers = 0.0;
    vec2 direction = vec2(cos(angle), sin(angle));
    for (int i = 0; i < taps; ++i, direction = kSkGoldenTurn * direction) {
        const float rho = float(i) / float(taps) * searchMetres;
        const vec2 offset = uvFromDisk * (direction * rho);
        const float stored = skStoredDepth(texture(SK_SHADOW_DEPTHS, vec3((uv + offset) * atlasFromMap.xy + atlasFromMap.zw, float(layer))).r);
        // The comparison's own test (a blocker where reference > stored), in metres towards the light.
        const float metres = (depth + dot(dDepthDuv, offset) - stored) / depthPerMetre;
        if (metres > 0.0 && metres * o.lightTanHalfAngle >= rho) {
            blockerMetres += metres;
            blockers += 1.0;
        }
    }
    if (blockers == 0.0) return 1.0;

    // 2. Percentage-closer filtering over the cone's disk at the blockers' mean distance.
    const float filterMetres = min(blockerMetres / blockers * o.lightTanHalfAngle, widestMetres);
    float lit = 0.0;
    direction = vec2(cos(angle), sin(angle));
    for (int i = 0; i < taps; ++i, direction = kSkGoldenTurn * direction) {
        const vec2 offset = uvFromDisk * (direction * (sqrt((float(i) + 0.5) / float(taps)) * filterMetres));
        const float reference = clamp(depth + dot(dDepthDuv, offset), 0.0, 1.0);
        lit += texture(maps, vec4((uv + offset) * atlasFromMap.xy + atlasFromMap.zw, float(layer), skStoredDepth(reference)));
    }
    return lit / float(taps);
}
#endif

#ifdef SK_SHADOW_MOMENTS
// Moment shadow maps (Peters & Klein 2015), the Hamburger 4MSM bound. `b` holds the filtered
// moments (E z, E z², E z³, E z⁴) of the stored depths over the lookup's footprint; the lit
// fraction is the share of that depth distribution at or behind the receiver's depth zf. Of all
// distributions with these four moments, the one that puts the most mass in front of zf has three
// support points, zf and two more, z2 ≤ z3: the roots of the polynomial c1 + c2 z + c3 z² whose
// coefficients solve the Hankel system [1 b1 b2; b1 b2 b3; b2 b3 b4] c = (1, zf, zf²) (here by
// LDLᵀ); the mass in front of zf then follows from the two roots (the "sharpest lower bound" on
// the shadow of 64 bits of moments). Its failure is light bleeding: a receiver behind two stacked
// blockers can come out partly lit. The moments are first pulled a little towards those of the
// uniform distribution on [0, 1], (1/2, 1/3, 1/4, 1/5) — a valid moment vector, so the mix is one
// too — which keeps the system positive definite where one depth fills the footprint.
//
// The bound leaks: under a lone blocker it leaves some 3 % of light (81 % of the umbra pixels of
// `perpendicular` above 0.01), so the lit fraction is rescaled, (lit − β) / (1 − β) clamped —
// light-bleeding reduction, β = SK_MSM_BLEEDING_REDUCTION. Chosen against the sun disk's truth on
// `perpendicular`, `paper` and `aerial` (TSM 2048², blur 2): soft_mae 0.0193 / 0.0083 / 0.0223
// with β = 0, 0.0069 / 0.0082 / 0.0198 with 0.05, 0.0057 / 0.0082 / 0.0186 with 0.1 and
// 0.0052 / 0.0083 / 0.0171 with 0.2, whose penumbrae harden (penumbra_mae 0.077 → 0.095 → 0.116).
#ifndef SK_MSM_BLEEDING_REDUCTION
#define SK_MSM_BLEEDING_REDUCTION 0.1
#endif
float skMomentLit(vec4 b, float zf) {
    b = mix(b, vec4(1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0, 1.0 / 5.0), 3e-5);
    const float d2 = b.y - b.x * b.x; // the LDLᵀ factors: D = diag(1, d2, d3), L's l21 = b1, l31 = b2, l32
    const float l32 = (b.z - b.x * b.y) / d2;
    const float d3 = b.w - b.y * b.y - l32 * l32 * d2;
    const float y2 = zf - b.x, y3 = zf * zf - b.y - l32 * y2; // L y = (1, zf, zf²)
    const float c3 = y3 / d3, c2 = y2 / d2 - l32 * c3, c1 = 1.0 - b.x * c2 - b.y * c3; // D Lᵀ c = y
    const float p = c2 / c3, q = c1 / c3;
    const float r = sqrt(max(0.25 * p * p - q, 0.0));
    const float z2 = -0.5 * p - r, z3 = -0.5 * p + r;
    float shadow = 0.0; // zf in front of both: nothing can be in front of it
    if (zf > z3)
        shadow = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
    else if (zf > z2)
        shadow = (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
    const float lit = 1.0 - clamp(shadow, 0.0, 1.0);
    return clamp((lit - SK_MSM_BLEEDING_REDUCTION) / (1.0 - SK_MSM_BLEEDING_REDUCTION), 0.0, 1.0);
}
#endif

#ifdef SK_SHADOW_OPACITY
// When the leaves' lookup applies (shadowkit_foliage_opacity.glsl names the samplers to define).
#ifndef SK_SHADOW_OPACITY_ENABLED
#define SK_SHADOW_OPACITY_ENABLED true
#endif
// The share of the sun the leaves let through to a receiver: shadowkit_foliage_opacity.glsl, which
// an engine with opacity layers appends after this file. The first for a map filling a layer, the
// second for one stored at atlasFromMap (a virtual page, as skShadowMapIn's).
float skFoliageTransmittance(int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec3 ws);
float skFoliageTransmittanceIn(int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o,
                               vec4 atlasFromMap, vec3 ws);
#endif

// The receiver's depth slope in the map, d depth / d(u, v) on its plane, from the screen
// derivatives of (u, v, depth): J⁻ᵀ (dz/dx, dz/dy); 0 where its plane is edge-on to the map.
vec2 skReceiverDepthSlope(mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec4 t, vec3 dwsdx, vec3 dwsdy) {
    const vec3 dx = skShadowStep(textureFromWorld, linearDepthFromWorld, o.linearDepth, t, dwsdx);
    const vec3 dy = skShadowStep(textureFromWorld, linearDepthFromWorld, o.linearDepth, t, dwsdy);
    const float det = dx.x * dy.y - dx.y * dy.x;
    return abs(det) > 1e-20 ? vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det : vec2(0.0);
}

// The offset guard (BiasSettings::offsetGuard): 0 where the receiver, at `before` (its (u, v,
// depth) before the normal offsets, t its homogeneous coordinates there), lies behind a caster
// in its own texel by more than SK_OFFSET_GUARD_SLOPE_TEXELS texels of its own depth slope — more
// than its own surface reaches across a few texels, so another caster's — where the light grazes
// its triangle and the offsets moved its lookup to `uvAfter`, SK_OFFSET_GUARD_MOVED_TEXELS
// texels or more along u or v; 1 elsewhere.
// The offsets exist against the receiver's own surface, and move it across the light as well:
// where the light grazes (a sphere's rim, N·L 0.02–0.1) by up to a quarter of a stretched
// texel's extent, which carried the rims of spheres standing in walled cells out of the walls'
// shadows (docs/reliability.md, "Models we did not make"). There a distant caster's shadow edge
// is where the receiver itself looks it up. Elsewhere the offset lookup's edges are the better
// ones: on the forest's ground, which the offsets move a quarter texel too, the guard drew 353
// pixels of false shadow along the trees' shadows on `perpendicular` for 26 it mended (the four
// cascades); and where the lookup barely moved the two differ only in the texel an edge falls in.
float skOffsetGuard(sampler2DArrayShadow maps, int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld,
                    SkShadowOptions o, vec4 atlasFromMap, vec4 t, mat3 g, vec3 before, vec2 uvAfter, vec3 dwsdx,
                    vec3 dwsdy) {
    const vec2 moved = abs(uvAfter - before.xy) * o.mapTexels;
    if (max(moved.x, moved.y) < SK_OFFSET_GUARD_MOVED_TEXELS) return 1.0;
    if (t.w <= 0.0 || any(lessThan(before.xy, vec2(0.0))) || any(greaterThan(before.xy, vec2(1.0)))) return 1.0;
    // Grazing: the drawn triangle's normal f against ℓ, the direction along which (u, v) hold,
    // ∇u × ∇v (whatever the warp); g is skMapGradients at t.
    const vec3 light = cross(g[0], g[1]), face = cross(dwsdx, dwsdy);
    if (!(abs(dot(face, light)) < SK_OFFSET_GUARD_GRAZING * length(face) * length(light))) return 1.0;
    const vec2 slope = skReceiverDepthSlope(textureFromWorld, linearDepthFromWorld, o, t, dwsdx, dwsdy);
    const float margin = SK_OFFSET_GUARD_SLOPE_TEXELS * (abs(slope.x) + abs(slope.y)) / o.mapTexels;
    // The one texel the receiver lies in, whatever the sampler's filter: a bilinear compare would
    // spread a distant caster's shadow half a texel past its edge. textureGather's four are the
    // bilinear footprint's, (i0, j1) (i1, j1) (i1, j0) (i0, j0); the point lies in i1 where the
    // footprint's fraction along u is ½ or more, in j1 where along v.
    const vec2 at = before.xy * atlasFromMap.xy + atlasFromMap.zw;
    const vec4 four = textureGather(maps, vec3(at, float(layer)), skStoredDepth(clamp(before.z - margin, 0.0, 1.0)));
    const vec2 f = fract(at * vec2(textureSize(maps, 0).xy) - 0.5);
    return f.y >= 0.5 ? (f.x >= 0.5 ? four.y : four.x) : (f.x >= 0.5 ? four.z : four.w);
}

// The lit fraction (0 shadowed .. 1 lit) of a receiver at `ws` with unit normal `n` in one map
// stored in layer `layer` of `maps` at (u, v) · atlasFromMap.xy + atlasFromMap.zw: the whole layer
// (1, 1, 0, 0), or a virtual map's page in the page atlas, whose guard band holds every tap.
float skShadowMapIn(sampler2DArrayShadow maps, int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld,
                    SkShadowOptions o, vec4 atlasFromMap, vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    textureFromWorld = skDepthFromLight(textureFromWorld);
    linearDepthFromWorld = skDepthFromLight(linearDepthFromWorld);
    vec4 t;
    vec3 uvz = skShadowCoordinates(textureFromWorld, linearDepthFromWorld, o.linearDepth, ws, t);
    float guard = 1.0; // skOffsetGuard's, for the hard test and the 2 × 2 PCF
    if (o.normalOffsetTexels > 0.0 || o.normalOffsetFootprint > 0.0) {
        const vec4 tBefore = t;
        const vec3 before = uvz;
        const mat3 g = skMapGradients(textureFromWorld, linearDepthFromWorld, o, t);
        ws += skNormalOffset(g, o, n, dwsdx, dwsdy);
        uvz = skShadowCoordinates(textureFromWorld, linearDepthFromWorld, o.linearDepth, ws, t);
        if (o.offsetGuard)
            guard = skOffsetGuard(maps, layer, textureFromWorld, linearDepthFromWorld, o, atlasFromMap, tBefore, g,
                                  before, uvz.xy, dwsdx, dwsdy);
    }
    // Outside the map nothing is known to occlude: lit. (Focused maps cover every visible
    // receiver, so this only happens off the focus body.)
    if (t.w <= 0.0 || any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0)))) return 1.0;
    const vec2 uv = uvz.xy;
    float depth = uvz.z;

    // Receiver plane: depth as a function of (u, v) on the receiver's plane.
    vec2 dDepthDuv = vec2(0.0);
    if (o.receiverPlane) {
        dDepthDuv = skReceiverDepthSlope(textureFromWorld, linearDepthFromWorld, o, t, dwsdx, dwsdy);
        // The map holds the rasteriser's depth plane of each caster, not the exact one: vertices
        // snapped to its sub-pixel grid shift and tilt that plane by a fraction of a texel times
        // its depth slope. Slope-scaled offset covers that; with the reference on the receiver's
        // exact plane and no slope-scaled offset nothing did: a PSM map's ground acned on 95 % of
        // its pixels on an NVIDIA H200 (4 units of constant offset; a slope-scaled 0.004 was
        // enough), and with no offset at all 44–83 % under PSM, LiSPSM and TSM on llvmpipe. So
        // the reference keeps a margin of SK_RECEIVER_PLANE_MARGIN texels of the receiver's own
        // slope towards the light: 1/64 clears both and moves PSM's `pcf:3` forest figures by at
        // most 0.03 points (1/16 moved `paper` by 0.38, leaking light at contacts).
        depth -= SK_RECEIVER_PLANE_MARGIN * (abs(dDepthDuv.x) + abs(dDepthDuv.y)) / o.mapTexels;
    }
#ifdef SK_SHADOW_MOMENTS
    if (o.filterKind == SK_FILTER_MSM)
        return skMomentLit(texture(SK_SHADOW_MOMENTS, vec3(uv * atlasFromMap.xy + atlasFromMap.zw, float(layer))),
                           clamp(depth, 0.0, 1.0));
#endif
#ifdef SK_SHADOW_DEPTHS
    if (o.filterKind == SK_FILTER_PCSS && o.lightTanHalfAngle > 0.0)
        return skPcss(maps, layer, textureFromWorld, linearDepthFromWorld, o, atlasFromMap, t, uv, depth, dDepthDuv);
#endif
    const float size = o.mapTexels;
    const int taps = o.filterTaps;
    if (o.filterKind == SK_FILTER_GRID || o.filterKind == SK_FILTER_POISSON) {
        float sum = 0.0;
        const int count = o.filterKind == SK_FILTER_GRID ? taps * taps : taps;
        const float angle = skPixelAngle();
        const mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
        for (int i = 0; i < count; ++i) {
            const vec2 offsetTexels = o.filterKind == SK_FILTER_GRID ? vec2(i % taps, i / taps) - 0.5 * float(taps - 1)
                                                                     : rotation * kSkPoisson[i] * o.poissonRadiusTexels;
            const vec2 tapUv = uv + offsetTexels / size;
            const float tapDepth = depth + dot(dDepthDuv, offsetTexels / size);
            sum += texture(maps, vec4(tapUv * atlasFromMap.xy + atlasFromMap.zw, float(layer), skStoredDepth(clamp(tapDepth, 0.0, 1.0))));
        }
        return sum / float(count);
    }
    if (o.filterKind == SK_FILTER_HARD && o.receiverPlane) {
        // Hard test: compare at the centre of the texel the sample falls in, on the receiver plane.
        const vec2 centre = (floor(uv * size) + 0.5) / size;
        depth += dot(dDepthDuv, centre - uv);
    }
    // SK_FILTER_PCF2: the sampler's GL_LINEAR filter does the 2 × 2 PCF in hardware. Depth clamp
    // in the shadow pass stores casters in front of the near plane at 0: clamp the reference too.
    return min(guard, texture(maps, vec4(uv * atlasFromMap.xy + atlasFromMap.zw, float(layer), skStoredDepth(clamp(depth, 0.0, 1.0)))));
}

// One map filling layer `layer` of `maps`.
// With opacity layers (SK_SHADOW_OPACITY), the leaves' transmittance times the depth map's term.
float skShadowMap(sampler2DArrayShadow maps, int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o,
                  vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    float lit = skShadowMapIn(maps, layer, textureFromWorld, linearDepthFromWorld, o, vec4(1.0, 1.0, 0.0, 0.0), ws, n, dwsdx, dwsdy);
#ifdef SK_SHADOW_OPACITY
    if (SK_SHADOW_OPACITY_ENABLED && lit > 0.0) lit *= skFoliageTransmittance(layer, textureFromWorld, linearDepthFromWorld, o, ws);
#endif
    return lit;
}

#ifdef SK_SHADOW_SPLIT
// The map serving this view depth: the first whose range ends beyond it.
int skCascadeOf(float viewDepth, int mapCount) {
    for (int i = 0; i < mapCount - 1; ++i)
        if (viewDepth <= SK_SHADOW_SPLIT(i).y) return i;
    return mapCount - 1;
}

// Cascades in the layers 0 .. mapCount − 1 of `maps`. With a blend band (CascadeOptions::blendBand)
// each split reaches back into the previous one: there the two maps' terms are mixed linearly in
// view depth, hiding the seam. viewDepth = dot(ws − eye, unit view direction).
float skCascadedShadow(sampler2DArrayShadow maps, int mapCount, SkShadowOptions o, float viewDepth, vec3 ws, vec3 n, vec3 dwsdx,
                       vec3 dwsdy) {
    const int map = skCascadeOf(viewDepth, mapCount);
    float term = skShadowMap(maps, map, SK_SHADOW_TEXTURE_FROM_WORLD(map), SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(map), o, ws, n, dwsdx, dwsdy);
    if (map + 1 < mapCount && viewDepth > SK_SHADOW_SPLIT(map + 1).x) {
        const float t = (viewDepth - SK_SHADOW_SPLIT(map + 1).x) / max(SK_SHADOW_SPLIT(map).y - SK_SHADOW_SPLIT(map + 1).x, 1e-6);
        const float next = skShadowMap(maps, map + 1, SK_SHADOW_TEXTURE_FROM_WORLD(map + 1), SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(map + 1),
                                       o, ws, n, dwsdx, dwsdy);
        term = mix(term, next, clamp(t, 0.0, 1.0));
    }
    return term;
}
#endif

// Virtual shadow maps: a clipmap of virtualTexels² maps whose resident pages live in one atlas
// (layer 0 of a sampler2DArrayShadow), each page with a guard band of guardTexels around it, and
// a page table (usampler2D, pagesPerSide wide, pagesPerSide rows per level) holding slot + 1 of
// each resident page of the level's window, 0 for none, at the page's cell: its place in the
// window plus the first page's cell (SK_VIRTUAL_LEVEL_TABLE_ORIGIN), modulo pagesPerSide.
// core::VirtualClipmap has the rest.
struct SkVirtualMaps {
    int levels;              // clipmap levels, finest first
    int firstExponent;       // level 0's texel is 2^firstExponent metres
    float footprintPerMetre; // a pixel's size at view depth 1 m
    float lodBias;           // added to log2 of the footprint
    int pagesPerSide;        // pages per side of a level's window
    int pageTexels;          // texels per side of a page
    int guardTexels;         // texels of guard band around each page in the atlas
    int slotsPerRow;         // atlas slots per row
    vec2 atlasTexels;        // the atlas's width and height
    float virtualTexels;     // texels per side of a level (pagesPerSide · pageTexels)
    float blendBand;         // [0, 1): the last fraction of each level's footprints fades into the next
};

// The level rule of core::clipmapLevelFor: the largest texel no larger than the pixel's footprint.
int skVirtualLevelRule(SkVirtualMaps v, float viewDepth) {
    const int e = int(floor(log2(max(viewDepth * v.footprintPerMetre, 1e-30)) + v.lodBias));
    return clamp(e - v.firstExponent, 0, v.levels - 1);
}

#ifdef SK_VIRTUAL_LEVEL_FROM_WORLD
#ifndef SK_VIRTUAL_LEVEL_TABLE_ORIGIN
#error "shadowkit_shadows.glsl: SK_VIRTUAL_LEVEL_FROM_WORLD needs SK_VIRTUAL_LEVEL_TABLE_ORIGIN (the page table is toroidal)"
#endif
// The level serving a receiver and where its page lies in the atlas: the rule's level, or the
// first coarser one with the receiver's page resident (a page not resident — the pool full, or
// the rule's level not reaching as far as a narrow view — falls back to the coarser level, which
// the marking always requests too). False when no level has it: lit, as outside any map.
//
// The loop runs on a local and assigns `level` once, at the return: NVIDIA's GLSL compiler
// (580.159) returned the loop's out parameter one increment on when the loop ran on it — every
// receiver read its page with the next coarser level's matrix.
bool skVirtualPageFrom(usampler2D pageTable, SkVirtualMaps v, int first, vec3 ws, out int level, out vec4 atlasFromMap) {
    level = v.levels - 1;
    atlasFromMap = vec4(0.0);
    for (int l = first; l < v.levels; ++l) {
        const vec4 t = SK_VIRTUAL_LEVEL_FROM_WORLD(l) * vec4(ws, 1.0);
        const vec2 uv = t.xy / t.w;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        const ivec2 page = min(ivec2(uv * float(v.pagesPerSide)), ivec2(v.pagesPerSide - 1));
        const ivec2 cell = (page + SK_VIRTUAL_LEVEL_TABLE_ORIGIN(l)) % v.pagesPerSide; // both in [0, pagesPerSide)
        const uint entry = texelFetch(pageTable, ivec2(cell.x, cell.y + l * v.pagesPerSide), 0).r;
        if (entry == 0u) continue;
        const int slot = int(entry) - 1;
        // Atlas texel of map texel m: slot corner + guard + (m − page · pageTexels).
        const vec2 corner = vec2(slot % v.slotsPerRow, slot / v.slotsPerRow) * float(v.pageTexels + 2 * v.guardTexels);
        const vec2 offsetTexels = corner + float(v.guardTexels) - vec2(page) * float(v.pageTexels);
        atlasFromMap = vec4(vec2(v.virtualTexels) / v.atlasTexels, offsetTexels / v.atlasTexels);
        level = l;
        return true;
    }
    return false;
}
bool skVirtualPage(usampler2D pageTable, SkVirtualMaps v, float viewDepth, vec3 ws, out int level, out vec4 atlasFromMap) {
    return skVirtualPageFrom(pageTable, v, skVirtualLevelRule(v, viewDepth), ws, level, atlasFromMap);
}

// The lit fraction of a receiver in level `level` of a virtual clipmap, its page at atlasFromMap.
// With opacity layers (SK_SHADOW_OPACITY) in atlases laid out as the depth atlas, the leaves'
// transmittance times the depth page's term. A page's clip depth is linear (its map is
// orthographic), so the layers' linear depth is that depth: textureFromWorld's depth row.
float skVirtualLevelShadow(sampler2DArrayShadow atlas, int level, vec4 atlasFromMap, SkShadowOptions o, vec3 ws, vec3 n,
                           vec3 dwsdx, vec3 dwsdy) {
    const mat4 textureFromWorld = SK_VIRTUAL_LEVEL_FROM_WORLD(level);
    float lit = skShadowMapIn(atlas, 0, textureFromWorld, vec4(0.0), o, atlasFromMap, ws, n, dwsdx, dwsdy);
#ifdef SK_SHADOW_OPACITY
    if (SK_SHADOW_OPACITY_ENABLED && lit > 0.0) {
        const vec4 depthRow = vec4(textureFromWorld[0].z, textureFromWorld[1].z, textureFromWorld[2].z, textureFromWorld[3].z);
        lit *= skFoliageTransmittanceIn(0, textureFromWorld, depthRow, o, atlasFromMap, ws);
    }
#endif
    return lit;
}

// The lit fraction of a receiver in a virtual clipmap; o.mapTexels is virtualTexels. The pages
// store clip depth, linear in an orthographic map: o.linearDepth is ignored.
float skVirtualShadow(sampler2DArrayShadow atlas, usampler2D pageTable, SkVirtualMaps v, SkShadowOptions o, float viewDepth,
                      vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
    o.linearDepth = false;
    int level;
    vec4 atlasFromMap;
    if (!skVirtualPage(pageTable, v, viewDepth, ws, level, atlasFromMap)) return 1.0;
    float term = skVirtualLevelShadow(atlas, level, atlasFromMap, o, ws, n, dwsdx, dwsdy);
    // Blend band (as cascades'): where the footprint nears the next level's texel, fade into that
    // level, so resolution changes smoothly with view depth instead of at a line that moves with
    // the camera. Only from the rule's own level (a fallback is already coarser).
    const float e = log2(max(viewDepth * v.footprintPerMetre, 1e-30)) + v.lodBias - float(v.firstExponent + level);
    const float w = v.blendBand > 0.0 ? clamp((e - (1.0 - v.blendBand)) / v.blendBand, 0.0, 1.0) : 0.0;
    int next;
    vec4 nextFromMap;
    if (w > 0.0 && e < 1.0 && skVirtualPageFrom(pageTable, v, level + 1, ws, next, nextFromMap))
        term = mix(term, skVirtualLevelShadow(atlas, next, nextFromMap, o, ws, n, dwsdx, dwsdy), w);
    return term;
}
#endif
