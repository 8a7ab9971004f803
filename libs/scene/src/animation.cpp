#include "shadowkit/scene/animation.h"

#include "shadowkit/core/conventions.h"

#include <cmath>

namespace shadowkit::scene {

glm::mat4 trackTransform(const Track& track, const Scene& scene, double t) {
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

uint32_t globalInstanceIndex(const Scene& scene, uint32_t batch, uint32_t instance) {
    SK_ASSERT(batch < scene.batches.size() && instance < scene.batches[batch].worldFromObject.size(),
              "globalInstanceIndex(): no such instance");
    size_t first = 0;
    for (uint32_t b = 0; b < batch; ++b) first += scene.batches[b].worldFromObject.size();
    return static_cast<uint32_t>(first + instance);
}

void animate(Scene& scene, double t, std::vector<uint32_t>* moved) {
    std::vector<size_t> batchFirst(scene.batches.size(), 0);
    for (size_t b = 1; b < scene.batches.size(); ++b) batchFirst[b] = batchFirst[b - 1] + scene.batches[b - 1].worldFromObject.size();
    for (const Track& track : scene.tracks) {
        SK_ASSERT(track.batch < scene.batches.size() && track.instance < scene.batches[track.batch].worldFromObject.size(),
                  "animate(): a track names no instance");
        scene.batches[track.batch].worldFromObject[track.instance] = trackTransform(track, scene, t);
        if (moved) moved->push_back(static_cast<uint32_t>(batchFirst[track.batch] + track.instance));
    }
}

} // namespace shadowkit::scene
