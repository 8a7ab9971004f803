// Shared by the error-driven tests: a camera low over a ground plane and the receivers it sees
// there, the view where the seeds say the warp's parameter matters most (Wimmer et al. 2004 §4.3).
#pragma once

#include "shadowkit/core/sampling_error.h"
#include "shadowkit/core/shadow_setup.h"

#include <vector>

namespace shadowkit::core::testing {

inline constexpr int kGroundWidth = 640, kGroundHeight = 360;

// A ground plane receiving everywhere the camera looks: a grid of points at y = 0.
inline std::vector<ReceiverSample> groundReceivers(const PerspectiveCamera& camera, double extent, int perSide) {
    std::vector<ReceiverSample> samples;
    for (int i = 0; i < perSide; ++i)
        for (int j = 0; j < perSide; ++j) {
            const Vec3 p(camera.wsEye.x + extent * ((i + 0.5) / perSide - 0.5), 0.0,
                         camera.wsEye.z - extent * (j + 0.5) / perSide);
            samples.push_back({p, Vec3(0.0, 1.0, 0.0)});
        }
    return samples;
}

// A 1.8 m camera looking along −z, nearly level, over a 600 m square of ground; a 1024² map.
inline ShadowSetupInputs groundView(double sunElevation, double sunAzimuth) {
    ShadowSetupInputs in;
    in.camera.wsEye = Vec3(0.0, 1.8, 0.0);
    in.camera.wsDirection = Vec3(0.0, -0.05, -1.0);
    in.camera.aspect = double(kGroundWidth) / kGroundHeight;
    in.camera.zNear = 0.5;
    in.camera.zFar = 300.0;
    in.light = *DirectionalLight::fromSunAngles(sunElevation, sunAzimuth);
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-300.0, -1.0, -300.0), Vec3(300.0, 20.0, 300.0));
    in.mapSize = 1024;
    return in;
}

} // namespace shadowkit::core::testing
