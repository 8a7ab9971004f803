#include "frame_config_options.h"

namespace shadowkit::app {

core::Result<frame::FrameConfig> frameConfigOf(const TechniqueOptions& technique, const RenderOptions& render,
                                               const LocalLightOptions& lights) {
    // The ranges are FrameConfig::check's, run once by FrameDriver::create (or frame::firstSetup);
    // the commands ran RenderOptions::check before loading anything.
    auto filter = core::parseFilter(render.filter);
    if (!filter) return withFlagName(filter.errorInfo());
    frame::FrameConfig config;
    // The technique's inputs without a frame: camera, light and scene box come with each.
    auto inputs = technique.inputsFor(scene::ResolvedView{}, core::Aabb{});
    if (!inputs) return inputs.errorInfo();
    config.technique = std::move(inputs).value();
    config.visibleDepthFromFrame = technique.visibleDepthFromFrame();
    if (technique.automatic) {
        auto options = technique.autoOptions();
        if (!options) return options.errorInfo();
        config.automatic = *options;
    }
    if (technique.holdsLattices()) config.heldLattices = technique.hysteresis;

    gl::RenderSettings& s = config.render;
    s.filter = *filter;
    s.sunAngleDegrees = render.sunAngle;
    s.blur = render.blur;
    s.cascadeColors = render.cascadeColors;
    s.foliageOpacity = render.foliageOpacity;
    s.aliasingOverlay = render.aliasingOverlay;
    s.culling = render.culling();
    s.receiverMask = render.receiverMask;
    s.lod = !render.noLod;
    s.lodPixelError = render.lodPixelError;
    s.lodTexelError = render.lodTexelError;
    s.lodFoliageScale = render.lodFoliageScale;
    s.lodFade = render.lodFade;
    s.virtualPoolPages = technique.virtualPoolPages;
    s.virtualBlendBand = technique.virtualBlendBand;
    s.virtualPageBudget = technique.virtualPageBudget;
    s.virtualRequestsLate = technique.virtualRequestsLate;
    s.localPass = lights.pass;
    s.localBias = lights.bias;
    config.fogDensity = render.fog;
    config.bias.slope = render.biasSlope;
    config.bias.constant = render.biasConstant;
    config.bias.normalOffset = render.normalOffset;
    config.bias.normalOffsetFootprint = render.normalOffsetFootprint;
    using Cull = RenderOptions::CullChoice;
    if (render.cull != Cull::Auto)
        config.bias.cull = render.cull == Cull::Closed  ? core::CasterCull::BackOfClosed
                           : render.cull == Cull::Back  ? core::CasterCull::Back
                           : render.cull == Cull::Front ? core::CasterCull::Front
                                                        : core::CasterCull::None;
    if (render.receiverPlaneBias != RenderOptions::Choice::Auto)
        config.bias.receiverPlane = render.receiverPlaneBias == RenderOptions::Choice::On;
    if (render.offsetGuard != RenderOptions::Choice::Auto)
        config.bias.offsetGuard = render.offsetGuard == RenderOptions::Choice::On;

    auto local = lights.lights();
    if (!local) return local.errorInfo();
    config.lights.assign(local->begin(), local->end());
    config.localMapSize = lights.mapSize;
    return config;
}

} // namespace shadowkit::app
