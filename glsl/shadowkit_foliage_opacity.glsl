// shadowkit_foliage_opacity.glsl: partial occlusion by leaves for shadowkit_shadows.glsl — opacity
// layers beside the depth maps (--foliage-opacity; docs/materials.md, "Partial occlusion").
// Deep opacity maps (Yuksel & Keyser 2008) for the layers; PCSS's two steps (Fernando 2005) over
// the sun's disk, with the search for leaves beside a receiver one fetch of the layers prefiltered
// into a mip chain (a ratio of prefiltered sums, as in convolution soft shadows, Annen et al. 2008).
//
// Append it after shadowkit_shadows.glsl, whose options, coordinates and sun-disk geometry it uses;
// shadowkit_shadows.glsl's skShadowMap calls skFoliageTransmittance (declared there) when
// SK_SHADOW_OPACITY is defined. The helpers at the top — skLeafTransmittance, skOpacityLayerOf,
// skLayerAbsorbanceBefore, skLeavesMeanMetres — are for the engine's own passes that write the
// layers (gl's opacity.frag and opacity_prefilter.frag are the models) and need no samplers.
#ifndef SK_SHADOWS_GLSL
#error "shadowkit_foliage_opacity.glsl: append it after shadowkit_shadows.glsl"
#endif

// Partial occlusion by foliage: opacity layers beside the depth map (--foliage-opacity). A texel
// of a sun map holds one depth, so an alpha-tested canopy whose leaves are smaller than a texel
// either covers it or not, and the ground under it is all lit or all dark, where under the real
// sun it is a fraction lit. Deep opacity maps (Yuksel & Keyser 2008) keep instead, per texel, the
// depth of the first leaf and how much light the leaves behind it let through, in a few layers
// measured from it: here four, ending SK_OPACITY_LAYER_EDGES metres behind the first leaf, each
// the product of (1 − coverage) over its leaves (multiplicative blending: any order). A receiver
// `m` metres behind the first leaf is lit by the product of the layers in front of it, a layer it
// lies inside counted in proportion, T^share (its leaves taken as spread evenly through it; what
// lies beyond the last edge counts in the last layer). Transmittance, not absorbance, is what is
// stored and filtered: the sun's disk averages transmittance, and the exponential of a mean
// absorbance is darker than the mean transmittance (measured: a half-covered card stacked on
// another let through 0.17 of the light averaged as absorbance, 0.25 — the truth — averaged as
// transmittance). The opaque casters stay in the depth map; the two multiply (skShadowMap).
//
// The layers are thin at the front, where a receiver inside a canopy lies: there its share of a
// layer stands for the leaves in front of it, and the thinner the layer, the less a leaf behind
// it counts as one in front (chosen on the leafy forest's six views; docs/materials.md).
#ifndef SK_OPACITY_LAYER_EDGES
#define SK_OPACITY_LAYER_EDGES vec4(0.3, 1.5, 5.0, 12.0)
#endif
// The lookup's own bias, in texels of the map towards the light. A texel holds its first leaf's
// depth at the texel's centre, so a receiver on a leaf tilted against the light lies up to half a
// texel times the tilt's slope behind it, and without a bias took a share of its own leaf's shade:
// acne, in fractions (a sunlit card 45° to the light read 0.93 of the light where it is all lit).
#ifndef SK_OPACITY_BIAS_TEXELS
#define SK_OPACITY_BIAS_TEXELS 1.5
#endif
// A leaf covering a texel whole lets this much through it: 1 %.
#ifndef SK_OPACITY_MAX_COVERAGE
#define SK_OPACITY_MAX_COVERAGE 0.99
#endif

// What a fragment covering `coverage` of its texel lets through.
float skLeafTransmittance(float coverage) { return 1.0 - clamp(coverage, 0.0, SK_OPACITY_MAX_COVERAGE); }

// The layer a leaf `metres` behind the texel's first leaf multiplies, as a one-hot vector.
vec4 skOpacityLayerOf(float metres) {
    const vec4 end = SK_OPACITY_LAYER_EDGES;
    return vec4(metres < end.x, metres >= end.x && metres < end.y, metres >= end.y && metres < end.z, metres >= end.z);
}

// How much of each layer lies in front of a receiver `metres` behind the first leaf, 0 to 1.
vec4 skLayerShareBefore(float metres) {
    const vec4 end = SK_OPACITY_LAYER_EDGES, start = vec4(0.0, end.xyz);
    return clamp((metres - start) / (end - start), 0.0, 1.0);
}

// Each layer's absorbance, −ln T, in front of a receiver `metres` behind the first leaf; `share`
// says how much of each layer lies in front of it.
vec4 skLayerAbsorbanceBefore(vec4 layers, float metres, out vec4 share) {
    share = skLayerShareBefore(metres);
    return -log(max(layers, vec4(1e-6))) * share; // 0 · ln 0 would be NaN
}

// The mean distance behind the first leaf of the leaves of absorbance `mass` (> 0 in all) in the
// parts `share` of the layers: each layer's part weighted by its absorbance, taken at its middle.
float skLeavesMeanMetres(vec4 mass, vec4 share) {
    const vec4 end = SK_OPACITY_LAYER_EDGES, start = vec4(0.0, end.xyz);
    return dot(mass, start + 0.5 * share * (end - start)) / dot(mass, vec4(1.0));
}

#ifdef SK_SHADOW_OPACITY
// The caller names three sampler2DArrays laid out as the depth maps — for virtual maps as the
// page atlas, one layer, each page drawn into its slot with its guard band: the layers'
// transmittance (RGBA; 1 where no leaf is) and the first leaf's linear depth (R; 1 where no
// leaf covers the texel), both read texel by texel, and the layers prefiltered (RG, mipmapped,
// GL_LINEAR_MIPMAP_LINEAR: per texel A = −ln T and A × the leaves' depth; gl's
// opacity_prefilter.frag is the model), and when the lookup applies:
//   #define SK_SHADOW_OPACITY              myOpacityLayers
//   #define SK_SHADOW_OPACITY_FIRST        myOpacityFirst
//   #define SK_SHADOW_OPACITY_PREFILTERED  myOpacityPrefiltered
//   #define SK_SHADOW_OPACITY_ENABLED  (myFoliageOpacity != 0)   (default: always)

// The texel at (u, v) of map `layer`, stored at (u, v) · atlasFromMap.xy + atlasFromMap.zw of the
// textures: the whole layer (1, 1, 0, 0), or a virtual map's page in the atlases laid out as the
// depth atlas (skVirtualShadow), whose guard band holds every tap. The layers and the first
// leaf's depth are read texel by texel (texelFetch, whatever the samplers' filters): each
// texel's layers are measured from its own first leaf, and a receiver's layers blended with a
// neighbour's, measured from another depth, put leaves where its own texel has none (bilinear
// layers until 2026-12-01: the cascades' mean `soft_mae` 0.0331 against 0.0323 read texel by
// texel; docs/materials.md).
ivec3 skOpacityTexel(int layer, vec2 uv, vec4 atlasFromMap) {
    const ivec2 size = textureSize(SK_SHADOW_OPACITY_FIRST, 0).xy;
    return ivec3(clamp(ivec2(floor((uv * atlasFromMap.xy + atlasFromMap.zw) * vec2(size))), ivec2(0), size - 1), layer);
}

// The leaves in front of a receiver at linear depth `depth` at one point (u, v) of map `layer`,
// `metresPerDepth` metres per unit of depth: their absorbance, −ln T (0 where none is), and in
// `metresAway` their mean distance in front of the receiver, each layer's part weighted by its
// absorbance and taken at its middle.
float skLeavesInFront(int layer, vec2 uv, vec4 atlasFromMap, float depth, float metresPerDepth, out float metresAway) {
    metresAway = 0.0;
    const ivec3 texel = skOpacityTexel(layer, uv, atlasFromMap);
    const float metres = (depth - texelFetch(SK_SHADOW_OPACITY_FIRST, texel, 0).r) * metresPerDepth;
    if (!(metres > 0.0)) return 0.0; // in front of every leaf, or none here
    vec4 share;
    const vec4 mass = skLayerAbsorbanceBefore(texelFetch(SK_SHADOW_OPACITY, texel, 0), metres, share);
    const float total = dot(mass, vec4(1.0));
    if (!(total > 0.0)) return 0.0;
    metresAway = metres - skLeavesMeanMetres(mass, share);
    return total;
}

// The leaves' transmittance at one point (u, v) of map `layer`: exp(−Σ share · (−ln T)) over the
// layers, computed as the product it is, Π T^share. Every layer but the one the receiver lies in
// has a share of 0 or 1, so that is the product of the layers wholly in front times one power:
// a logarithm and an exponential per tap of the disk where the sum took five.
float skOpacityTransmittanceAt(int layer, vec2 uv, vec4 atlasFromMap, float depth, float metresPerDepth) {
    const ivec3 texel = skOpacityTexel(layer, uv, atlasFromMap);
    const float metres = (depth - texelFetch(SK_SHADOW_OPACITY_FIRST, texel, 0).r) * metresPerDepth;
    if (!(metres > 0.0)) return 1.0; // in front of every leaf, or none here
    const vec4 layers = max(texelFetch(SK_SHADOW_OPACITY, texel, 0), vec4(1e-6));
    const vec4 share = skLayerShareBefore(metres);
    const vec4 whole = vec4(greaterThanEqual(share, vec4(1.0)));
    const vec4 inside = vec4(greaterThan(share, vec4(0.0))) - whole; // one-hot, or none
    const vec4 front = mix(vec4(1.0), layers, whole);
    const float partial = dot(inside, layers) + 1.0 - dot(inside, vec4(1.0)); // 1 where none
    return front.x * front.y * front.z * front.w * pow(partial, dot(inside, share));
}

// The share of the sun the leaves let through to a receiver at `ws` in map `layer`, stored at
// atlasFromMap (skOpacityTexel). The opacity layers are in linear depth whatever the depth map's
// layout (linearDepthFromWorld's row, whose gradient's length is 1 / the range in metres; a
// virtual page's clip depth, skVirtualLevelShadow). With PCSS and a sun of some size, skPcss's two
// steps on the layers: the leaves' distance in front of the receiver, then the mean transmittance
// over the sun's disk at that distance, o.filterTaps taps of a Vogel disk (one, the receiver's own
// point, where the disk lies inside its texel); otherwise at the receiver's own point. The
// distance is that of the leaves in front of the receiver in its own texel, or where there are
// none — a gap in a canopy, the ground just beside its shadow — the absorbance-weighted mean depth
// of the leaves over the widest disk that can matter, one fetch of the prefiltered layers
// (opacity_prefilter.frag). Without that search such a receiver was drawn wholly lit (measured on
// the leafy forest: penumbrae at 0.65 of the truth's width, 35 % of the ground's penumbra pixels
// lit whole; docs/materials.md). The search used to take o.filterTaps taps of the layers too,
// counting only leaves whose cone reaches the receiver: most of the lookup's cost, for soft_mae
// within 0.0004 of this one's on every view of the leafy forest.
float skFoliageTransmittanceIn(int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o,
                               vec4 atlasFromMap, vec3 ws) {
    textureFromWorld = skDepthFromLight(textureFromWorld); // the layers hold d, near side 0, either way
    linearDepthFromWorld = skDepthFromLight(linearDepthFromWorld);
    vec4 t;
    vec3 uvz = skShadowCoordinates(textureFromWorld, linearDepthFromWorld, true, ws, t);
    if (t.w <= 0.0 || any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0)))) return 1.0;
    const float metresPerDepth = 1.0 / max(length(linearDepthFromWorld.xyz), 1e-30);
    mat2 uvFromDisk;
    float depthPerMetre, metresPerTexel;
    const bool footprint = skSunDiskInMap(textureFromWorld, linearDepthFromWorld, o, t, uvFromDisk, depthPerMetre, metresPerTexel);
    uvz.z -= SK_OPACITY_BIAS_TEXELS * metresPerTexel / metresPerDepth; // 0 where the map has no footprint here
    if (o.filterKind != SK_FILTER_PCSS || !(o.lightTanHalfAngle > 0.0) || !footprint)
        return skOpacityTransmittanceAt(layer, uvz.xy, atlasFromMap, uvz.z, metresPerDepth);
    const float widestMetres = o.poissonRadiusTexels * metresPerTexel;
    const int taps = max(o.filterTaps, 1);

    // 1. The leaves' distance: in the receiver's own texel, else their mean over the search's disk
    // (PCSS's: the cone up to the map's near plane, at most half a texel per tap).
    float awayMetres;
    const float ownAbsorbance = skLeavesInFront(layer, uvz.xy, atlasFromMap, uvz.z, metresPerDepth, awayMetres);
    if (!(ownAbsorbance > 0.0)) {
        const float searchMetres = min(uvz.z * metresPerDepth * o.lightTanHalfAngle,
                                       min(0.5 * float(taps) * metresPerTexel, widestMetres));
        const float side = 1.77 * searchMetres; // √π r: a square of the disk's area
        const vec3 at = vec3(uvz.xy * atlasFromMap.xy + atlasFromMap.zw, float(layer));
        const vec4 found = textureGrad(SK_SHADOW_OPACITY_PREFILTERED, at, uvFromDisk[0] * side * atlasFromMap.xy,
                                       uvFromDisk[1] * side * atlasFromMap.xy);
        if (!(found.x > 1e-3)) return 1.0; // no leaf there
        awayMetres = (uvz.z - found.y / found.x) * metresPerDepth;
        if (!(awayMetres > 0.0)) return 1.0; // the leaves there lie behind the receiver
    }

    // 2. The mean transmittance over the cone's disk at that distance. The layers are constant
    // over a texel, so over a disk inside the receiver's own texel their mean is that texel's:
    // one tap, the receiver's own point, whose leaves step 1 has read, exp(−absorbance) =
    // Π T^share — exactly. That is most receivers inside a canopy, a metre or a few below its
    // leaves, where the disk is millimetres wide. (The disk's reach along u is its radius times
    // the length of uvFromDisk's first row, along v its second's.)
    const float diskMetres = min(awayMetres * o.lightTanHalfAngle, widestMetres);
    const vec2 size = vec2(textureSize(SK_SHADOW_OPACITY_FIRST, 0).xy) * atlasFromMap.xy; // the map's texels
    const vec2 inTexel = fract(uvz.xy * size);
    const vec2 uvPerMetre = vec2(length(vec2(uvFromDisk[0].x, uvFromDisk[1].x)), length(vec2(uvFromDisk[0].y, uvFromDisk[1].y)));
    const vec2 reach = diskMetres * size * uvPerMetre; // in texels
    if (all(lessThan(reach, min(inTexel, 1.0 - inTexel)))) return exp(-ownAbsorbance);
    const float angle = skPixelAngle();
    float lit = 0.0;
    vec2 direction = vec2(cos(angle), sin(angle));
    for (int i = 0; i < taps; ++i, direction = kSkGoldenTurn * direction) {
        const vec2 offset = uvFromDisk * (direction * (sqrt((float(i) + 0.5) / float(taps)) * diskMetres));
        lit += skOpacityTransmittanceAt(layer, uvz.xy + offset, atlasFromMap, uvz.z, metresPerDepth);
    }
    return lit / float(taps);
}

// One map filling layer `layer` of the textures.
float skFoliageTransmittance(int layer, mat4 textureFromWorld, vec4 linearDepthFromWorld, SkShadowOptions o, vec3 ws) {
    return skFoliageTransmittanceIn(layer, textureFromWorld, linearDepthFromWorld, o, vec4(1.0, 1.0, 0.0, 0.0), ws);
}
#endif
