// Scenes and a camera the truth tests share: a ground slab with one caster over it, seen from
// above and behind.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdint>

namespace shadowkit::test {

constexpr uint32_t kGroundId = 1; // surface id of the ground (instance 0)

// A ground slab with its top at y = 0 and one caster mesh placed by `worldFromCaster`.
inline scene::Scene groundAnd(scene::Mesh caster, const glm::mat4& worldFromCaster) {
    scene::Scene s;
    scene::Mesh ground;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, 0}), {30, 0.5f, 30}, glm::vec3(0.8f));
    ground.computeBounds();
    caster.computeBounds();
    s.meshes = {ground, caster};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {worldFromCaster}, false}};
    return s;
}

inline core::PerspectiveCamera cameraLookingAtOrigin() {
    core::PerspectiveCamera cam;
    cam.wsEye = {3, 9, 14};
    cam.wsDirection = core::Vec3(-1.5, 0, -1) - cam.wsEye;
    cam.fovYDegrees = 50;
    cam.aspect = 4.0 / 3.0;
    cam.zNear = 0.5;
    cam.zFar = 80;
    return cam;
}

} // namespace shadowkit::test
