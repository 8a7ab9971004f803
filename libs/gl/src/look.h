// The look of the camera pass: daylight, sky, sun and ambient radiance, fog colour. A look
// only: the shadow terms the evaluation compares do not depend on any of it.
#pragma once

#include "shadowkit/core/light.h"
#include "shadowkit/gl/render_settings.h"

#include <glm/glm.hpp>

namespace shadowkit::gl {

inline constexpr glm::vec3 kSky(0.62f, 0.72f, 0.85f);
inline constexpr glm::vec3 kNightSky(0.015f, 0.02f, 0.04f);

// Daylight, 1 to 0: full with the sun at 20° or higher, fading to night's at the horizon
// (dusk in the `village` view); 0 with the sun off.
inline float daylight(const core::DirectionalLight& light, const RenderSettings& settings) {
    return settings.sun ? glm::smoothstep(0.0f, 0.342f, static_cast<float>(light.wsTowardsLight().y)) : 0.0f; // sin 20°
}

// The sky's colour (display-referred, as cleared) under `day` daylight.
inline glm::vec3 skyColor(float day) { return glm::mix(kNightSky, kSky, day); }

struct Radiance {
    glm::vec4 sun, ambient, fogColor; // linear; fogColor's w is free for the density
};
inline Radiance radianceOf(float day) {
    return {day * glm::vec4(1.05f, 1.0f, 0.9f, 0.0f),
            glm::mix(glm::vec4(0.02f, 0.025f, 0.04f, 0.0f), glm::vec4(0.28f, 0.32f, 0.40f, 0.0f), day),
            glm::vec4(glm::pow(skyColor(day), glm::vec3(2.2f)), 0.0f)};
}

} // namespace shadowkit::gl
