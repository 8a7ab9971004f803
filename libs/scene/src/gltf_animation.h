// A glTF file's animations (glTF 2.0 §3.11) read as keyframed motion of its nodes, and
// written back (gltf_animation.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/scene/keyframes.h"

#include "gltf_nodes.h"

#include <tiny_gltf.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

// The channels that move one node, from whichever animation first moves each property.
struct NodeChannels {
    std::shared_ptr<const KeyframeChannel> translation, rotation, scale;
};
using AnimatedNodes = std::map<int, NodeChannels>; // node index -> its channels

// Channels that deform meshes: a skin's joints (and the nodes above them), which place a skin's
// vertices, and morph weights (deformation.h). Played as the others are; apart because the meshes
// they move are reshaped, not only placed (Scene::deformations), and because the loader poses the
// file's nodes with them at LoadOptions::poseSeconds before it reads a mesh.
struct PoseKeys {
    AnimatedNodes joints; // a joint node, or a node above one -> its channels
    // A node -> a channel per morph target of its mesh, each weight in x.
    std::map<int, std::vector<std::shared_ptr<const KeyframeChannel>>> weights;
    std::set<int> skins; // the skins whose joints (or nodes above them) some channel moves
};

struct FileAnimations {
    AnimatedNodes played; // moving rigid instances, frame by frame (scene::animate)
    PoseKeys posed;
};

/// Every animation's translation, rotation, scale and weight channels, checked. Shadows play
/// what they can and never refuse a scene for its animations: a channel that cannot be used —
/// a node written as a matrix, a bad sampler or accessor, a property another animation already
/// moves — is left at rest, with one line per animation in `warnings`.
FileAnimations readAnimations(const tinygltf::Model& model, const NodeTrees& trees, const std::string& file,
                              std::vector<std::string>& warnings);

/// Writes the posed channels' values at time t into the model's nodes (TRS and weights), so that
/// everything read from the nodes after — joint matrices, morph targets, the instances below a
/// joint — stands in that pose.
void poseNodes(tinygltf::Model& model, const PoseKeys& keys, double t);

/// The motion of an instance whose node is the last of `path` (node indices, root first), or
/// nullopt when no node of the path is animated. Its sceneFromRoot and nodeFromObject are the
/// identity: the loader sets them.
std::optional<NodeMotion> motionAlong(const tinygltf::Model& model, const std::vector<int>& path,
                                      const AnimatedNodes& animated);

/// Floats appended to the file's buffer as an accessor of `count` elements of glTF `type`
/// (`min`/`max` given for times, as glTF asks of a sampler's input); returns its index.
using FloatAccessorAppender = std::function<int(const std::vector<float>& data, int type, size_t count,
                                                std::vector<double> min, std::vector<double> max)>;

/// Writes keyframed instances back as glTF: the nodes of each one's chain, its moving nodes'
/// channels in animations — one per loop length, so each plays over the length it had when read —
/// and a sampler per channel shared by every instance the channel moves.
class AnimationWriter {
public:
    AnimationWriter(tinygltf::Model& model, FloatAccessorAppender appendFloats)
        : m_model(model), m_appendFloats(std::move(appendFloats)) {}

    /// The nodes placing `mesh` by `motion`, top first: sceneFromRoot, the chain, nodeFromObject
    /// with the mesh; returns the top node's index.
    int appendMotion(const NodeMotion& motion, int mesh);
    /// Node `node`'s morph weights moved by `keys`, one channel per morph target as the reader
    /// splits them (the same times, interpolation and loop): written back as one weights channel.
    void appendWeights(int node, const std::vector<std::shared_ptr<const KeyframeChannel>>& keys);
    /// Moves the animations written so far into the model.
    void finish();

private:
    int samplerOf(const KeyframeChannel& keys, bool rotation, tinygltf::Animation& animation);

    tinygltf::Model& m_model;
    FloatAccessorAppender m_appendFloats;
    std::map<double, tinygltf::Animation> m_animations; // by loop length
    std::map<const KeyframeChannel*, int> m_samplers;   // within its animation
};

} // namespace shadowkit::scene::formats
