// A glTF file's animations as keyframed motion of its nodes, and that motion written back.
//
// Based on: the glTF 2.0 specification, "Animations" (§3.11): a channel names a sampler and a
// target (a node and one of its properties); a sampler's input accessor holds the keys' times
// (SCALAR float, seconds, increasing), its output the values (VEC3 translations and scales,
// VEC4 rotation quaternions — float or normalised integers —, three per key for CUBICSPLINE).
// A node an animation targets must be written as TRS, not as a matrix. How the keys are played:
// keyframes.h.
//
// What shadowkit does not play stays at rest with a warning, never a refused scene: morph
// weights (the mesh keeps its rest weights, gltf_pose.cpp), the joints of a skin (a skinned
// mesh is posed once at load), and a property a second animation also moves — a character's
// clips (walk, run) all move the same nodes, and playing them at once would be neither; the
// first animation that moves a property plays it.
#include "gltf_animation.h"

#include "gltf_accessor.h"
#include "gltf_materials.h"
#include "gltf_pose.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string_view>
#include <tuple>

namespace shadowkit::scene::formats {

namespace {

// Keys read from one file in all: a hostile file can point a million channels at one long
// accessor, and each channel holds its own copy.
constexpr size_t kMaxKeysPerFile = size_t(1) << 24;

enum class Property { Translation, Rotation, Scale };

std::optional<Property> propertyNamed(const std::string& path) {
    if (path == "translation") return Property::Translation;
    if (path == "rotation") return Property::Rotation;
    if (path == "scale") return Property::Scale;
    return std::nullopt;
}

// One sampler's keys for `property`, checked; the reason it cannot be played otherwise.
core::Result<KeyframeChannel> readSampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler,
                                          Property property, const std::string& where, size_t& keysRead) {
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
    const size_t valuesPerKey = cubic ? 3 : 1;

    auto output = AccessorReader::open(model, sampler.output, where + " output");
    if (!output) return output.errorInfo();
    const int wantedType = property == Property::Rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
    if (model.accessors[size_t(sampler.output)].type != wantedType)
        return core::makeError(where + ": its values are not " +
                               (property == Property::Rotation ? "VEC4 quaternions" : "VEC3 vectors"));
    if (output->count() != keys * valuesPerKey)
        return core::makeError(where + ": " + std::to_string(output->count()) + " values for " + std::to_string(keys) +
                               " keys" + (cubic ? " (CUBICSPLINE: three a key)" : ""));
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
        const glm::dvec4 value(output->get(v, 0), output->get(v, 1), output->get(v, 2),
                               property == Property::Rotation ? output->get(v, 3) : 0.0);
        if (!std::isfinite(value.x + value.y + value.z + value.w))
            return core::makeError(where + ": value " + std::to_string(v) + " is not finite");
        channel.values[v] = value;
    }
    return channel;
}

} // namespace

AnimatedNodes readAnimations(const tinygltf::Model& model, const std::string& file,
                             std::vector<std::string>& warnings) {
    std::set<int> joints;
    for (const tinygltf::Skin& skin : model.skins) joints.insert(skin.joints.begin(), skin.joints.end());
    AnimatedNodes animated;
    std::map<std::pair<int, Property>, size_t> movedBy; // node and property -> the animation playing it
    size_t keysRead = 0;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& animation = model.animations[a];
        const std::string named = file + ": animation " + std::to_string(a) +
                                  (animation.name.empty() ? "" : " '" + printable(animation.name) + "'");
        // Read first, then given their animation's length: each loops over its own.
        std::vector<std::tuple<int, Property, KeyframeChannel>> played;
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
                leave(where + " moves " +
                      (ch.target_path == "weights" ? std::string("morph weights")
                                                   : "'" + printable(ch.target_path) + "'") +
                      ", which shadowkit does not play");
                continue;
            }
            if (joints.count(node)) {
                leave(where + " moves a skin's joint: skinned meshes stand in their rest pose");
                continue;
            }
            if (model.nodes[size_t(node)].matrix.size() == 16) {
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
            auto keys = readSampler(model, animation.samplers[size_t(ch.sampler)], *property,
                                    where + " (sampler " + std::to_string(ch.sampler) + ")", keysRead);
            if (!keys) {
                leave(keys.error());
                continue;
            }
            movedBy[{node, *property}] = a;
            played.emplace_back(node, *property, std::move(*keys));
        }
        double length = 0.0;
        for (const auto& [node, property, keys] : played) length = std::max(length, keys.times.back());
        for (auto& [node, property, keys] : played) {
            keys.loopSeconds = length;
            auto shared = std::make_shared<const KeyframeChannel>(std::move(keys));
            NodeChannels& channels = animated[node];
            (property == Property::Translation ? channels.translation
             : property == Property::Rotation  ? channels.rotation
                                               : channels.scale) = std::move(shared);
        }
        if (atRest > 0)
            warnings.push_back(named + ": " + firstProblem +
                               (atRest > 1 ? " (and " + std::to_string(atRest - 1) + " more channel(s))" : "") +
                               "; left at rest");
    }
    return animated;
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

void AnimationWriter::finish() {
    for (auto& [length, animation] : m_animations) m_model.animations.push_back(std::move(animation));
    m_animations.clear();
    m_samplers.clear();
}

} // namespace shadowkit::scene::formats
