#include "shadowkit/core/light_size.h"

#include "shadowkit/core/output_conventions.h"

#include <glm/trigonometric.hpp>

#include <cmath>

namespace shadowkit::core {

Status validateSunAngle(double degrees) {
    if (!(degrees >= 0.0 && degrees <= kMaxSunAngleDegrees)) // NaN-safe
        return fieldError("sun_angle", "must be in [0, 20] degrees (the sun: 0.53)");
    return Ok{};
}

double tanAngularRadius(double degrees) { return std::tan(glm::radians(0.5 * degrees)); }

double penumbraTexelsPerMetre(const Mat4& clipFromWorld, int mapSize, const Vec3& wsLightDirection, double degrees,
                              const Vec3& wsPoint) {
    const double tanRadius = tanAngularRadius(degrees);
    if (tanRadius == 0.0) return 0.0;
    return tanRadius / wsTexelSize(clipFromWorld, mapSize, wsLightDirection, wsPoint); // +inf / inf: 0 texels
}

} // namespace shadowkit::core
