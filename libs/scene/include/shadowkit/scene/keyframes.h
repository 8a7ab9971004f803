// Keyframed motion from a file: the nodes above an instance, some of them moved by sampled
// translations, rotations and scales, played as a function of the time t alone (animation.h).
//
// Based on: the glTF 2.0 specification, "Animations" (§3.11) and Appendix C, "Animation
// Sampler Interpolation Modes". Between keys t_k ≤ t < t_{k+1}, with Δ = t_{k+1} − t_k and
// s = (t − t_k) / Δ:
//   STEP         v_k
//   LINEAR       (1 − s)·v_k + s·v_{k+1}; a rotation slerp(q_k, q_{k+1}, s) along the shorter arc
//   CUBICSPLINE  (2s³ − 3s² + 1)·v_k + Δ(s³ − 2s² + s)·b_k + (−2s³ + 3s²)·v_{k+1} + Δ(s³ − s²)·a_{k+1}
//                with b_k the out-tangent of key k and a_{k+1} the in-tangent of key k+1; a
//                rotation normalised after
// Before the first key a channel holds its first value and after the last its last (§3.11:
// "clamped"). Each of a file's animations loops over its own length — its latest key — so a
// camera path longer than a clip sees it again, as glTF viewers play clips; all play at once.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace shadowkit::scene {

// One sampler driving one property of one node.
struct KeyframeChannel {
    enum class Interpolation { Step, Linear, CubicSpline };
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times; // seconds, increasing, at least one
    // A translation or scale in xyz, a rotation as a unit quaternion (x, y, z, w): one per key,
    // three per key for CUBICSPLINE (in-tangent, value, out-tangent).
    std::vector<glm::dvec4> values;
    double loopSeconds = 0.0; // its animation's length: t is taken modulo it (> 0), else clamped

    // The property at time t (seconds); a rotation comes back unit.
    glm::dvec4 at(double t, bool rotation) const;
};

// One node of the chain above an instance: fixed, or its TRS with the channels that move it.
struct MotionNode {
    std::optional<glm::dmat4> fixed; // a node no channel moves (several such folded into one)
    glm::dvec3 translation{0.0};     // the rest pose, where no channel moves that property
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
    std::shared_ptr<const KeyframeChannel> translationKeys, rotationKeys, scaleKeys;

    glm::dmat4 parentFromNodeAt(double t) const; // T · R · S, as glTF composes a node
};

// Where an instance stands at time t: sceneFromRoot · Π parentFromNode(t) · nodeFromObject.
struct NodeMotion {
    glm::dmat4 sceneFromRoot{1.0};  // the loader's origin shift and up-axis turn
    std::vector<MotionNode> chain;  // root first, down to the instance's node
    glm::dmat4 nodeFromObject{1.0}; // below the node: a GPU-instancing transform, a mesh's move to its origin

    glm::dmat4 sceneFromObjectAt(double t) const;
};

} // namespace shadowkit::scene
