#include "shadowkit/frame/frame_config.h"

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
    b.cull = cull.value_or(b.cull);
    b.receiverPlane = receiverPlane.value_or(b.receiverPlane);
    return b;
}

core::Status FrameConfig::check() const {
    // The technique's own options: their checks need no camera (validateOptions).
    if (auto s = core::validateOptions(technique); !s) return s;
    if (automatic)
        if (auto s = core::validate(*automatic); !s) return s;
    if (heldLattices)
        if (auto s = core::validate(*heldLattices); !s) return s;
    if (auto s = core::validate(render.filter); !s) return s;
    if (render.filter.kind == core::ShadowFilter::Msm && technique.technique == core::Technique::Virtual && !automatic)
        return core::fieldError("filter", "msm needs fixed maps: virtual pages hold depth only (use pcss)");
    if (auto s = gl::validate(render.blur); !s) return s;
    if (auto s = gl::validate(render.localBias); !s) return s;
    // The overridden bias values within BiasSettings' ranges (the recommendation always is).
    core::BiasSettings b;
    b.slope = bias.slope.value_or(b.slope);
    b.constant = bias.constant.value_or(b.constant);
    b.normalOffset = bias.normalOffset.value_or(b.normalOffset);
    if (auto s = core::validate(b); !s) return s;
    if (fogDensity && !(*fogDensity >= 0.0 && std::isfinite(*fogDensity)))
        return core::fieldError("fog", "must be a density >= 0 (1/m)");
    if (auto s = core::validateMapSize(localMapSize); !s)
        return core::fieldError("local_map_size", s.error().substr(s.errorInfo().field.size() + 2)); // "map_size: " off
    return core::Ok{};
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
    constexpr size_t kMax = static_cast<size_t>(gl::kMaxLocalLightsPerKind);
    if (points.size() > kMax || spots.size() > kMax)
        return core::fieldError("lights", "at most " + std::to_string(kMax) + " point and " + std::to_string(kMax) +
                                              " spot lights, got " + std::to_string(points.size()) + " and " +
                                              std::to_string(spots.size()) + " (with the view's)");
    const core::LocalShadowInputs inputs{
        .camera = view.camera, .wsSceneBounds = wsSceneBounds, .mapSize = config.localMapSize};
    auto lighting = core::computeLocalLighting(inputs, points, spots);
    if (!lighting) return core::fieldError("lights", lighting.error());
    return lighting;
}

} // namespace shadowkit::frame
