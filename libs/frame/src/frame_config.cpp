#include "shadowkit/frame/frame_config.h"

#include "shadowkit/core/light_size.h"

#include <cmath>
#include <string>

namespace shadowkit::frame {

std::optional<core::BiasSettings> BiasOverrides::resolve(const core::ShadowSetupInputs& inputs,
                                                         const core::FilterSettings& filter) const {
    if (!any()) return std::nullopt;
    core::BiasSettings b = core::recommendedBias(inputs.technique, core::depthLayoutFor(inputs), filter);
    b.slope = slope.value_or(b.slope);
    b.constant = constant.value_or(b.constant);
    b.normalOffset = normalOffset.value_or(b.normalOffset);
    b.normalOffsetFootprint = normalOffsetFootprint.value_or(b.normalOffsetFootprint);
    b.cull = cull.value_or(b.cull);
    b.receiverPlane = receiverPlane.value_or(b.receiverPlane);
    b.offsetGuard = offsetGuard.value_or(b.offsetGuard);
    return b;
}

core::Status BiasOverrides::validate() const {
    core::BiasSettings b;
    b.slope = slope.value_or(b.slope);
    b.constant = constant.value_or(b.constant);
    b.normalOffset = normalOffset.value_or(b.normalOffset);
    b.normalOffsetFootprint = normalOffsetFootprint.value_or(b.normalOffsetFootprint);
    return core::validate(b);
}

core::Status validateFog(std::optional<double> fogDensity) {
    return fogDensity ? gl::validateFogDensity(*fogDensity) : core::Ok{};
}

core::Status FrameConfig::check() const {
    // The technique's own options: their checks need no camera (validateOptions).
    if (auto s = core::validateOptions(technique); !s) return s;
    if (automatic)
        if (auto s = core::validate(*automatic); !s) return s;
    if (heldLattices)
        if (auto s = core::validate(*heldLattices); !s) return s;
    if (auto s = core::validate(render.filter); !s) return s;
    if (auto s = core::validateSunAngle(render.sunAngleDegrees); !s) return s;
    if (technique.technique == core::Technique::Virtual && !automatic)
        if (auto s = gl::validateVirtualFilter(render.filter); !s) return s;
    if (auto s = gl::validate(render.blur); !s) return s;
    if (auto s = core::validate(render.localBias); !s) return s;
    if (auto s = gl::validateVirtualSettings(render); !s) return s;
    if (auto s = gl::validateLevelsOfDetail(render.lodPixelError, render.lodTexelError, render.lodFoliageScale,
                                            render.lodFade);
        !s)
        return s;
    if (auto s = bias.validate(); !s) return s;
    if (auto s = validateFog(fogDensity); !s) return s;
    if (auto s = core::validateMapSize(localMapSize); !s)
        return core::fieldError("local_map_size", s.error().substr(s.errorInfo().field.size() + 2)); // "map_size: " off
    return core::Ok{};
}

core::Result<core::ShadowSetup> firstSetup(const FrameConfig& config, const core::ShadowSetupInputs& inputs) {
    if (auto s = config.check(); !s) return s.errorInfo();
    if (config.heldLattices) return core::SetupHysteresis(*config.heldLattices).next(inputs);
    return core::computeShadowSetup(inputs);
}

core::Result<core::LocalLighting> localLightingFor(const FrameConfig& config, const scene::ResolvedView& view,
                                                   const core::Aabb& wsSceneBounds) {
    std::vector<core::PointLight> points = view.points;
    std::vector<core::SpotLight> spots = view.spots;
    for (const LocalLight& l : config.lights) {
        if (const auto* p = std::get_if<core::PointLight>(&l))
            points.push_back(*p);
        else
            spots.push_back(std::get<core::SpotLight>(l));
    }
    // The view's lights count too.
    if (auto s = gl::validateLocalLightCounts(points.size(), spots.size()); !s) return s.errorInfo();
    const core::LocalShadowInputs inputs{
        .camera = view.camera, .wsSceneBounds = wsSceneBounds, .mapSize = config.localMapSize};
    auto lighting = core::computeLocalLighting(inputs, points, spots);
    if (!lighting) return core::fieldError("lights", lighting.error());
    return lighting;
}

} // namespace shadowkit::frame
