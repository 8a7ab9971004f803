// Framing a scene without ground (framing.h): along a compass direction and pitch, the least
// eye distance at which every corner of the bounds lies inside the field of view.
#include "framing.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {

Framing frameBounds(const core::Aabb& bounds, double azimuthRadians, double pitchRadians, double fovYDegrees,
                    double aspect) {
    Framing out;
    const double pitch = std::min(pitchRadians, glm::radians(kFramingMaxPitchDegrees));
    const double az = azimuthRadians;
    const core::Vec3 centre = bounds.center();
    const core::Vec3 forward(std::sin(az) * std::cos(pitch), std::sin(pitch), -std::cos(az) * std::cos(pitch));
    // Straight down (a pitch of −90°, which cos() leaves a hair off vertical) the right vector
    // is still the compass direction's: the cross product is tiny but not zero in doubles.
    const core::Vec3 right = glm::normalize(glm::cross(forward, core::Vec3(0, 1, 0))), up = glm::cross(right, forward);
    // The eye at `distance` back from the centre sees a corner c (x right, y up, z forward of the
    // centre) when |x| <= tanX (distance + z) and |y| <= tanY (distance + z): the least distance
    // for every corner frames the box tightly.
    const double tanY = std::tan(0.5 * glm::radians(fovYDegrees)), tanX = tanY * aspect;
    double distance = 0.0, nearest = INFINITY, farthest = 0.0;
    for (const core::Vec3& corner : bounds.corners()) {
        const core::Vec3 c = corner - centre;
        const double x = glm::dot(c, right), y = glm::dot(c, up), z = glm::dot(c, forward);
        distance = std::max({distance, std::abs(x) / tanX - z, std::abs(y) / tanY - z});
    }
    // A margin round the picture; a box of no size (a point) is seen from a thousandth of a
    // metre — a floor relative to the box, so a model of a millimetre fills the picture too.
    distance = std::max(distance * 1.05, bounds.diagonal() > 0.0 ? 1e-3 * bounds.diagonal() : 1e-3);
    for (const core::Vec3& corner : bounds.corners()) {
        const double depth = distance + glm::dot(corner - centre, forward);
        nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
    }
    out.eye = centre - distance * forward;
    out.direction = forward;
    out.pitchRadians = pitch;
    out.zNear = std::max(0.9 * nearest, 1e-3 * farthest);
    out.zFar = 1.1 * farthest;
    out.fogDensity = 0.3 / out.zFar;
    return out;
}

} // namespace shadowkit::scene
