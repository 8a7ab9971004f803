// A glTF file's animations (glTF 2.0 §3.11) read as keyframed motion of its nodes
// (gltf_animation.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/scene/keyframes.h"

#include <tiny_gltf.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

// The channels that move one node, from whichever animation first moves each property.
struct NodeChannels {
    std::shared_ptr<const KeyframeChannel> translation, rotation, scale;
};
using AnimatedNodes = std::map<int, NodeChannels>; // node index -> its channels

/// Every animation's translation, rotation and scale channels, checked. Shadows play what they
/// can and never refuse a scene for its animations: a channel that cannot be played — a morph
/// weight, a skin's joint, a bad sampler or accessor, a property another animation already
/// moves — is left at rest, with one line per animation in `warnings`.
AnimatedNodes readAnimations(const tinygltf::Model& model, const std::string& file, std::vector<std::string>& warnings);

/// The motion of an instance whose node is the last of `path` (node indices, root first), or
/// nullopt when no node of the path is animated. Its sceneFromRoot and nodeFromObject are the
/// identity: the loader sets them.
std::optional<NodeMotion> motionAlong(const tinygltf::Model& model, const std::vector<int>& path,
                                      const AnimatedNodes& animated);

} // namespace shadowkit::scene::formats
