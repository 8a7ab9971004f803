// The opacity layers prefiltered (opacity_layers.h): per texel of one map, what a receiver below
// every leaf of the texel sees of them — the product of the four layers, T, their absorbance
// A = −ln T, and A times the leaves' depth (each layer's absorbance taken at its middle, in the
// map's linear depth) — drawn into level 0 of a mipmapped RGBA16F array, whose mip chain, built
// after, holds their means over squares of 2^k texels. One filtered fetch at the level of a disk
// then gives the mean transmittance over it (the sun's disk, for a receiver below the leaves)
// and, as (A · depth) / A, the leaves' absorbance-weighted mean depth there (the blocker search):
// the lookup's two steps without a loop of taps (skFoliageTransmittance). Half floats are
// enough: an error of 2^-11 of the depth range in the leaves' depth moves the disk's radius by
// that times tan(α), 3 mm for a 1.5 km range under the real sun.
layout(binding = SK_OPACITY_UNIT) uniform sampler2DArray layers;
layout(binding = SK_OPACITY_FIRST_UNIT) uniform sampler2DArray firstDepths;
layout(location = SK_OPACITY_LAYER_LOCATION) uniform int mapLayer;
layout(location = SK_OPACITY_DEPTH_PER_METRE_LOCATION) uniform float depthPerMetre; // along the light
layout(location = 0) out vec4 prefiltered;

void main() {
    const ivec3 p = ivec3(gl_FragCoord.xy, mapLayer);
    const float first = texelFetch(firstDepths, p, 0).r;
    const vec4 absorbance = -log(max(texelFetch(layers, p, 0), vec4(1e-6)));
    const float total = dot(absorbance, vec4(1.0));
    const vec4 end = SK_OPACITY_LAYER_EDGES, start = vec4(0.0, end.xyz);
    const float metres = total > 0.0 ? dot(absorbance, 0.5 * (start + end)) / total : 0.0;
    prefiltered = vec4(exp(-total), total, total * (first + metres * depthPerMetre), 0.0);
}
