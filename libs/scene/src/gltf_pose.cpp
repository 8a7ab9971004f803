// glTF nodes, and what deforms a mesh read from the file: its morph targets and its skin.
//
// Based on: the glTF 2.0 specification, "Morph Targets" (§3.7.2.2), "Skins" (§3.7.3) and "Skinned
// Mesh Attributes" (§3.7.3.3); the formulas, and how a deformation is posed at any time, are in
// scene/deformation.h. Read here: the targets' moves, every JOINTS_n / WEIGHTS_n set (weights
// divided by their sum: the specification asks for a sum of 1, exporters round), and each
// joint's chain of nodes with the keys that move it, so a skin plays as its joints move.
#include "gltf_pose.h"

#include "gltf_accessor.h"
#include "scene_formats.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>

namespace shadowkit::scene::formats {

glm::dmat4 nodeLocalMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 m;
        std::copy(node.matrix.begin(), node.matrix.end(), glm::value_ptr(m));
        return m;
    }
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
        m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
        m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

std::vector<glm::dmat4> nodeGlobalTransforms(const tinygltf::Model& model, const NodeTrees& trees) {
    const size_t n = model.nodes.size();
    const std::vector<int>& parentOf = trees.parentOf;
    // Roots first, then each child after its parent: an explicit stack, as a file's trees may be
    // as deep as it is long.
    std::vector<glm::dmat4> global(n, glm::dmat4(1.0));
    std::vector<size_t> stack;
    for (size_t node = 0; node < n; ++node)
        if (parentOf[node] < 0) stack.push_back(node);
    while (!stack.empty()) {
        const size_t node = stack.back();
        stack.pop_back();
        const glm::dmat4 parent = parentOf[node] < 0 ? glm::dmat4(1.0) : global[size_t(parentOf[node])];
        global[node] = parent * nodeLocalMatrix(model.nodes[node]);
        for (int child : model.nodes[node].children)
            if (child >= 0 && size_t(child) < n) stack.push_back(size_t(child));
    }
    return global;
}

core::Result<SkinJoints> readSkinJoints(const tinygltf::Model& model, const NodeTrees& trees, int skinIndex,
                                        const AnimatedNodes& moving, double t, const std::string& where) {
    SkinJoints out;
    const tinygltf::Skin& skin = model.skins[size_t(skinIndex)];
    const std::string what = where + ": skin " + std::to_string(skinIndex);
    if (skin.joints.empty()) return core::makeError(what + " has no joints");
    std::optional<AccessorReader> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
        auto reader = AccessorReader::open(model, skin.inverseBindMatrices, what + " inverseBindMatrices");
        if (!reader) return reader.errorInfo();
        if (model.accessors[size_t(skin.inverseBindMatrices)].type != TINYGLTF_TYPE_MAT4 ||
            reader->count() < skin.joints.size())
            return core::makeError(what + ": its inverseBindMatrices must be a MAT4 accessor of one per joint (" +
                                   std::to_string(skin.joints.size()) + ")");
        inverseBind = std::move(*reader);
    }
    const std::vector<glm::dmat4> globals = nodeGlobalTransforms(model, trees);
    std::vector<int> path;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
        const int joint = skin.joints[j];
        if (joint < 0 || size_t(joint) >= model.nodes.size())
            return core::makeError(what + ": joint " + std::to_string(j) + " names node " + std::to_string(joint) +
                                   ", which is not a node");
        glm::dmat4 ibm(1.0);
        if (inverseBind)
            for (int c = 0; c < 16; ++c) ibm[c / 4][c % 4] = inverseBind->get(j, c); // column-major, as glTF
        // Root first down to the joint (NodeTrees: the walk up ends).
        path.clear();
        for (int node = joint; node >= 0; node = trees.parentOf[size_t(node)]) path.push_back(node);
        std::reverse(path.begin(), path.end());
        std::optional<NodeMotion> motion = motionAlong(model, path, moving);
        if (!motion) {
            motion.emplace();
            motion->chain.push_back({.fixed = globals[size_t(joint)]});
        }
        if (!core::isFinite(motion->sceneFromObjectAt(t) * ibm))
            return core::makeError(what + ": joint " + std::to_string(j) + "'s matrix is not finite");
        out.joints.push_back(std::move(*motion));
        out.inverseBind.push_back(ibm);
    }
    return out;
}

namespace {

// Every JOINTS_n / WEIGHTS_n set's influences, each vertex's weights divided by their sum.
core::Status readInfluences(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertices,
                            MeshDeformation& out, const std::string& where) {
    std::vector<std::vector<JointWeight>> of(vertices);
    for (int set = 0;; ++set) {
        const auto j = prim.attributes.find("JOINTS_" + std::to_string(set));
        const auto w = prim.attributes.find("WEIGHTS_" + std::to_string(set));
        if (j == prim.attributes.end() && w == prim.attributes.end()) break;
        if (j == prim.attributes.end() || w == prim.attributes.end())
            return core::makeError(where + ": JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set) +
                                   " come in pairs");
        auto jointsOf = AccessorReader::open(model, j->second, where + " JOINTS_" + std::to_string(set));
        if (!jointsOf) return jointsOf.errorInfo();
        auto weightsOf = AccessorReader::open(model, w->second, where + " WEIGHTS_" + std::to_string(set));
        if (!weightsOf) return weightsOf.errorInfo();
        const size_t count = std::min({jointsOf->count(), weightsOf->count(), vertices});
        for (size_t i = 0; i < count; ++i)
            for (int k = 0; k < 4; ++k) {
                const double weight = weightsOf->get(i, k);
                if (!(weight > 0.0)) continue; // no influence (a NaN weight neither)
                const double joint = jointsOf->get(i, k);
                if (!(joint >= 0.0 && joint < double(out.joints.size()))) {
                    // As written: a float accessor may hold 1e26 or NaN, which no integer holds.
                    char named[32];
                    std::snprintf(named, sizeof named, "%.6g", joint);
                    return core::makeError(where + ": vertex " + std::to_string(i) + " names joint " + named +
                                           " of a skin of " + std::to_string(out.joints.size()));
                }
                of[i].push_back({uint32_t(joint), weight});
            }
    }
    out.firstInfluence.assign(1, 0);
    for (std::vector<JointWeight>& influences : of) {
        double sum = 0.0;
        for (const JointWeight& one : influences) sum += one.weight;
        if (sum > 0.0 && std::isfinite(sum)) // else unweighted: as bound
            for (JointWeight& one : influences) out.influences.push_back({one.joint, one.weight / sum});
        out.firstInfluence.push_back(uint32_t(out.influences.size()));
    }
    return core::Ok{};
}

// The primitive's morph targets, each POSITION and NORMAL read whole.
core::Status readTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertices,
                         MeshDeformation& out, const std::string& where) {
    for (size_t t = 0; t < prim.targets.size(); ++t) {
        MorphTarget target;
        for (const char* attribute : {"POSITION", "NORMAL"}) {
            const auto a = prim.targets[t].find(attribute);
            if (a == prim.targets[t].end()) continue;
            const std::string what = where + " target " + std::to_string(t);
            auto reader = AccessorReader::open(model, a->second, what + " " + attribute);
            if (!reader) return reader.errorInfo();
            std::vector<glm::vec3>& moves = attribute[0] == 'N' ? target.normals : target.positions;
            moves.resize(std::min(reader->count(), vertices));
            for (size_t v = 0; v < moves.size(); ++v) moves[v] = glm::vec3(reader->read(v));
        }
        out.targets.push_back(std::move(target));
    }
    return core::Ok{};
}

} // namespace

core::Result<MeshDeformation> readDeformation(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                              const Mesh& mesh, const std::vector<double>& weights,
                                              const std::vector<std::shared_ptr<const KeyframeChannel>>& weightKeys,
                                              const SkinJoints* skin, const std::string& where) {
    MeshDeformation d;
    for (const Vertex& v : mesh.vertices) d.bindPositions.push_back(v.position), d.bindNormals.push_back(v.normal);
    for (size_t k = 0; k < std::min(weights.size(), prim.targets.size()); ++k)
        if (!std::isfinite(weights[k]))
            return core::makeError(where + " target " + std::to_string(k) + ": its weight is not finite");
    d.weights = weights;
    d.weightKeys = weightKeys;
    if (auto s = readTargets(model, prim, mesh.vertices.size(), d, where); !s) return s.errorInfo();
    // Faces give the normals of a primitive without any, once its targets move it.
    d.normalsFromFaces = prim.attributes.count("NORMAL") == 0 && !d.targets.empty();
    if (skin) {
        d.joints = skin->joints;
        d.inverseBind = skin->inverseBind;
        if (auto s = readInfluences(model, prim, mesh.vertices.size(), d, where); !s) return s.errorInfo();
    }
    return d;
}

core::Status poseAtLoad(MeshDeformation& deformation, double t, Mesh& mesh, glm::dvec3& anchor,
                        const std::string& where) {
    anchor = glm::dvec3(0.0);
    std::vector<bool> mirrored;
    std::vector<glm::dvec3> normals;
    const std::vector<glm::dvec3> posed = deformation.posedPositions(t, normals, &mirrored);
    for (size_t v = 0; v < posed.size(); ++v)
        if (!core::isFinite(posed[v]))
            return core::makeError(where + ": vertex " + std::to_string(v) + " is posed to a non-finite position");
    if (deformation.skinned()) {
        core::Aabb bounds;
        for (const glm::dvec3& p : posed) bounds.extend(p);
        anchor = anchorOf(bounds);
    }
    deformation.meshFromPosed = glm::translate(glm::dmat4(1.0), -anchor);
    deformation.writePose(mesh, posed, normals);
    // A pose that mirrors turns a triangle's winding as a mirrored node does (gltf_read.cpp), while
    // its normals, moved by the inverse transpose, keep pointing out: so a triangle whose corners
    // are mostly mirrored is reversed, and its front stays the side its normals face.
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const auto flips = [&](uint32_t v) { return v < mirrored.size() && mirrored[v] ? 1 : 0; };
        if (flips(mesh.indices[i]) + flips(mesh.indices[i + 1]) + flips(mesh.indices[i + 2]) >= 2)
            std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }
    return core::Ok{};
}

} // namespace shadowkit::scene::formats
