#include "shadowkit/frame/option_table.h"

#include <array>

namespace shadowkit::frame {
namespace {

using enum CheckedIn;

// Grouped by struct, in member order. A member with several checked fields (a light's position,
// range, cone) has a row for each, all naming the same flag.
constexpr auto kRows = std::to_array<OptionRow>({
    // core::ShadowSetupInputs: the technique's inputs (FrameConfig::technique).
    {"ShadowSetupInputs.camera", "", "", "a finite view, 0 < near < far", Core,
     "each frame's view (--view, --eye, --dir, --up, --fov, --near, --far)"},
    {"ShadowSetupInputs.light", "--sun", "light_direction", "a finite unit vector", Core},
    {"ShadowSetupInputs.wsSceneBounds", "--scene-bounds", "scene_bounds", "finite, min <= max", Core},
    {"ShadowSetupInputs.technique", "--technique", "", "a technique's name", None},
    {"ShadowSetupInputs.mapSize", "--map-size", "map_size", "[16, 16384] texels (and the driver's limit)", Core},
    {"ShadowSetupInputs.lispsm.formula", "--lispsm-formula", "", "scherzer | wimmer", None},
    {"ShadowSetupInputs.lispsm.direction", "--lispsm-direction", "", "cross-product | view", None},
    {"ShadowSetupInputs.lispsm.weight", "--lispsm-weight", "lispsm.weight", "finite, > 0", Core},
    {"ShadowSetupInputs.lispsm.nOverride", "--lispsm-n", "lispsm.n", "finite, > 0 metres", Core},
    {"ShadowSetupInputs.lispsm.visibleNear", "--lispsm-visible-near", "", "on | off", None},
    {"ShadowSetupInputs.tsm.focusFraction", "--tsm-focus", "tsm.focus", "(0, 1)", Core},
    {"ShadowSetupInputs.cascades.count", "--cascades", "cascades.count", "[1, 8]", Core},
    {"ShadowSetupInputs.cascades.lambda", "--lambda", "cascades.lambda", "[0, 1]", Core},
    {"ShadowSetupInputs.cascades.splits", "--splits", "cascades.splits", "count + 1 increasing distances", Core},
    {"ShadowSetupInputs.cascades.warp", "--cascade-warp", "", "none | lispsm", None},
    {"ShadowSetupInputs.cascades.stabilize", "--stabilize", "cascades.stabilize", "csm without warp", Core},
    {"ShadowSetupInputs.cascades.blendBand", "--blend-band", "cascades.blend_band", "[0, 0.5]", Core},
    {"ShadowSetupInputs.virtualMaps.virtualTexels", "--virtual-texels", "virtual.texels",
     "a power of two in [1024, 65536]", Core},
    {"ShadowSetupInputs.virtualMaps.pageTexels", "--virtual-page-texels", "virtual.page_texels",
     "a power of two in [16, 1024], virtual texels / 512 to / 8", Core},
    {"ShadowSetupInputs.virtualMaps.firstLevel", "--virtual-first-level", "virtual.first_level", "[-24, 24]", Core},
    {"ShadowSetupInputs.virtualMaps.lodBias", "--virtual-lod-bias", "virtual.lod_bias", "[-8, 8]", Core},
    {"ShadowSetupInputs.virtualMaps.imageHeight", "", "virtual.image_height", ">= 1", Core,
     "each frame's image height (--size)"},
    {"ShadowSetupInputs.depthLayout", "--depth-layout", "", "auto | hyperbolic | linear", None},
    {"ShadowSetupInputs.visibleDepth", "--visible-depth", "visible_depth", "0 <= near < far, or auto", Core},
    {"ShadowSetupInputs.wsGridOrigin", "", "", "", None, "the scene's origin (Scene::wsOrigin)"},

    // gl::RenderSettings (FrameConfig::render).
    {"RenderSettings.width", "--size", "image_size", "[1, the driver's GL_MAX_TEXTURE_SIZE]", Gl},
    {"RenderSettings.height", "--size", "image_size", "[1, the driver's GL_MAX_TEXTURE_SIZE]", Gl},
    {"RenderSettings.bias", "", "", "", None, "FrameConfig.bias, resolved each frame for its technique"},
    {"RenderSettings.filter", "--filter", "filter", "hard | pcf2 | pcf:N | poisson:N | pcss[:N] | msm", Core},
    {"RenderSettings.filter", "--filter", "filter.taps", "pcf [1, 9]; msm [0, 8]; poisson and pcss their sample counts",
     Core},
    {"RenderSettings.filter", "--filter", "filter.radius", "(0, 16] texels", Core},
    {"RenderSettings.sunAngleDegrees", "--sun-angle", "sun_angle", "[0, 20] degrees", Core},
    {"RenderSettings.blur.iterations", "--blur-iterations", "blur.iterations", "[0, 64]", Gl},
    {"RenderSettings.blur.radiusPixels", "--blur-radius", "blur.radius", "(0, 16] pixels", Gl},
    {"RenderSettings.blur.depthFalloff", "--blur-depth-falloff", "blur.depth_falloff", "[0, 10] per metre", Gl},
    {"RenderSettings.blur.depthThreshold", "--blur-depth-threshold", "blur.depth_threshold", "(0, 1]", Gl},
    {"RenderSettings.fogDensity", "--fog", "fog", "a density >= 0 per metre", Gl},
    {"RenderSettings.culling", "--visibility", "", "off | frustum | chc | gpu | auto", None},
    {"RenderSettings.receiverMask", "--caster-culling", "", "volume | receivers", None},
    {"RenderSettings.lod", "--no-lod", "", "on | off", None},
    {"RenderSettings.lodPixelError", "--lod-pixel-error", "lod.pixel_error", "(0, 16] pixels", Gl},
    {"RenderSettings.lodTexelError", "--lod-texel-error", "lod.texel_error", "(0, 16] texels", Gl},
    {"RenderSettings.lodFoliageScale", "--lod-foliage-scale", "lod.foliage_scale", "[1, 64]", Gl},
    {"RenderSettings.lodFade", "--lod-fade", "lod.fade", "[0, 0.9]", Gl},
    {"RenderSettings.lodCamera", "", "", "a camera", None, "eval --path --level-pops: the previous frame's camera"},
    {"RenderSettings.cascadeColors", "--cascade-colors", "", "on | off", None},
    {"RenderSettings.foliageOpacity", "--foliage-opacity", "", "on | off", None},
    {"RenderSettings.aliasingOverlay", "--aliasing-overlay", "", "on | off", None},
    {"RenderSettings.sun", "--sun", "", "a direction, or off (night)", None},
    {"RenderSettings.localPass", "--local-pass", "", "layered | vertex-layer | geometry | per-face", None},
    {"RenderSettings.localBias.slopeTexels", "--local-bias-slope", "local_bias.slope", "[0, 16] texels", Gl},
    {"RenderSettings.localBias.normalOffsetTexels", "--local-normal-offset", "local_bias.normal_offset",
     "[0, 16] texels", Gl},
    {"RenderSettings.localBias.constantMetres", "--local-bias-constant", "local_bias.constant", "[0, 1] metres", Gl},
    {"RenderSettings.virtualPoolPages", "--virtual-pool-pages", "virtual.pool_pages", ">= 0 (0: as many as fit 64 MiB)",
     Gl},
    {"RenderSettings.virtualBlendBand", "--virtual-blend-band", "virtual.blend_band", "[0, 1)", Gl},
    {"RenderSettings.virtualPageBudget", "--virtual-page-budget", "virtual.page_budget", ">= 0 (0: every page)", Gl},
    {"RenderSettings.virtualRequestsLate", "--virtual-requests", "", "wait | late", None},

    // frame::FrameConfig.
    {"FrameConfig.technique", "", "", "", None, "the ShadowSetupInputs rows"},
    {"FrameConfig.render", "", "", "", None, "the RenderSettings rows"},
    {"FrameConfig.bias.slope", "--bias-slope", "bias.slope", "[0, 100]", Core},
    {"FrameConfig.bias.constant", "--bias-constant", "bias.constant", "[0, 1e6]", Core},
    {"FrameConfig.bias.normalOffset", "--normal-offset", "bias.normal_offset", "[0, 10] texels", Core},
    {"FrameConfig.bias.normalOffsetFootprint", "--normal-offset-footprint", "bias.normal_offset_footprint",
     "[0, 10] texel footprints", Core},
    {"FrameConfig.bias.cull", "--cull", "", "auto | closed | back | front | none", None},
    {"FrameConfig.bias.receiverPlane", "--receiver-plane-bias", "", "auto | on | off", None},
    {"FrameConfig.bias.offsetGuard", "--offset-guard", "", "auto | on | off", None},
    {"FrameConfig.fogDensity", "--fog", "fog", "a density >= 0 per metre", Gl},
    {"FrameConfig.visibleDepthFromFrame", "--visible-depth", "", "auto", None},
    {"FrameConfig.automatic.texelBudget", "--texel-budget", "auto.texel_budget", "N[K|M] texels", Core},
    {"FrameConfig.automatic.cascades", "--cascades", "auto.cascades", "[0, 8]", Core},
    {"FrameConfig.automatic.hysteresis", "", "auto.hysteresis", "[0, 1)", Core, "1 - 1 / --stabilize-growth"},
    {"FrameConfig.automatic.searchSamples", "", "auto.search_samples", "[20, 1000000]", Core, "the library's default"},
    {"FrameConfig.heldLattices.margin", "--stabilize-margin", "hysteresis.margin", "[0, 1]", Core},
    {"FrameConfig.heldLattices.maxTexelGrowth", "--stabilize-growth", "hysteresis.growth", "finite, > 1", Core},
    {"FrameConfig.heldLattices.lookaheadFrames", "--stabilize-lookahead", "hysteresis.lookahead", "[0, 1000]", Core},
    {"FrameConfig.lights", "--light", "lights", "at most 16 point and 16 spot lights", Frame},
    {"FrameConfig.lights", "--light", "spot.position", "finite", Core},
    {"FrameConfig.lights", "--light", "spot.direction", "finite, not zero", Core},
    {"FrameConfig.lights", "--light", "spot.cone", "(0, 170] degrees", Core},
    {"FrameConfig.lights", "--light", "spot.range", "finite, > 0 metres", Core},
    {"FrameConfig.lights", "--light", "spot.radius", "[0, range) metres", Core},
    {"FrameConfig.lights", "--light", "point.position", "finite", Core},
    {"FrameConfig.lights", "--light", "point.range", "finite, > 0 metres", Core},
    {"FrameConfig.lights", "--light", "point.radius", "[0, range) metres", Core},
    {"FrameConfig.localMapSize", "--local-map-size", "local_map_size", "[16, 16384] texels (and the driver's)", Core},
});

} // namespace

std::span<const OptionRow> optionTable() { return kRows; }

const OptionRow* optionForField(std::string_view field) {
    if (field.empty()) return nullptr;
    for (const OptionRow& row : kRows)
        if (row.field == field && !row.flag.empty()) return &row;
    return nullptr;
}

} // namespace shadowkit::frame
