#include "fly_camera.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::viewer {

FlyCamera FlyCamera::looking(const core::Vec3& wsEye, const core::Vec3& wsDirection) {
    FlyCamera c;
    c.wsEye = wsEye;
    const core::Vec3 d = glm::normalize(wsDirection);
    c.yawDegrees = glm::degrees(std::atan2(d.x, -d.z));
    c.pitchDegrees = std::clamp(glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0))), -89.0, 89.0);
    return c;
}

core::Vec3 FlyCamera::wsDirection() const {
    const double yaw = glm::radians(yawDegrees), pitch = glm::radians(pitchDegrees);
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

void FlyCamera::move(const core::Vec3& rightUpForward, double seconds) {
    const core::Vec3 forward = wsDirection();
    const core::Vec3 right = glm::normalize(glm::cross(forward, core::Vec3(0, 1, 0)));
    const double step = metresPerSecond * seconds;
    wsEye += step * (rightUpForward.x * right + rightUpForward.y * core::Vec3(0, 1, 0) + rightUpForward.z * forward);
}

void FlyCamera::turn(double dxPixels, double dyPixels) {
    yawDegrees = std::fmod(yawDegrees + 0.2 * dxPixels, 360.0);
    pitchDegrees = std::clamp(pitchDegrees - 0.2 * dyPixels, -89.0, 89.0);
}

void FlyCamera::orbit(double dxPixels, double dyPixels, const core::Vec3& wsTarget) {
    const double distance = glm::length(wsTarget - wsEye);
    turn(dxPixels, dyPixels);
    wsEye = wsTarget - distance * wsDirection();
}

void FlyCamera::frame(const core::Aabb& wsBounds, double fovYDegrees) {
    if (wsBounds.isEmpty()) return; // nothing to frame: stay
    const core::Vec3 centre = 0.5 * (wsBounds.min + wsBounds.max);
    const double radius = 0.5 * glm::length(wsBounds.max - wsBounds.min);
    const double distance = radius / std::sin(0.5 * glm::radians(fovYDegrees));
    const core::Vec3 direction = glm::normalize(core::Vec3(0.0, -0.6, -0.8)); // 37° down, looking north
    *this = looking(centre - distance * direction, direction);
    metresPerSecond = std::max(1.0, 0.1 * radius);
}

} // namespace shadowkit::viewer
