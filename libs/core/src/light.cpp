#include "shadowkit/core/light.h"

#include <cmath>

namespace shadowkit::core {

Result<DirectionalLight> DirectionalLight::fromDirection(const Vec3& wsTravel) {
    const double len = glm::length(wsTravel);
    if (!std::isfinite(len) || len < 1e-12) return makeError("light direction: must be a finite, non-zero vector");
    return DirectionalLight{wsTravel / len};
}

Result<DirectionalLight> DirectionalLight::fromSunAngles(double elevationDegrees, double azimuthDegrees) {
    if (!(elevationDegrees >= -90.0 && elevationDegrees <= 90.0)) // NaN-safe
        return makeError("sun elevation: must be in [-90, 90] degrees");
    if (!std::isfinite(azimuthDegrees)) return makeError("sun azimuth: must be finite");
    const double el = glm::radians(elevationDegrees);
    const double az = glm::radians(azimuthDegrees);
    const Vec3 towardsSun(std::sin(az) * std::cos(el), std::sin(el), -std::cos(az) * std::cos(el));
    return DirectionalLight{-towardsSun};
}

double azimuthDegreesOf(const Vec3& wsDirection) { return glm::degrees(std::atan2(wsDirection.x, -wsDirection.z)); }

} // namespace shadowkit::core
