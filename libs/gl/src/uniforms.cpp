#include "uniforms.h"

#include "visibility.h"

#include <array>
#include <cstddef>
#include <string_view>

namespace shadowkit::gl {

#define SK_FIELD(type, member)                                                                                         \
    UniformField { #member, offsetof(type, member) }
#define SK_ARRAY_FIELD(type, member)                                                                                   \
    UniformField { #member "[0]", offsetof(type, member) }

std::span<const UniformField> depthPassFields() {
    static constexpr std::array kFields = {
        SK_FIELD(DepthPassUniforms, clipFromWorld), SK_FIELD(DepthPassUniforms, linearDepthFromWorld),
        SK_FIELD(DepthPassUniforms, slopeBias),     SK_FIELD(DepthPassUniforms, constantBias),
        SK_FIELD(DepthPassUniforms, ditherOrigin),  SK_FIELD(DepthPassUniforms, wsViewer),
    };
    return kFields;
}

std::span<const UniformField> frameFields() {
    static constexpr std::array kFields = {
        SK_FIELD(FrameUniforms, clipFromWorld),
        SK_FIELD(FrameUniforms, wsEye),
        SK_FIELD(FrameUniforms, wsViewForward),
        SK_FIELD(FrameUniforms, wsTowardsLight),
        SK_FIELD(FrameUniforms, sunRadiance),
        SK_FIELD(FrameUniforms, ambientRadiance),
        SK_FIELD(FrameUniforms, fogColorDensity),
        SK_FIELD(FrameUniforms, mapTexels),
        SK_FIELD(FrameUniforms, mapCount),
        SK_FIELD(FrameUniforms, linearLayout),
        SK_FIELD(FrameUniforms, cascadeColors),
        SK_FIELD(FrameUniforms, foliageOpacity),
        SK_FIELD(FrameUniforms, filterKind),
        SK_FIELD(FrameUniforms, filterTaps),
        SK_FIELD(FrameUniforms, poissonRadiusTexels),
        SK_FIELD(FrameUniforms, receiverPlane),
        SK_FIELD(FrameUniforms, normalOffsetTexels),
        SK_FIELD(FrameUniforms, normalOffsetFootprint),
        SK_FIELD(FrameUniforms, offsetGuard),
        SK_FIELD(FrameUniforms, readBlurredMask),
        SK_FIELD(FrameUniforms, aliasingOverlay),
        SK_FIELD(FrameUniforms, lightTanHalfAngle),
        SK_ARRAY_FIELD(FrameUniforms, shadowTextureFromWorld),
        SK_ARRAY_FIELD(FrameUniforms, shadowLinearDepthFromWorld),
        SK_ARRAY_FIELD(FrameUniforms, cascadeRange),
    };
    return kFields;
}

std::span<const UniformField> virtualMapsFields() {
    static constexpr std::array kFields = {
        UniformField{"virtualEnabled", offsetof(VirtualMapsUniforms, enabled)},
        UniformField{"virtualLevels", offsetof(VirtualMapsUniforms, levels)},
        UniformField{"virtualFirstExponent", offsetof(VirtualMapsUniforms, firstExponent)},
        UniformField{"virtualFootprintPerMetre", offsetof(VirtualMapsUniforms, footprintPerMetre)},
        UniformField{"virtualLodBias", offsetof(VirtualMapsUniforms, lodBias)},
        UniformField{"virtualPagesPerSide", offsetof(VirtualMapsUniforms, pagesPerSide)},
        UniformField{"virtualPageTexels", offsetof(VirtualMapsUniforms, pageTexels)},
        UniformField{"virtualGuardTexels", offsetof(VirtualMapsUniforms, guardTexels)},
        UniformField{"virtualSlotsPerRow", offsetof(VirtualMapsUniforms, slotsPerRow)},
        UniformField{"virtualTexels", offsetof(VirtualMapsUniforms, virtualTexels)},
        UniformField{"virtualAtlasTexels", offsetof(VirtualMapsUniforms, atlasTexels)},
        UniformField{"virtualBlendBand", offsetof(VirtualMapsUniforms, blendBand)},
        UniformField{"virtualTableOrigin[0]", offsetof(VirtualMapsUniforms, tableOrigin)},
    };
    return kFields;
}

std::span<const UniformField> virtualMarkFields() {
    static constexpr std::array kFields = {
        SK_FIELD(VirtualMarkUniforms, worldFromClip),
        SK_FIELD(VirtualMarkUniforms, wsEye),
        SK_FIELD(VirtualMarkUniforms, wsViewForward),
        SK_ARRAY_FIELD(VirtualMarkUniforms, levelClipFromWorld),
        SK_FIELD(VirtualMarkUniforms, levels),
        SK_FIELD(VirtualMarkUniforms, firstExponent),
        SK_FIELD(VirtualMarkUniforms, footprintPerMetre),
        SK_FIELD(VirtualMarkUniforms, lodBias),
        SK_FIELD(VirtualMarkUniforms, pagesPerSide),
        SK_FIELD(VirtualMarkUniforms, pageTexels),
        SK_FIELD(VirtualMarkUniforms, reachTexels),
    };
    return kFields;
}

std::span<const UniformField> blurFields() {
    static constexpr std::array kFields = {
        SK_FIELD(BlurUniforms, radiusPixels),
        SK_FIELD(BlurUniforms, depthFalloff),
        SK_FIELD(BlurUniforms, depthThreshold),
    };
    return kFields;
}

std::span<const UniformField> receiverMaskFields() {
    static constexpr std::array kFields = {
        SK_FIELD(ReceiverMaskUniforms, worldFromClip),
        SK_FIELD(ReceiverMaskUniforms, wsEye),
        SK_FIELD(ReceiverMaskUniforms, wsViewForward),
        SK_ARRAY_FIELD(ReceiverMaskUniforms, mapClipFromWorld),
        SK_ARRAY_FIELD(ReceiverMaskUniforms, mapLinearDepthFromWorld),
        SK_FIELD(ReceiverMaskUniforms, mapCount),
        SK_FIELD(ReceiverMaskUniforms, linearLayout),
        SK_FIELD(ReceiverMaskUniforms, maskSize),
    };
    return kFields;
}

std::span<const UniformField> localDepthFields() {
    static constexpr std::array kFields = {
        SK_ARRAY_FIELD(LocalDepthUniforms, faceClipFromWorld),
        SK_FIELD(LocalDepthUniforms, wsLightInvRange),
        SK_ARRAY_FIELD(LocalDepthUniforms, faceOfReplica),
        SK_FIELD(LocalDepthUniforms, layerBase),
        SK_FIELD(LocalDepthUniforms, replicas),
    };
    return kFields;
}

std::span<const UniformField> localLightsFields() {
    static constexpr std::array kFields = {
        SK_ARRAY_FIELD(LocalLightsUniforms, pointPositionRange),
        SK_ARRAY_FIELD(LocalLightsUniforms, pointRadianceTexel),
        SK_ARRAY_FIELD(LocalLightsUniforms, spotPositionRange),
        SK_ARRAY_FIELD(LocalLightsUniforms, spotAxisCosHalf),
        SK_ARRAY_FIELD(LocalLightsUniforms, spotRadianceTexel),
        SK_ARRAY_FIELD(LocalLightsUniforms, spotTextureFromWorld),
        SK_FIELD(LocalLightsUniforms, pointCount),
        SK_FIELD(LocalLightsUniforms, spotCount),
        SK_FIELD(LocalLightsUniforms, evalLight),
        SK_FIELD(LocalLightsUniforms, sunLights),
        SK_FIELD(LocalLightsUniforms, localSlopeBiasTexels),
        SK_FIELD(LocalLightsUniforms, localNormalOffsetTexels),
        SK_FIELD(LocalLightsUniforms, localConstantBiasMetres),
        SK_FIELD(LocalLightsUniforms, localMapTexels),
        SK_ARRAY_FIELD(LocalLightsUniforms, lightRadius),
    };
    return kFields;
}

#undef SK_FIELD
#undef SK_ARRAY_FIELD

const std::string& shaderPrelude() {
    static const std::string kPrelude = [] {
        std::string s = "#version 450 core\n";
        auto define = [&s](std::string_view name, long long value) {
            s.append("#define ").append(name).append(1, ' ').append(std::to_string(value)).append(1, '\n');
        };
        using core::ShadowFilter;
        define("SK_MAX_CASCADES", kMaxCascades);
        define("SK_FILTER_HARD", static_cast<int>(ShadowFilter::Hard));
        define("SK_FILTER_PCF2", static_cast<int>(ShadowFilter::Pcf2));
        define("SK_FILTER_GRID", static_cast<int>(ShadowFilter::PcfGrid));
        define("SK_FILTER_POISSON", static_cast<int>(ShadowFilter::Poisson));
        define("SK_FILTER_PCSS", static_cast<int>(ShadowFilter::Pcss));
        define("SK_FILTER_MSM", static_cast<int>(ShadowFilter::Msm));
        define("SK_FRAME_BINDING", kFrameBinding);
        define("SK_DEPTH_PASS_BINDING", kDepthPassBinding);
        define("SK_BLUR_BINDING", kBlurBinding);
        define("SK_INSTANCES_BINDING", kInstancesBinding);
        define("SK_VISIBLE_BINDING", kVisibleBinding);
        define("SK_BOXES_BINDING", kBoxesBinding);
        define("SK_MASK_BINDING", kMaskBinding);
        define("SK_DILATED_MASK_BINDING", kDilatedMaskBinding);
        define("SK_RECEIVER_MASK_BINDING", kReceiverMaskBinding);
        define("SK_RECEIVER_DEPTH_UNIT", kReceiverDepthUnit);
        define("SK_RANGE_BINDING", kRangeBinding);
        define("SK_PAGE_REQUEST_BINDING", kPageRequestBinding);
        define("SK_VIRTUAL_BINDING", kVirtualBinding);
        define("SK_VIRTUAL_MARK_BINDING", kVirtualMarkBinding);
        define("SK_PAGE_TABLE_UNIT", kPageTableUnit);
        define("SK_PAGE_TABLE_CHANGES_BINDING", kPageTableChangesBinding);
        define("SK_PAGE_TABLE_IMAGE_UNIT", kPageTableImageUnit);
        define("SK_RANGE_DEPTH_UNIT", kRangeDepthUnit);
        define("SK_BOX_OFFSET_LOCATION", kBoxOffsetLocation);
        define("SK_INSTANCE_OFFSET_LOCATION", kInstanceOffsetLocation);
        define("SK_LOD_ERROR_LOCATION", kLodErrorLocation);
        define("SK_SHADOW_MAP_UNIT", kShadowMapUnit);
        define("SK_SHADOW_DEPTH_UNIT", kShadowDepthUnit);
        define("SK_SPOT_DEPTH_UNIT", kSpotDepthUnit);
        define("SK_POINT_DEPTH_UNIT", kPointDepthUnit);
        define("SK_MOMENTS_UNIT", kMomentsUnit);
        define("SK_BASE_COLOR_UNIT", kBaseColorUnit);
        define("SK_OPACITY_UNIT", kOpacityUnit);
        define("SK_OPACITY_FIRST_UNIT", kOpacityFirstUnit);
        define("SK_OPACITY_PREFILTERED_UNIT", kOpacityPrefilteredUnit);
        define("SK_OPACITY_DEPTH_PER_METRE_LOCATION", kOpacityDepthPerMetreLocation);
        define("SK_OPACITY_LAYER_LOCATION", kOpacityLayerLocation);
        define("SK_BASE_ALPHA_LOCATION", kBaseAlphaLocation);
        define("SK_ALPHA_CUTOFF_LOCATION", kAlphaCutoffLocation);
        define("SK_MOMENTS_SOURCE_UNIT", kMomentsSourceUnit);
        define("SK_MOMENTS_IMAGE_UNIT", kMomentsImageUnit);
        define("SK_SHADOW_MASK_UNIT", kShadowMaskUnit);
        define("SK_BLUR_MASK_UNIT", kBlurMaskUnit);
        define("SK_BLUR_DEPTH_UNIT", kBlurDepthUnit);
        define("SK_INSTANCE_BASE_LOCATION", kInstanceBaseLocation);
        define("SK_SPOT_MAP_UNIT", kSpotMapUnit);
        define("SK_POINT_MAP_UNIT", kPointMapUnit);
        define("SK_LOCAL_DEPTH_BINDING", kLocalDepthBinding);
        define("SK_LOCAL_LIGHTS_BINDING", kLocalLightsBinding);
        define("SK_MAX_LOCAL_LIGHTS", kMaxLocalLights);
        define("SK_CULL_PYRAMID_UNIT", kCullPyramidUnit);
        define("SK_CULL_INSTANCES_BINDING", kCullInstancesBinding);
        define("SK_CULL_CHUNKS_BINDING", kCullChunksBinding);
        define("SK_CULL_BATCHES_BINDING", kCullBatchesBinding);
        define("SK_CULL_LEVELS_BINDING", kCullLevelsBinding);
        define("SK_CULL_FLAGS_BINDING", kCullFlagsBinding);
        define("SK_CULL_RANKS_BINDING", kCullRanksBinding);
        define("SK_CULL_CHUNK_SUMS_BINDING", kCullChunkSumsBinding);
        define("SK_CULL_STAGE_BINDING", kCullStageBinding);
        define("SK_CULL_PASSES_BINDING", kCullPassesBinding);
        define("SK_PAGES_BINDING", kPagesBinding);
        define("SK_DRAW_PAGES_BINDING", kDrawPagesBinding);
        define("SK_PAGE_BASE_LOCATION", kPageBaseLocation);
        define("SK_VIEWPORT_BASE_LOCATION", kViewportBaseLocation);
        define("SK_PAGE_PER_DRAW_LOCATION", kPagePerDrawLocation);
        define("SK_IMPOSTOR_SPHERE_LOCATION", kImpostorSphereLocation);
        define("SK_IMPOSTOR_GRID_LOCATION", kImpostorGridLocation);
        define("SK_EDGE_ATTRIBUTE", kEdgeAttribute);
        define("SK_CONSERVATIVE_DEPTH_CHECK_BINDING", kConservativeDepthCheckBinding);
        define("SK_CULL_GROUP", kCullGroup);
        define("SK_CULL_LEVELS", static_cast<long long>(kMaxLodLevels));
        define("SK_CULL_MAX_PYRAMID_LEVELS", kCullMaxPyramidLevels);
        s += "#line 1\n";
        return s;
    }();
    return kPrelude;
}

DepthPassUniforms depthPassUniformsFor(const core::ShadowView& view, const core::BiasSettings& bias,
                                       const core::Vec3& wsTowardsSun) {
    DepthPassUniforms uniforms = depthPassUniformsFor(view.clipFromWorld, bias, wsTowardsSun);
    uniforms.linearDepthFromWorld = glm::vec4(view.linearDepthFromWorld);
    return uniforms;
}

DepthPassUniforms depthPassUniformsFor(const core::Mat4& clipFromWorld, const core::BiasSettings& bias,
                                       const core::Vec3& wsTowardsSun) {
    // Linear layout: the same slope / constant bias, applied in depth.frag; hyperbolic: the
    // slope term by glPolygonOffset, the constant one in depth.vert. One constant unit is 2^-24
    // of the depth range, the resolvable step of a 24-bit buffer.
    return {.clipFromWorld = glm::mat4(clipFromWorld),
            .slopeBias = static_cast<float>(bias.slope),
            .constantBias = static_cast<float>(bias.constant) * 0x1p-24f,
            .wsViewer = glm::vec4(glm::vec3(wsTowardsSun), 0.0f)};
}

} // namespace shadowkit::gl
