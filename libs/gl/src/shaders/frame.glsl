// Declarations shared by the camera passes (main and eval), after the prelude of
// uniforms.h. The C++ side of Frame is FrameUniforms there (member offsets checked when
// the programs are built).
layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };

layout(std140, binding = SK_FRAME_BINDING) uniform Frame {
    mat4 clipFromWorld;       // camera
    vec4 wsEye;               // xyz
    vec4 wsViewForward;       // xyz, unit: view depth = dot(ws - eye, forward)
    vec4 wsTowardsLight;      // xyz, unit
    vec4 sunRadiance;         // rgb
    vec4 ambientRadiance;     // rgb
    vec4 fogColorDensity;     // rgb, a: density in 1/m
    float mapTexels;          // texels per side of every map
    int mapCount;             // maps in use
    int linearLayout;         // 1: the maps store linear depth
    int cascadeColors;        // 1: tint each split's range
    int filterKind;           // SK_FILTER_HARD, _PCF2 (hardware 2x2), _GRID (N x N), _POISSON
    int filterTaps;           // N
    float poissonRadiusTexels; // Poisson's disk, or PCSS's widest kernel
    int receiverPlane;        // 1: receiver-plane depth bias
    float normalOffsetTexels; // receiver offset along its normal, in texels' world size
    int readBlurredMask;      // 1: the main pass reads the blurred mask instead of the maps
    int aliasingOverlay;      // 1: the main pass shows pixels per texel instead of shading
    float lightTanHalfAngle;  // tan of the sun's angular radius (PCSS); 0: a point
    int foliageOpacity;       // 1: the maps' opacity layers apply (leaves cast a fraction of shadow)
    float normalOffsetFootprint; // receiver offset along its normal, × its texel's footprint on the normal
    int offsetGuard;          // 1: a receiver behind another caster keeps its shadow under the offsets
    mat4 shadowTextureFromWorld[SK_MAX_CASCADES];     // (u, v, depth, 1) · w of each map
    vec4 shadowLinearDepthFromWorld[SK_MAX_CASCADES]; // rows, see DepthPass
    vec4 cascadeRange[SK_MAX_CASCADES];               // x, y: view depth [start, end] each map serves
};
// The block's arrays as glsl/shadowkit_shadows.glsl's accessors.
#define SK_SHADOW_TEXTURE_FROM_WORLD(i) shadowTextureFromWorld[i]
#define SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(i) shadowLinearDepthFromWorld[i]
#define SK_SHADOW_SPLIT(i) cascadeRange[i].xy
// The sun's maps (or the virtual page atlas) once more, their stored depths through a sampler
// without comparison: PCSS's blocker search.
layout(binding = SK_SHADOW_DEPTH_UNIT) uniform sampler2DArray shadowDepths;
#define SK_SHADOW_DEPTHS shadowDepths
// The sun's maps as prefiltered moments (moment_maps.h): MSM's lookup.
layout(binding = SK_MOMENTS_UNIT) uniform sampler2DArray shadowMoments;
#define SK_SHADOW_MOMENTS shadowMoments
// The sun's opacity layers (opacity_layers.h): the leaves' absorbance behind the first leaf's depth.
layout(binding = SK_OPACITY_UNIT) uniform sampler2DArray shadowOpacity;
layout(binding = SK_OPACITY_FIRST_UNIT) uniform sampler2DArray shadowOpacityFirst;
#define SK_SHADOW_OPACITY shadowOpacity
#define SK_SHADOW_OPACITY_FIRST shadowOpacityFirst
layout(binding = SK_OPACITY_PREFILTERED_UNIT) uniform sampler2DArray shadowOpacityPrefiltered;
#define SK_SHADOW_OPACITY_PREFILTERED shadowOpacityPrefiltered
#define SK_SHADOW_OPACITY_ENABLED (foliageOpacity != 0)

// Virtual shadow maps (virtual_pages.h): the C++ side is VirtualMapsUniforms. The levels'
// textureFromWorld are Frame's shadowTextureFromWorld.
layout(std140, binding = SK_VIRTUAL_BINDING) uniform VirtualMaps {
    int virtualEnabled; // 1: the sun's maps are a virtual clipmap
    int virtualLevels;
    int virtualFirstExponent;
    float virtualFootprintPerMetre;
    float virtualLodBias;
    int virtualPagesPerSide;
    int virtualPageTexels;
    int virtualGuardTexels;
    int virtualSlotsPerRow;
    float virtualTexels;
    vec2 virtualAtlasTexels;
    float virtualBlendBand;
    ivec4 virtualTableOrigin[SK_MAX_CASCADES]; // xy: the page table's cell of each level's first page
};
#define SK_VIRTUAL_LEVEL_FROM_WORLD(i) shadowTextureFromWorld[i]
#define SK_VIRTUAL_LEVEL_TABLE_ORIGIN(i) virtualTableOrigin[i].xy
