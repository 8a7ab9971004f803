// A frame in the scene's coordinates, where everything on the GPU lives (scene::Scene's
// wsOrigin at 0): the camera moved by −wsOrigin, the set-up rebased there in double from its
// eye-relative matrices (core::rebased), so float sees numbers of the scene's size however far
// from the world's origin the scene stands. Renderer's public calls take world coordinates and
// come through here.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/shadow_setup.h"

#include <optional>

namespace shadowkit::gl {

struct SceneFrame {
    core::PerspectiveCamera camera;
    std::optional<core::ShadowSetup> rebasedSetup; // only for a scene away from the origin
    const core::ShadowSetup* givenSetup = nullptr;
    const core::ShadowSetup& setup() const { return rebasedSetup ? *rebasedSetup : *givenSetup; }
};

// A scene at the world's origin is drawn with the set-up as given (no copy, the same bits).
inline SceneFrame inScene(const core::Vec3& wsOrigin, const core::PerspectiveCamera& wsCamera,
                          const core::ShadowSetup& wsSetup) {
    SceneFrame frame{wsCamera, std::nullopt, &wsSetup};
    if (wsOrigin == core::Vec3(0.0)) return frame;
    frame.camera.wsEye -= wsOrigin;
    frame.rebasedSetup = core::rebased(wsSetup, wsOrigin);
    return frame;
}

} // namespace shadowkit::gl
