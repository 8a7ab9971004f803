#include "frame_check.h"

#include "gl_object.h"
#include "uniforms.h"

#include "shadowkit/core/light_size.h"

#include <string>

namespace shadowkit::gl {

core::Status checkFrame(const core::ShadowSetup& setup, const RenderSettings& settings,
                        const core::BiasSettings& bias) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    // The set-up's map size is valid for core ([kMinMapSize, kMaxMapSize]); here it must also fit
    // this driver: within core's range but beyond this driver's is the machine's limit, not a
    // wrong value.
    const bool virtualMaps = setup.clipmap.has_value();
    if (!virtualMaps && (setup.mapSize < core::kMinMapSize || setup.mapSize > maxSize))
        return core::environmentError(
            "map_size: must be in [" + std::to_string(core::kMinMapSize) + ", " + std::to_string(maxSize) +
                "] texels on this GL driver (GL_MAX_TEXTURE_SIZE), got " + std::to_string(setup.mapSize),
            "map_size");
    if (settings.width < 1 || settings.height < 1 || settings.width > maxSize || settings.height > maxSize)
        return core::environmentError("image_size: each side must be in [1, " + std::to_string(maxSize) +
                                          "] pixels on this GL driver (GL_MAX_TEXTURE_SIZE)",
                                      "image_size");
    if (auto s = core::validate(bias); !s) return s;
    if (auto s = core::validate(settings.filter); !s) return s;
    if (auto s = core::validateSunAngle(settings.sunAngleDegrees); !s) return s;
    if (auto s = validate(settings.blur); !s) return s;
    if (auto s = core::validate(settings.localBias); !s) return s;
    if (auto s = validateLevelsOfDetail(settings.lodPixelError, settings.lodTexelError, settings.lodFoliageScale,
                                        settings.lodFade);
        !s)
        return s;
    if (auto s = validateFogDensity(settings.fogDensity); !s) return s;
    if (settings.lodCamera)
        if (auto s = settings.lodCamera->validate(); !s) return s;
    const int maps = static_cast<int>(setup.views.size());
    if (maps < 1 || maps > kMaxCascades)
        return core::makeError("renderer: set-ups need 1 to " + std::to_string(kMaxCascades) + " shadow maps, got " +
                               std::to_string(maps));
    if (!virtualMaps) return core::Ok{};
    if (auto s = validateVirtualFilter(settings.filter); !s) return s;
    return validateVirtualSettings(settings);
    return core::Ok{};
}

core::Status checkLocalLights(const core::LocalLighting& lights) {
    if (auto s = validateLocalLightCounts(lights.points.size(), lights.spots.size()); !s) return s;
    if (lights.pointSetups.size() != lights.points.size() || lights.spotSetups.size() != lights.spots.size())
        return core::makeError("renderer: every local light needs its set-up (core::computeLocalLighting)");
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &maxSize);
    if (!lights.empty() && (lights.mapSize < core::kMinMapSize || lights.mapSize > maxSize))
        return core::environmentError(
            "local_map_size: must be in [" + std::to_string(core::kMinMapSize) + ", " + std::to_string(maxSize) +
                "] texels on this GL driver (GL_MAX_CUBE_MAP_TEXTURE_SIZE), got " + std::to_string(lights.mapSize),
            "local_map_size");
    return core::Ok{};
}

} // namespace shadowkit::gl
