// Animation of a scene's dynamic instances. Every tracked instance (Scene::tracks) is placed
// as a function of the time t alone, so any frame of a sequence can be rendered, evaluated or
// tested by itself, and a renderer that moves instances by the list animate() returns never
// keeps a stale transform.
#pragma once

#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace shadowkit::scene {

// The instance's transform at time t (seconds): a keyframed track's where its keys put it
// (keyframes.h); any other's on the circle at compass angle
// phase + speed / radius · t, `lift` metres above the ground there (Scene::groundHeightAt),
// turned about +Y by the angle travelled since t = 0 (so t = 0 is the unturned placement).
glm::mat4 trackTransform(const Track& track, const Scene& scene, double t);

// A circling track (not keyframed) as the keys a file can carry, so that an exported scene's
// movers play on in other tools and when loaded back: one loop of 2πr / |speed| seconds, LINEAR
// translations at keys close enough that the chord between two strays at most
// `chordErrorMetres` from the arc (N = ⌈π / acos(1 − e / r)⌉ keys, 16 to 4,096), doubled until
// the heights between keys pass as close to the ground the track follows at their middles, and
// LINEAR rotations, which slerp turns exactly as the track does (a constant rate about +Y).
// nullopt for a keyframed track or one that stands still (speed 0).
std::optional<NodeMotion> circleAsKeys(const Track& track, const Scene& scene, double chordErrorMetres = 0.01);

// Places every tracked instance at time t and poses every deformed mesh there
// (Scene::deformations). `moved`, when given, receives the global instance index
// (Scene::globalIndex) of each instance it placed or reshaped.
void animate(Scene& scene, double t, std::vector<uint32_t>* moved = nullptr);

} // namespace shadowkit::scene
