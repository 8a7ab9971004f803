// A glTF file's animations as keyframed motion of its nodes, and that motion written back.
//
// Based on: the glTF 2.0 specification, "Animations" (§3.11): a channel names a sampler and a
// target (a node and one of its properties); a sampler's input accessor holds the keys' times
// (SCALAR float, seconds, increasing), its output the values (VEC3 translations and scales,
// VEC4 rotation quaternions — float or normalised integers —, three per key for CUBICSPLINE).
// A node an animation targets must be written as TRS, not as a matrix. How the keys are played:
// keyframes.h.
//
// Morph weights (SCALAR, one a target a key, three for CUBICSPLINE: the key's in-tangents, values
// and out-tangents, each a target long) and a skin's joints deform a mesh: they pose the file
// once, at the moment asked, rather than play (gltf_animation.h). What shadowkit cannot use
// stays at rest with a warning, never a refused scene — among it a property a second animation
// also moves: a character's clips (walk, run) all move the same nodes, and playing them at once
// would be neither; the first animation that moves a property plays it.
#include "gltf_animation.h"

#include "gltf_accessor.h"
#include "gltf_materials.h"
#include "gltf_pose.h"
#include "scene_formats.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string_view>
#include <tuple>

namespace shadowkit::scene::formats {

namespace {

// Keys read from one file in all: a hostile file can point a million channels at one long
// accessor, and each channel holds its own copy.
constexpr size_t kMaxKeysPerFile = size_t(1) << 24;
// Warning lines about a file's animations, the last of them a count of the rest.
constexpr size_t kMaxAnimationLines = 4;

enum class Property { Translation, Rotation, Scale, Weights };

std::optional<Property> propertyNamed(const std::string& path) {
    if (path == "translation") return Property::Translation;
    if (path == "rotation") return Property::Rotation;
    if (path == "scale") return Property::Scale;
    if (path == "weights") return Property::Weights;
    return std::nullopt;
}

// How many morph targets the node's mesh has (glTF asks every primitive of a mesh for as many).
size_t morphTargetsOf(const tinygltf::Model& model, int node) {
    const int mesh = model.nodes[size_t(node)].mesh;
    if (mesh < 0 || size_t(mesh) >= model.meshes.size() || model.meshes[size_t(mesh)].primitives.empty()) return 0;
    return model.meshes[size_t(mesh)].primitives.front().targets.size();
}

// One sampler's keys for `property`, checked; the reason it cannot be used otherwise. Weights
// come `targets` a key, all in x, target after target within each key.
core::Result<KeyframeChannel> readSampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler,
                                          Property property, size_t targets, const std::string& where,
                                          size_t& keysRead) {
    KeyframeChannel channel;
    if (sampler.interpolation == "STEP")
        channel.interpolation = KeyframeChannel::Interpolation::Step;
    else if (sampler.interpolation == "CUBICSPLINE")
        channel.interpolation = KeyframeChannel::Interpolation::CubicSpline;
    else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR")
        channel.interpolation = KeyframeChannel::Interpolation::Linear;
    else
        return core::makeError(where + ": unknown interpolation '" + printable(sampler.interpolation) + "'");

    auto input = AccessorReader::open(model, sampler.input, where + " input");
    if (!input) return input.errorInfo();
    const tinygltf::Accessor& inputAccessor = model.accessors[size_t(sampler.input)];
    if (inputAccessor.type != TINYGLTF_TYPE_SCALAR || inputAccessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        return core::makeError(where + ": its times are not a SCALAR float accessor");
    const size_t keys = input->count();
    if (keys == 0) return core::makeError(where + ": no keys");
    const bool cubic = channel.interpolation == KeyframeChannel::Interpolation::CubicSpline;
    const bool weights = property == Property::Weights;
    const size_t valuesPerKey = (cubic ? 3 : 1) * (weights ? targets : 1);

    auto output = AccessorReader::open(model, sampler.output, where + " output");
    if (!output) return output.errorInfo();
    const int wantedType = property == Property::Rotation ? TINYGLTF_TYPE_VEC4
                           : weights                      ? TINYGLTF_TYPE_SCALAR
                                                          : TINYGLTF_TYPE_VEC3;
    if (model.accessors[size_t(sampler.output)].type != wantedType)
        return core::makeError(where + ": its values are not " +
                               (property == Property::Rotation ? "VEC4 quaternions"
                                : weights                      ? "SCALAR weights"
                                                               : "VEC3 vectors"));
    if (output->count() != keys * valuesPerKey)
        return core::makeError(where + ": " + std::to_string(output->count()) + " values for " + std::to_string(keys) +
                               " keys" + (weights ? " of " + std::to_string(targets) + " morph target(s)" : "") +
                               (cubic ? " (CUBICSPLINE: three a key)" : ""));
    keysRead += keys * (1 + valuesPerKey);
    if (keysRead > kMaxKeysPerFile)
        return core::makeError(where + ": more keys than shadowkit reads from one file (2^24)");

    channel.times.resize(keys);
    for (size_t k = 0; k < keys; ++k) {
        const double t = input->get(k, 0);
        if (!std::isfinite(t)) return core::makeError(where + ": key " + std::to_string(k) + "'s time is not finite");
        if (k > 0 && t < channel.times[k - 1])
            return core::makeError(where + ": key " + std::to_string(k) + "'s time comes before the key before it");
        channel.times[k] = t;
    }
    channel.values.resize(output->count());
    for (size_t v = 0; v < output->count(); ++v) {
        const glm::dvec4 value(output->get(v, 0), weights ? 0.0 : output->get(v, 1), weights ? 0.0 : output->get(v, 2),
                               property == Property::Rotation ? output->get(v, 3) : 0.0);
        if (!std::isfinite(value.x + value.y + value.z + value.w))
            return core::makeError(where + ": value " + std::to_string(v) + " is not finite");
        channel.values[v] = value;
    }
    return channel;
}

// A weights channel (every target in turn within a key) as one channel per target.
std::vector<KeyframeChannel> perTarget(const KeyframeChannel& all, size_t targets) {
    const bool cubic = all.interpolation == KeyframeChannel::Interpolation::CubicSpline;
    std::vector<KeyframeChannel> out(targets);
    for (size_t target = 0; target < targets; ++target) {
        KeyframeChannel& one = out[target];
        one.interpolation = all.interpolation;
        one.times = all.times;
        one.loopSeconds = all.loopSeconds;
        for (size_t k = 0; k < all.times.size(); ++k)
            for (size_t part = 0; part < (cubic ? 3u : 1u); ++part) // in-tangent, value, out-tangent
                one.values.push_back(all.values[(k * (cubic ? 3 : 1) + part) * targets + target]);
    }
    return out;
}

} // namespace

FileAnimations readAnimations(const tinygltf::Model& model, const NodeTrees& trees, const std::string& file,
                              std::vector<std::string>& warnings) {
    // A skin's joints and every node above one: a skinned mesh's vertices follow them all.
    const std::vector<int>& parentOf = trees.parentOf;
    std::set<int> joints;
    for (const tinygltf::Skin& skin : model.skins)
        for (int node : skin.joints) // up to a root, or to a node already met (NodeTrees: the walk ends)
            while (node >= 0 && size_t(node) < model.nodes.size() && joints.insert(node).second)
                node = parentOf[size_t(node)];
    FileAnimations out;
    std::vector<std::string> lines;                     // a line an animation that has something to say
    std::map<std::pair<int, Property>, size_t> movedBy; // node and property -> the animation using it
    size_t keysRead = 0;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& animation = model.animations[a];
        const std::string named = file + ": animation " + std::to_string(a) +
                                  (animation.name.empty() ? "" : " '" + printable(animation.name) + "'");
        // Read first, then given their animation's length: each loops over its own.
        struct Read {
            int node;
            Property property;
            KeyframeChannel keys;
            bool posed; // a joint's (or a node's above one) or weights: deforms a mesh
        };
        std::vector<Read> read;
        std::string firstProblem;
        size_t atRest = 0;
        const auto leave = [&](const std::string& why) {
            if (atRest++ == 0) firstProblem = why;
        };
        for (size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = animation.channels[c];
            const std::string where = "channel " + std::to_string(c);
            const int node = ch.target_node;
            if (node < 0 || size_t(node) >= model.nodes.size()) {
                leave(where + " targets no node");
                continue;
            }
            const std::optional<Property> property = propertyNamed(ch.target_path);
            if (!property) {
                leave(where + " moves '" + printable(ch.target_path) + "', which shadowkit does not play");
                continue;
            }
            const bool weights = *property == Property::Weights;
            const size_t targets = weights ? morphTargetsOf(model, node) : 0;
            if (weights && targets == 0) {
                leave(where + " moves the morph weights of node " + std::to_string(node) +
                      ", whose mesh has no morph targets");
                continue;
            }
            if (!weights && model.nodes[size_t(node)].matrix.size() == 16) {
                leave(where + " targets node " + std::to_string(node) + ", written as a matrix (glTF asks for TRS)");
                continue;
            }
            if (const auto it = movedBy.find({node, *property}); it != movedBy.end() && it->second != a) {
                leave(where + " moves what animation " + std::to_string(it->second) +
                      " moves (the first animation that moves a property plays it)");
                continue;
            }
            if (ch.sampler < 0 || size_t(ch.sampler) >= animation.samplers.size()) {
                leave(where + " names no sampler");
                continue;
            }
            auto keys = readSampler(model, animation.samplers[size_t(ch.sampler)], *property, targets,
                                    where + " (sampler " + std::to_string(ch.sampler) + ")", keysRead);
            if (!keys) {
                leave(keys.error());
                continue;
            }
            movedBy[{node, *property}] = a;
            read.push_back({node, *property, std::move(*keys), weights || joints.count(node) > 0});
        }
        double length = 0.0;
        for (const Read& r : read) length = std::max(length, r.keys.times.back());
        for (Read& r : read) {
            r.keys.loopSeconds = length;
            if (r.property == Property::Weights) {
                auto& channels = out.posed.weights[r.node];
                for (KeyframeChannel& one : perTarget(r.keys, morphTargetsOf(model, r.node)))
                    channels.push_back(std::make_shared<const KeyframeChannel>(std::move(one)));
            } else {
                NodeChannels& channels = (r.posed ? out.posed.joints : out.played)[r.node];
                (r.property == Property::Translation ? channels.translation
                 : r.property == Property::Rotation  ? channels.rotation
                                                     : channels.scale) =
                    std::make_shared<const KeyframeChannel>(std::move(r.keys));
            }
        }
        if (atRest > 0)
            lines.push_back(named + ": " + firstProblem +
                            (atRest > 1 ? " (and " + std::to_string(atRest - 1) + " more channel(s))" : "") +
                            "; left at rest");
    }
    // A character's clips (idle, walk, run, …) often number dozens, each moving what the first
    // moves: the first few lines say what happens, a count says the rest.
    const size_t shown = lines.size() > kMaxAnimationLines ? kMaxAnimationLines - 1 : lines.size();
    warnings.insert(warnings.end(), lines.begin(), lines.begin() + std::ptrdiff_t(shown));
    if (shown < lines.size())
        warnings.push_back(file + ": and " + std::to_string(lines.size() - shown) +
                           " more animations with channels left at rest, as above");
    // Whether a channel poses a node or one above it, each node settled once (a file may hold a
    // long chain of joints): walk up to a settled node or a root, then settle the walk.
    std::vector<int8_t> posedFromAbove(model.nodes.size(), -1);
    std::vector<int> walk;
    const auto isPosed = [&](int node) {
        for (walk.clear(); node >= 0 && posedFromAbove[size_t(node)] < 0; node = parentOf[size_t(node)])
            walk.push_back(node);
        bool posed = node >= 0 && posedFromAbove[size_t(node)] > 0;
        for (auto it = walk.rbegin(); it != walk.rend(); ++it)
            posedFromAbove[size_t(*it)] = (posed = posed || out.posed.joints.count(*it) > 0) ? 1 : 0;
        return posed;
    };
    for (size_t skin = 0; skin < model.skins.size(); ++skin)
        for (int joint : model.skins[skin].joints)
            if (joint >= 0 && size_t(joint) < model.nodes.size() && isPosed(joint)) out.posed.skins.insert(int(skin));
    return out;
}

void poseNodes(tinygltf::Model& model, const PoseKeys& keys, double t) {
    for (const auto& [index, channels] : keys.joints) {
        tinygltf::Node& node = model.nodes[size_t(index)];
        const auto set = [&](std::vector<double>& property, const std::shared_ptr<const KeyframeChannel>& channel,
                             bool rotation) {
            if (!channel) return;
            const glm::dvec4 v = channel->at(t, rotation);
            property.assign({v.x, v.y, v.z});
            if (rotation) property.push_back(v.w);
        };
        set(node.translation, channels.translation, false);
        set(node.rotation, channels.rotation, true);
        set(node.scale, channels.scale, false);
    }
    for (const auto& [index, channels] : keys.weights) {
        tinygltf::Node& node = model.nodes[size_t(index)];
        node.weights.resize(channels.size());
        for (size_t target = 0; target < channels.size(); ++target)
            node.weights[target] = channels[target]->at(t, false).x;
    }
}

std::optional<NodeMotion> motionAlong(const tinygltf::Model& model, const std::vector<int>& path,
                                      const AnimatedNodes& animated) {
    bool moves = false;
    for (int node : path) moves = moves || animated.count(node);
    if (!moves) return std::nullopt;
    NodeMotion motion;
    for (int index : path) {
        const tinygltf::Node& node = model.nodes[size_t(index)];
        const auto it = animated.find(index);
        if (it == animated.end()) { // fixed: folded into the fixed node before it, if any
            const glm::dmat4 local = nodeLocalMatrix(node);
            if (!motion.chain.empty() && motion.chain.back().fixed)
                *motion.chain.back().fixed *= local;
            else
                motion.chain.push_back({.fixed = local});
            continue;
        }
        MotionNode moving;
        if (node.translation.size() == 3)
            moving.translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
        if (node.rotation.size() == 4) {
            const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            const double length = glm::length(q);
            if (length > 0.0 && std::isfinite(length)) moving.rotation = q / length;
        }
        if (node.scale.size() == 3) moving.scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
        moving.translationKeys = it->second.translation;
        moving.rotationKeys = it->second.rotation;
        moving.scaleKeys = it->second.scale;
        motion.chain.push_back(std::move(moving));
    }
    return motion;
}

namespace {

std::vector<double> columnMajor(const glm::dmat4& m) {
    std::vector<double> out;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out.push_back(m[c][r]);
    return out;
}

const char* interpolationName(KeyframeChannel::Interpolation interpolation) {
    switch (interpolation) {
    case KeyframeChannel::Interpolation::Step:
        return "STEP";
    case KeyframeChannel::Interpolation::CubicSpline:
        return "CUBICSPLINE";
    case KeyframeChannel::Interpolation::Linear:
        break;
    }
    return "LINEAR";
}

} // namespace

int AnimationWriter::samplerOf(const KeyframeChannel& keys, bool rotation, tinygltf::Animation& animation) {
    if (const auto it = m_samplers.find(&keys); it != m_samplers.end()) return it->second;
    // Each channel holds its own times (readSampler), so its sampler, cached above, is their one reader.
    const std::vector<float> times(keys.times.begin(), keys.times.end());
    const int input =
        m_appendFloats(times, TINYGLTF_TYPE_SCALAR, times.size(), {keys.times.front()}, {keys.times.back()});
    // A rotation's values are quaternions (x, y, z, w); a translation's and a scale's, xyz.
    std::vector<float> values;
    for (const glm::dvec4& v : keys.values)
        for (int c = 0; c < (rotation ? 4 : 3); ++c) values.push_back(float(v[c]));
    tinygltf::AnimationSampler sampler;
    sampler.input = input;
    sampler.output =
        m_appendFloats(values, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, keys.values.size(), {}, {});
    sampler.interpolation = interpolationName(keys.interpolation);
    animation.samplers.push_back(std::move(sampler));
    return m_samplers[&keys] = int(animation.samplers.size() - 1);
}

int AnimationWriter::appendMotion(const NodeMotion& motion, int mesh) {
    // Bottom up, each node the child of the next.
    tinygltf::Node drawing;
    drawing.mesh = mesh;
    if (motion.nodeFromObject != glm::dmat4(1.0)) drawing.matrix = columnMajor(motion.nodeFromObject);
    m_model.nodes.push_back(std::move(drawing));
    int child = int(m_model.nodes.size() - 1);
    for (auto it = motion.chain.rbegin(); it != motion.chain.rend(); ++it) {
        tinygltf::Node node;
        node.children = {child};
        if (it->fixed) {
            if (*it->fixed != glm::dmat4(1.0)) node.matrix = columnMajor(*it->fixed);
        } else {
            node.translation = {it->translation.x, it->translation.y, it->translation.z};
            node.rotation = {it->rotation.x, it->rotation.y, it->rotation.z, it->rotation.w};
            node.scale = {it->scale.x, it->scale.y, it->scale.z};
        }
        m_model.nodes.push_back(std::move(node));
        child = int(m_model.nodes.size() - 1);
        const std::pair<const std::shared_ptr<const KeyframeChannel>*, const char*> moved[] = {
            {&it->translationKeys, "translation"}, {&it->rotationKeys, "rotation"}, {&it->scaleKeys, "scale"}};
        for (const auto& [keys, path] : moved) {
            if (!*keys) continue;
            tinygltf::Animation& animation = m_animations[(*keys)->loopSeconds];
            tinygltf::AnimationChannel channel;
            channel.sampler = samplerOf(**keys, std::string_view(path) == "rotation", animation);
            channel.target_node = child;
            channel.target_path = path;
            animation.channels.push_back(std::move(channel));
        }
    }
    tinygltf::Node top;
    top.children = {child};
    if (motion.sceneFromRoot != glm::dmat4(1.0)) top.matrix = columnMajor(motion.sceneFromRoot);
    m_model.nodes.push_back(std::move(top));
    return int(m_model.nodes.size() - 1);
}

void AnimationWriter::appendWeights(int node, const std::vector<std::shared_ptr<const KeyframeChannel>>& keys) {
    if (keys.empty() || !keys.front()) return;
    const KeyframeChannel& first = *keys.front();
    const size_t targets = keys.size();
    const size_t perKey = first.interpolation == KeyframeChannel::Interpolation::CubicSpline ? 3 : 1;
    // glTF's layout: per key (and per in-tangent, value, out-tangent) every target's weight.
    std::vector<float> values(first.times.size() * perKey * targets, 0.0f);
    for (size_t t = 0; t < targets; ++t)
        for (size_t i = 0; keys[t] && i < keys[t]->values.size() && i * targets + t < values.size(); ++i)
            values[i * targets + t] = float(keys[t]->values[i].x);
    tinygltf::Animation& animation = m_animations[first.loopSeconds];
    const std::vector<float> times(first.times.begin(), first.times.end());
    tinygltf::AnimationSampler sampler;
    sampler.input =
        m_appendFloats(times, TINYGLTF_TYPE_SCALAR, times.size(), {first.times.front()}, {first.times.back()});
    sampler.output = m_appendFloats(values, TINYGLTF_TYPE_SCALAR, values.size(), {}, {});
    sampler.interpolation = interpolationName(first.interpolation);
    animation.samplers.push_back(std::move(sampler));
    tinygltf::AnimationChannel channel;
    channel.sampler = int(animation.samplers.size() - 1);
    channel.target_node = node;
    channel.target_path = "weights";
    animation.channels.push_back(std::move(channel));
}

void AnimationWriter::finish() {
    for (auto& [length, animation] : m_animations) m_model.animations.push_back(std::move(animation));
    m_animations.clear();
    m_samplers.clear();
}

} // namespace shadowkit::scene::formats
