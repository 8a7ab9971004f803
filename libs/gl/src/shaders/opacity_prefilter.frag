// The opacity layers prefiltered for the lookup's search (opacity_layers.h): per texel of one
// map, the leaves' absorbance A = −ln T (T the product of the four layers) and A times their
// depth (each layer's leaves taken at its middle, in the map's linear depth), drawn into level 0
// of a mipmapped RG16F array whose mip chain, built after, holds their means over squares of 2^k
// texels. One filtered fetch at the level of the search's disk then gives, as (A · depth) / A,
// the leaves' absorbance-weighted mean depth over it: the blocker search as a ratio of two
// prefiltered sums, as convolution soft shadows find their blockers' mean depth (Annen et al.
// 2008, "Real-Time, All-Frequency Shadows in Dynamic Scenes", SIGGRAPH), instead of a loop of
// taps (skFoliageTransmittance). Half floats are enough: an error of 2^-11 of the depth range in
// the leaves' depth moves the disk's radius by that times tan(α), 3 mm for a 1.5 km range under
// the real sun.
layout(binding = SK_OPACITY_UNIT) uniform sampler2DArray layers;
layout(binding = SK_OPACITY_FIRST_UNIT) uniform sampler2DArray firstDepths;
layout(location = SK_OPACITY_LAYER_LOCATION) uniform int mapLayer;
layout(location = SK_OPACITY_DEPTH_PER_METRE_LOCATION) uniform float depthPerMetre; // along the light
layout(location = 0) out vec2 prefiltered;

void main() {
    const ivec3 p = ivec3(gl_FragCoord.xy, mapLayer);
    const float first = texelFetch(firstDepths, p, 0).r;
    vec4 share; // every layer whole: a receiver behind the last edge
    const vec4 absorbance = skLayerAbsorbanceBefore(texelFetch(layers, p, 0), SK_OPACITY_LAYER_EDGES.w, share);
    const float total = dot(absorbance, vec4(1.0));
    const float metres = total > 0.0 ? skLeavesMeanMetres(absorbance, share) : 0.0;
    prefiltered = vec2(total, total * (first + metres * depthPerMetre));
}
