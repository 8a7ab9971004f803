// RenderSettings' names and checks (render_settings.h): what a front end validates before it draws.
#include "shadowkit/gl/render_settings.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

namespace shadowkit::gl {

const char* localPassName(LocalPass pass) {
    switch (pass) {
    case LocalPass::Layered:
        return "layered";
    case LocalPass::VertexLayer:
        return "vertex-layer";
    case LocalPass::Geometry:
        return "geometry";
    case LocalPass::PerFace:
        return "per-face";
    }
    return "?";
}

const char* cullingName(Culling culling) {
    switch (culling) {
    case Culling::Off:
        return "off";
    case Culling::Frustum:
        return "frustum";
    case Culling::Occlusion:
        return "chc";
    case Culling::Gpu:
        return "gpu";
    case Culling::Auto:
        return "auto";
    }
    return "?";
}

bool isSoftwareRasteriser(std::string_view glRenderer) {
    std::string lower(glRenderer);
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const char* software : {"llvmpipe", "softpipe", "swiftshader", "swrast", "gdi generic", "basic render"})
        if (lower.find(software) != std::string::npos) return true;
    return false;
}

Culling resolveCulling(Culling requested, std::string_view glRenderer) {
    if (requested != Culling::Auto) return requested;
    return isSoftwareRasteriser(glRenderer) ? Culling::Occlusion : Culling::Gpu;
}

core::Status validate(const BlurSettings& b) {
    if (b.iterations < 0 || b.iterations > 64) return core::fieldError("blur.iterations", "must be in [0, 64]");
    if (!(b.radiusPixels > 0.0f && b.radiusPixels <= 16.0f))
        return core::fieldError("blur.radius", "must be in (0, 16] pixels");
    if (!(b.depthFalloff >= 0.0f && b.depthFalloff <= 10.0f))
        return core::fieldError("blur.depth_falloff", "must be in [0, 10] per metre");
    if (!(b.depthThreshold > 0.0f && b.depthThreshold <= 1.0f))
        return core::fieldError("blur.depth_threshold", "must be in (0, 1]");
    return core::Ok{};
}

core::Status validateVirtualSettings(const RenderSettings& settings) {
    if (settings.virtualPoolPages < 0)
        return core::fieldError("virtual.pool_pages", "must be >= 0 (0: as many as fit 64 MiB), got " +
                                                          std::to_string(settings.virtualPoolPages));
    if (!(settings.virtualBlendBand >= 0.0f && settings.virtualBlendBand < 1.0f))
        return core::fieldError("virtual.blend_band", "must be a fraction in [0, 1)");
    if (settings.virtualPageBudget < 0)
        return core::fieldError("virtual.page_budget", "must be >= 0 (0: every page requested), got " +
                                                           std::to_string(settings.virtualPageBudget));
    return core::Ok{};
}

core::Status validateLevelsOfDetail(float pixelError, float texelError, float foliageScale, float fade) {
    if (!(pixelError > 0.0f && pixelError <= 16.0f))
        return core::fieldError("lod.pixel_error", "must be in (0, 16] pixels");
    if (!(texelError > 0.0f && texelError <= 16.0f))
        return core::fieldError("lod.texel_error", "must be in (0, 16] texels");
    if (!(foliageScale >= 1.0f && foliageScale <= 64.0f))
        return core::fieldError("lod.foliage_scale", "must be in [1, 64]");
    if (!(fade >= 0.0f && fade <= 0.9f)) return core::fieldError("lod.fade", "must be a fraction in [0, 0.9]");
    return core::Ok{};
}

core::Status validateFogDensity(double density) {
    if (!(density >= 0.0 && std::isfinite(density))) return core::fieldError("fog", "must be a density >= 0 (1/m)");
    return core::Ok{};
}

core::Status validateLocalLightCounts(size_t points, size_t spots) {
    constexpr auto kMax = static_cast<size_t>(kMaxLocalLightsPerKind);
    if (points > kMax || spots > kMax)
        return core::fieldError("lights", "at most " + std::to_string(kMax) + " point and " + std::to_string(kMax) +
                                              " spot lights, got " + std::to_string(points) + " and " +
                                              std::to_string(spots));
    return core::Ok{};
}

core::Status validateVirtualFilter(const core::FilterSettings& filter) {
    if (filter.kind == core::ShadowFilter::Msm)
        return core::fieldError("filter", "msm needs fixed maps: virtual pages hold depth only (use pcss)");
    return core::Ok{};
}

core::BiasSettings biasFor(const core::ShadowSetup& setup, const RenderSettings& settings) {
    return settings.bias.value_or(core::recommendedBias(setup.technique, setup.depthLayout, settings.filter));
}

} // namespace shadowkit::gl
