// The sun's opacity layers (opacity_layers.h): the alpha-tested casters, drawn twice.
// SK_OPACITY_FIRST: the first pass keeps, per texel, the nearest linear depth of any leaf
// (depth-tested, blending GL_MIN into an R32F layer). Otherwise the second pass, with no depth
// test, multiplies the layer of each leaf fragment's distance behind that first leaf by what the
// fragment lets through, 1 − coverage (blending GL_ZERO, GL_SRC_COLOR into an RGBA16F layer
// cleared to 1: four layers, SK_OPACITY_LAYER_EDGES), in any order.
in vec3 wsPosition;
#ifdef SK_OPACITY_FIRST
layout(location = 0) out float firstDepth;
#else
layout(binding = SK_OPACITY_FIRST_UNIT) uniform sampler2DArray opacityFirst;
layout(location = SK_OPACITY_LAYER_LOCATION) uniform int opacityLayer;
layout(location = 0) out vec4 transmittance;
#endif

// The share of the fragment's footprint the material covers: four alpha tests on a rotated grid
// inside it, each at the mip level of a quarter of the footprint (the coverage-keeping mips,
// scene/texture_mips.h, keep each level's share above the cutoff). A leaf wider than a texel
// covers it (1); a card of many small leaves a texel sees whole covers its share of it.
float skFootprintCoverage() {
    const vec2 dx = dFdx(vUv), dy = dFdy(vUv);
    const vec2 grid[4] = vec2[](vec2(-0.125, -0.375), vec2(0.375, -0.125), vec2(0.125, 0.375), vec2(-0.375, 0.125));
    float covered = 0.0;
    for (int i = 0; i < 4; ++i) {
        const float alpha = textureGrad(skBaseColorTexture, vUv + grid[i].x * dx + grid[i].y * dy, 0.5 * dx, 0.5 * dy).a;
        covered += alpha * skBaseAlpha >= skAlphaCutoff ? 0.25 : 0.0;
    }
    return covered;
}

void main() {
    // An instance crossing levels of detail casts each level's share of its absorbance.
    const float coverage = skFootprintCoverage() * skCrossingShare();
    const float depth = dot(linearDepthFromWorld, vec4(wsPosition, 1.0));
#ifdef SK_OPACITY_FIRST
    firstDepth = depth;
#else
    const float first = texelFetch(opacityFirst, ivec3(gl_FragCoord.xy, opacityLayer), 0).r;
    const float metres = max(depth - first, 0.0) / length(linearDepthFromWorld.xyz);
    transmittance = mix(vec4(1.0), vec4(skLeafTransmittance(coverage)), skOpacityLayerOf(metres));
#endif
    if (coverage == 0.0) discard;
}
