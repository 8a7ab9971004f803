#include "shadowkit/scene/animation.h"

#include "shadowkit/core/conventions.h"

#include <cmath>

namespace shadowkit::scene {

glm::mat4 trackTransform(const Track& track, const Scene& scene, double t) {
    if (track.keyframed) return glm::mat4(track.keyframed->sceneFromObjectAt(t));
    SK_ASSERT(track.radius > 0.0, "trackTransform(): a track's radius must be positive");
    // Compass angle: 0 = -Z, increasing towards +X (conventions.h), so a positive speed
    // runs clockwise seen from above.
    const double travelled = track.speed / track.radius * t;
    const double angle = track.phase + travelled;
    const double x = track.centreX + track.radius * std::sin(angle);
    const double z = track.centreZ - track.radius * std::cos(angle);
    const double y = scene.groundHeightAt(x, z) + track.lift;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(float(x), float(y), float(z)));
    // Turning clockwise seen from above is a negative rotation about +Y.
    m = glm::rotate(m, static_cast<float>(-travelled), glm::vec3(0, 1, 0));
    return glm::scale(m, glm::vec3(track.scale));
}

void animate(Scene& scene, double t, std::vector<uint32_t>* moved) {
    for (const Track& track : scene.tracks) {
        const uint32_t global = scene.globalIndex({track.batch, track.instance}); // asserts the instance exists
        scene.batches[track.batch].worldFromObject[track.instance] = trackTransform(track, scene, t);
        if (moved) moved->push_back(global);
    }
    // A deformed mesh changes its shape, not its placement: its instances move by their bounds.
    for (const MeshDeformation& deformation : scene.deformations) {
        const MeshBatch& batch = scene.batches[deformation.batch];
        deformation.poseInto(scene.meshes[batch.mesh], t);
        if (moved)
            for (uint32_t i = 0; i < batch.worldFromObject.size(); ++i)
                moved->push_back(scene.globalIndex({deformation.batch, i}));
    }
}

} // namespace shadowkit::scene
