#include "shadowkit/scene/animation.h"

#include "shadowkit/core/conventions.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

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

std::optional<NodeMotion> circleAsKeys(const Track& track, const Scene& scene, double chordErrorMetres) {
    if (track.keyframed || track.speed == 0.0 || !(track.radius > 0.0)) return std::nullopt;
    constexpr int kMostKeys = 4096;
    // A chord of angle θ strays r(1 − cos(θ/2)) from its arc at its middle: θ = 2π/N.
    const double halfAngle = std::acos(std::clamp(1.0 - chordErrorMetres / track.radius, -1.0, 1.0));
    int keys = halfAngle > 0.0 ? std::clamp(int(std::ceil(std::numbers::pi / halfAngle)), 16, kMostKeys) : kMostKeys;
    const double loop = 2.0 * std::numbers::pi * track.radius / std::abs(track.speed);
    // The track at every key and at every middle between two: 2N + 1 places, once per N.
    const auto sampled = [&](int n) {
        std::vector<glm::dvec3> at(size_t(2 * n + 1));
        for (int j = 0; j <= 2 * n; ++j)
            at[size_t(j)] = glm::dvec3(trackTransform(track, scene, loop * j / (2.0 * n))[3]);
        return at;
    };
    // The ground the track follows bends where the arc does not (a heightfield's creases): keys
    // twice as dense until every key's height, drawn straight to the next, passes within the same
    // bound of the ground at their middle — within twice it anywhere between them, a crease
    // straying most where it falls in the middle.
    const auto followsGround = [&](const std::vector<glm::dvec3>& at) {
        for (size_t k = 0; k + 2 < at.size(); k += 2)
            if (std::abs(at[k + 1].y - 0.5 * (at[k].y + at[k + 2].y)) > chordErrorMetres) return false;
        return true;
    };
    std::vector<glm::dvec3> at = sampled(keys);
    while (keys < kMostKeys && !followsGround(at)) {
        keys = std::min(2 * keys, kMostKeys);
        at = sampled(keys);
    }
    auto translation = std::make_shared<KeyframeChannel>();
    auto rotation = std::make_shared<KeyframeChannel>();
    for (KeyframeChannel* channel : {translation.get(), rotation.get()}) channel->loopSeconds = loop;
    for (int k = 0; k <= keys; ++k) { // the last key closes the loop where the first began
        const double t = loop * (2 * k) / (2.0 * keys);
        translation->times.push_back(t);
        translation->values.emplace_back(at[size_t(2 * k)], 0.0);
        const double travelled = track.speed / track.radius * t; // as trackTransform turns it
        const glm::dquat turned = glm::angleAxis(-travelled, glm::dvec3(0.0, 1.0, 0.0));
        rotation->times.push_back(t);
        rotation->values.emplace_back(turned.x, turned.y, turned.z, turned.w);
    }
    MotionNode node;
    node.scale = glm::dvec3(track.scale);
    node.translationKeys = std::move(translation);
    node.rotationKeys = std::move(rotation);
    NodeMotion motion;
    motion.chain.push_back(std::move(node));
    return motion;
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
