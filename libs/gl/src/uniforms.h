// The interface between the C++ passes and their GLSL: uniform block layouts, binding
// points, texture units and the filter codes, declared once here. The shaders get the
// numbers from shaderPrelude() (#defines prepended to every stage), and every block's
// member offsets are compared with what the driver reports when the programs are built
// (checkUniformBlock), so a field added, moved or retyped on one side only fails there.
#pragma once

#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/render_settings.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace shadowkit::gl {

// Maps of the sun in one frame: cascades, or the levels of a virtual clipmap. GLSL: SK_MAX_CASCADES
inline constexpr int kMaxCascades = 16;
static_assert(kMaxCascades == int(core::kMaxShadowViews));

// Uniform block bindings (GLSL: SK_*_BINDING) and the instance storage buffer.
inline constexpr unsigned kFrameBinding = 0;
inline constexpr unsigned kDepthPassBinding = 1;
inline constexpr unsigned kBlurBinding = 2;
inline constexpr unsigned kInstancesBinding = 0; // shader storage: mat4 worldFromObject[] of the batch drawn
inline constexpr unsigned kVisibleBinding = 1;   // shader storage: uint visibleInstances[] of the frame
inline constexpr unsigned kMaskBinding = 3;      // shader storage: uint maskTexels[] of the receiver masks
inline constexpr unsigned kDilatedMaskBinding =
    8; // shader storage: the dilated masks (receiver_dilate.comp, gpu_cull.comp)
inline constexpr unsigned kReceiverMaskBinding = 3; // uniform block ReceiverMask (receiver_mask.comp)
inline constexpr unsigned kReceiverDepthUnit = 0;   // receiver mask pass: the pre-pass's view depth
inline constexpr unsigned kRangeBinding = 4;        // shader storage: uint nearBits, farBits (depth_range.comp)
inline constexpr unsigned kRangeDepthUnit = 0;      // depth range pass: the pre-pass's view depth
inline constexpr unsigned kBoxesBinding = 2;        // shader storage: vec4 boxCorners[] (min, max) of occlusion queries
inline constexpr unsigned kPageRequestBinding = 5;  // shader storage: uint requestBits[] (virtual_mark.comp)
inline constexpr unsigned kVirtualBinding = 7;      // uniform block VirtualMaps (frame.glsl)
inline constexpr unsigned kVirtualMarkBinding = 8;  // uniform block VirtualMark (virtual_mark.comp)
inline constexpr unsigned kPageTableChangesBinding = 6; // shader storage: uvec2 changes[] (page_table_update.comp)
inline constexpr unsigned kPageTableImageUnit = 0;      // page_table_update.comp: the page table it writes
// Texture units (GLSL: SK_*_UNIT). The camera passes and the blur pass never run together.
inline constexpr unsigned kShadowMapUnit = 0;  // camera passes: sampler2DArrayShadow, one layer per map
inline constexpr unsigned kShadowMaskUnit = 1; // main pass: the blurred shadow mask
inline constexpr unsigned kBlurMaskUnit = 0;   // blur pass: the mask being blurred
inline constexpr unsigned kBlurDepthUnit = 1;  // blur pass: view depth, to stop at depth steps
// Local lights (local_shadows.h): their maps beside the sun's in the camera passes.
inline constexpr unsigned kSpotMapUnit = 2;       // sampler2DArrayShadow, one layer per spot light
inline constexpr unsigned kPointMapUnit = 3;      // samplerCubeArrayShadow, one cube per point light
inline constexpr unsigned kPageTableUnit = 4;     // usampler2D: virtual maps' page table
inline constexpr unsigned kShadowDepthUnit = 5;   // camera passes: kShadowMapUnit's texture, stored depths (PCSS)
inline constexpr unsigned kSpotDepthUnit = 6;     // camera passes: the spot maps' stored distances (PCSS)
inline constexpr unsigned kPointDepthUnit = 7;    // camera passes: the point cubes' stored distances (PCSS)
inline constexpr unsigned kMomentsUnit = 8;       // camera passes: the sun's moment maps (MSM)
inline constexpr unsigned kBaseColorUnit = 9;     // SK_MATERIAL passes: the batch's base colour texture (material.glsl)
inline constexpr unsigned kOpacityUnit = 10;      // camera passes: the sun's opacity layers (opacity_layers.h)
inline constexpr unsigned kOpacityFirstUnit = 11; // camera passes and opacity.frag: the first leaves' depths
inline constexpr unsigned kOpacityPrefilteredUnit = 12;        // camera passes: the layers prefiltered, mipmapped
inline constexpr unsigned kMomentsSourceUnit = 0;              // moments.comp: the depth maps or moments it reads
inline constexpr unsigned kMomentsImageUnit = 0;               // moments.comp: the image it writes
inline constexpr unsigned kLocalDepthBinding = 5;              // uniform block LocalDepth (local_depth.glsl)
inline constexpr unsigned kLocalLightsBinding = 6;             // uniform block LocalLights (local_lights.glsl)
inline constexpr int kMaxLocalLights = kMaxLocalLightsPerKind; // GLSL: SK_MAX_LOCAL_LIGHTS
// GPU culling's storage buffers (gpu_cull.comp, depth_pyramid.comp; gpu_culling.h), bound before each dispatch.
inline constexpr unsigned kCullInstancesBinding = 0; // boxes and scales
inline constexpr unsigned kCullChunksBinding = 1;    // up to kCullGroup instances of one batch each
inline constexpr unsigned kCullBatchesBinding = 2;
inline constexpr unsigned kCullLevelsBinding = 3;    // per batch and level: errors and index ranges
inline constexpr unsigned kCullFlagsBinding = 4;     // visible last frame, per instance
inline constexpr unsigned kCullRanksBinding = 5;     // per instance: its level and rank in its chunk
inline constexpr unsigned kCullChunkSumsBinding = 6; // per chunk and level: count, then offset
inline constexpr unsigned kCullStageBinding =
    7; // each stage its own: the pyramid read (1), commands (2), lists (3), or the pyramid written
inline constexpr unsigned kCullPassesBinding = 9; // per pass: its volume and level-of-detail projection
// Virtual pages drawn together (depth.vert's SK_PAGES): each page's matrix and dither origin.
inline constexpr unsigned kPagesBinding = 10;
// ... and, for the pages' CPU lists drawn together (GpuScene::drawTogether's second form), the
// page of each draw: uint drawPages[] (depth.vert, pagePerDraw 2).
inline constexpr unsigned kDrawPagesBinding = 11;
inline constexpr unsigned kCullPyramidUnit = 0; // GPU culling: the depth the pyramid is built from
inline constexpr uint32_t kCullGroup = 128;     // GPU culling: instances per work group (gpu_cull.comp's chunks)
inline constexpr int kCullMaxPyramidLevels =
    16;                                         // GPU culling: depth pyramid levels (level 0 up to 32768 texels a side)
inline constexpr int kInstanceBaseLocation = 0; // uniform uint instanceBase (main.vert): surface identity
inline constexpr int kInstanceOffsetLocation = 1; // uniform uint instanceOffset: the draw's list in visibleInstances
inline constexpr int kBoxOffsetLocation = 3;      // uniform uint boxOffset (occlusion_box.vert): first box of the draw
inline constexpr int kBaseAlphaLocation = 4;      // uniform float skBaseAlpha (material.glsl): baseColorFactor.a
inline constexpr int kAlphaCutoffLocation = 5;    // uniform float skAlphaCutoff (material.glsl); < 0: never discard
inline constexpr int kOpacityLayerLocation = 6;   // uniform int (opacity.frag, opacity_prefilter.frag): the map drawn
inline constexpr int kOpacityDepthPerMetreLocation = 7; // uniform float depthPerMetre (opacity_prefilter.frag)
// uniform float lodObjectErrors[kMaxLodLevels] (main.vert): the error of each level a draw holds,
// locations 8 to 8 + kMaxLodLevels - 1 (an array takes a location an element: gpu_scene.cpp checks they end before
// kPageBaseLocation)
inline constexpr int kLodErrorLocation = 8;
inline constexpr int kPageBaseLocation = 16;     // uniform uint pageBase (depth.vert, SK_PAGES): the draw's first page
inline constexpr int kViewportBaseLocation = 17; // uniform int viewportBase (depth.vert, SK_PAGES): its viewport
// uniform uint pagePerDraw (depth.vert, SK_PAGES): where a draw's page is, after pageBase — 0: the
// call's; 1: the draw's index in the multi-draw; 2: drawPages[the draw's index]
inline constexpr int kPagePerDrawLocation = 18;
// uniform vec4 skImpostorSphere and ivec2 skImpostorGrid (impostor.glsl): the card of the level a
// shadow pass draws, set by GpuScene for an impostor's level (a frames count of 0 otherwise).
inline constexpr int kImpostorSphereLocation = 19;
inline constexpr int kImpostorGridLocation = 20;
// Vertex attribute float osLongestEdge (depth.vert's SK_LINEAR_DEPTH, local_depth_layer.vert), from
// its own buffer binding: the longest edge of the vertex's triangles, for the rasterised depth's
// bound of the passes that write their depth (GpuScene).
inline constexpr unsigned kEdgeAttribute = 4;
inline constexpr unsigned kEdgeBufferBinding = 1;
// Atomic counters (GLSL: SK_CONSERVATIVE_DEPTH_CHECK_BINDING), with CheckingConservativeDepth alone:
// the fragments of the passes that write their depth, those that broke depth_greater's promise and
// those whose bound lies within 1 and 5 m (depth.frag, local_depth.frag).
inline constexpr unsigned kConservativeDepthCheckBinding = 0;

// std140: scalars pack in fours, vec4 and mat4 start on 16 bytes. Booleans are int32.

// A virtual page's block when pages are drawn together (depth.vert's SkPage, std430).
struct PageBlock {
    glm::mat4 clipFromWorld;
    glm::vec4 ditherOrigin{0.0f}; // xy: DepthPassUniforms::ditherOrigin for the page
};
static_assert(sizeof(PageBlock) == 80);

struct DepthPassUniforms {          // GLSL: DepthPass (depth_pass.glsl)
    glm::mat4 clipFromWorld;        // the shadow view's light clip space
    glm::vec4 linearDepthFromWorld; // row: depth = dot(row, (ws, 1)), [0, 1] over B
    float slopeBias;                // linear layout: × max depth slope (glPolygonOffset's factor)
    float constantBias;             // both layouts: in depth units (glPolygonOffset's units × 2^-24)
    // Added to gl_FragCoord.xy for the levels' cross-fade dither (material.glsl): a virtual
    // page's texel origin in its level minus its slot's in the atlas, modulo the dither's 8.
    glm::vec2 ditherOrigin{0.0f};
    // The light, for the impostors' cards (impostor.glsl): xyz towards it (w 0: the sun).
    glm::vec4 wsViewer{0.0f, 1.0f, 0.0f, 0.0f};
};

// The block for drawing into `view` of the sun towards `wsTowardsSun`: the linear layout's bias as
// glPolygonOffset's would be, the constant term for both layouts (depth.vert says why not
// glPolygonOffset's).
DepthPassUniforms depthPassUniformsFor(const core::ShadowView& view, const core::BiasSettings& bias,
                                       const core::Vec3& wsTowardsSun);
// The same for a map that stores clip depth only (a virtual page): no linear row.
DepthPassUniforms depthPassUniformsFor(const core::Mat4& clipFromWorld, const core::BiasSettings& bias,
                                       const core::Vec3& wsTowardsSun);

struct FrameUniforms {        // GLSL: Frame (frame.glsl)
    glm::mat4 clipFromWorld;  // camera
    glm::vec4 wsEye;          // xyz
    glm::vec4 wsViewForward;  // xyz, unit: view depth = dot(ws − eye, forward)
    glm::vec4 wsTowardsLight; // xyz, unit
    glm::vec4 sunRadiance;    // rgb
    glm::vec4 ambientRadiance;
    glm::vec4 fogColorDensity;                      // rgb, a: density in 1/m
    float mapTexels;                                // texels per side of every map
    int32_t mapCount;                               // layers in use, [1, kMaxCascades]
    int32_t linearLayout;                           // 1: maps store linear depth
    int32_t cascadeColors;                          // 1: tint each split's range
    int32_t filterKind;                             // core::ShadowFilter (SK_FILTER_*)
    int32_t filterTaps;                             // N of N x N, or Poisson samples
    float poissonRadiusTexels;                      // Poisson's disk, or PCSS's widest kernel
    int32_t receiverPlane;                          // 1: receiver-plane depth bias
    float normalOffsetTexels;                       // receiver offset along its normal, in texels' world size
    int32_t readBlurredMask;                        // 1: main pass reads the blurred mask instead of the maps
    int32_t aliasingOverlay;                        // 1: main pass shows pixels per texel instead of shading
    float lightTanHalfAngle;                        // tan of the sun's angular radius (PCSS); 0: a point
    int32_t foliageOpacity;                         // 1: the maps' opacity layers apply (opacity_layers.h)
    float normalOffsetFootprint;                    // receiver offset along its normal, × its texel's footprint on it
    int32_t offsetGuard;                            // 1: core::BiasSettings::offsetGuard
    float pad0;                                     // std140: the mat4 array starts on 16 bytes
    glm::mat4 shadowTextureFromWorld[kMaxCascades]; // (u, v, depth, 1) · w of each map (core::toEngineView)
    glm::vec4 shadowLinearDepthFromWorld[kMaxCascades]; // rows, as in DepthPass
    glm::vec4 cascadeRange[kMaxCascades];               // x, y: view depth [start, end] each map serves
};

struct LocalDepthUniforms {         // GLSL: LocalDepth (local_depth.glsl)
    glm::mat4 faceClipFromWorld[6]; // a point light's cube faces, or a spot light's view in [0]
    glm::vec4 wsLightInvRange;      // xyz: the light; w: 1 / range (stored depth = distance / range)
    glm::ivec4 faceOfReplica[2];    // the face replica r of a draw writes: [r / 4][r % 4]
    int32_t layerBase;              // the light's first array layer (6 × index for a cube array)
    int32_t replicas;               // faces one draw writes, [1, 6]
    float pad0, pad1;
};

struct LocalLightsUniforms {                       // GLSL: LocalLights (local_lights.glsl)
    glm::vec4 pointPositionRange[kMaxLocalLights]; // xyz, w: range in metres
    glm::vec4 pointRadianceTexel[kMaxLocalLights]; // rgb, w: texel size per metre (core::texelSizePerMetre)
    glm::vec4 spotPositionRange[kMaxLocalLights];
    glm::vec4 spotAxisCosHalf[kMaxLocalLights]; // xyz: unit axis, w: cos(cone / 2)
    glm::vec4 spotRadianceTexel[kMaxLocalLights];
    glm::mat4 spotTextureFromWorld[kMaxLocalLights];
    int32_t pointCount, spotCount;
    int32_t evalLight;             // eval pass: −1 the sun, else a local light (points first, then spots)
    int32_t sunLights;             // 0: night, the sun neither lights nor is evaluated
    float localSlopeBiasTexels;    // receiver distance reduced by this × texel size × tan(angle to the light)
    float localNormalOffsetTexels; // receiver moved along its normal by this × texel size
    float localConstantBiasMetres; // and its distance reduced by this
    float localMapTexels;          // texels per side of every spot map and cube face
    glm::vec4 lightRadius[kMaxLocalLights]; // x: point light i's radius, y: spot light i's, in metres (PCSS)
};

struct ReceiverMaskUniforms { // GLSL: ReceiverMask (receiver_mask.comp)
    glm::mat4 worldFromClip;  // camera
    glm::vec4 wsEye;
    glm::vec4 wsViewForward;
    glm::mat4 mapClipFromWorld[kMaxCascades];
    glm::vec4 mapLinearDepthFromWorld[kMaxCascades];
    int32_t mapCount;
    int32_t linearLayout;
    int32_t maskSize;
    int32_t pad0;
};

struct VirtualMapsUniforms { // GLSL: VirtualMaps (frame.glsl); SkVirtualMaps in shadowkit_shadows.glsl
    int32_t enabled;         // 1: the sun's maps are a virtual clipmap
    int32_t levels;
    int32_t firstExponent;   // level 0's texel is 2^firstExponent metres
    float footprintPerMetre; // a pixel's size at view depth 1 m
    float lodBias;
    int32_t pagesPerSide;
    int32_t pageTexels;
    int32_t guardTexels;
    int32_t slotsPerRow;
    float virtualTexels;
    glm::vec2 atlasTexels; // width, height
    float blendBand;       // RenderSettings::virtualBlendBand
    float pad0, pad1, pad2;
    glm::ivec4 tableOrigin[kMaxCascades]; // xy: each level's first page's cell (core::pageTableCellOf)
};

struct VirtualMarkUniforms { // GLSL: VirtualMark (virtual_mark.comp)
    glm::mat4 worldFromClip; // camera
    glm::vec4 wsEye;
    glm::vec4 wsViewForward;
    glm::mat4 levelClipFromWorld[kMaxCascades];
    int32_t levels;
    int32_t firstExponent;
    float footprintPerMetre;
    float lodBias;
    int32_t pagesPerSide;
    int32_t pageTexels;
    float reachTexels;
    int32_t pad0;
};

struct BlurUniforms {     // GLSL: Blur (blur.frag)
    float radiusPixels;   // tap distance at view depth 0
    float depthFalloff;   // 1/m: radius / (1 + falloff · depth)
    float depthThreshold; // relative view-depth step that stops the kernel
    float pad0;
};

static_assert(offsetof(DepthPassUniforms, linearDepthFromWorld) == 64 && offsetof(DepthPassUniforms, wsViewer) == 96 &&
              sizeof(DepthPassUniforms) == 112);
static_assert(offsetof(FrameUniforms, mapTexels) == 160 && offsetof(FrameUniforms, shadowTextureFromWorld) == 224,
              "std140: the scalars must fill whole 16-byte rows before the arrays");
static_assert(sizeof(FrameUniforms) == 224 + kMaxCascades * (64 + 16 + 16));
static_assert(sizeof(BlurUniforms) == 16);
static_assert(offsetof(VirtualMapsUniforms, tableOrigin) == 64 &&
              sizeof(VirtualMapsUniforms) == 64 + kMaxCascades * 16);
static_assert(sizeof(LocalDepthUniforms) == 6 * 64 + 16 + 32 + 16);
static_assert(sizeof(LocalLightsUniforms) == kMaxLocalLights * (6 * 16 + 64) + 32);

// One member of a block: its GLSL name (arrays: "name[0]") and C++ offset.
struct UniformField {
    const char* name;
    size_t offset;
};
std::span<const UniformField> depthPassFields();
std::span<const UniformField> frameFields();
std::span<const UniformField> blurFields();
std::span<const UniformField> virtualMapsFields();
std::span<const UniformField> virtualMarkFields();
std::span<const UniformField> receiverMaskFields();
std::span<const UniformField> localDepthFields();
std::span<const UniformField> localLightsFields();

// "#version 450 core" and the #defines above (SK_MAX_CASCADES, SK_FILTER_HARD, ...,
// SK_FRAME_BINDING, ..., SK_SHADOW_MAP_UNIT, ...): the first source of every stage.
const std::string& shaderPrelude();

} // namespace shadowkit::gl
