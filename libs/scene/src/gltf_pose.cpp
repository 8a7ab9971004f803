// glTF nodes, morph targets and skinned meshes in the pose the file's nodes hold.
//
// Based on: the glTF 2.0 specification, "Morph Targets" (§3.7.2.2): a morphed vertex is
// p + Σ_t w_t · POSITION_t, with the node's weights or else the mesh's defaults (normals
// likewise); then "Skins" (§3.7.3) and "Skinned Mesh Attributes" (§3.7.3.3): a skinned vertex is
//     p' = Σ_k w_k · J(j_k) · p,   J(j) = G(joint j) · IBM(j)
// with G a node's global transform and IBM the skin's inverse bind matrix (identity when the
// skin has none), over every JOINTS_n / WEIGHTS_n set; the transform of the node that holds the
// skinned mesh is ignored (only the joints place it). Skins and morph weights are posed once at
// load, not played: the nodes' transforms and weights are the file's, or its animations' at the
// moment asked (gltf_animation.cpp's poseNodes writes them into the nodes first); the shadows
// are of that pose. Weights are divided by their sum (the specification asks for a sum of 1; exporters
// round), a vertex with no weight keeps its bind position, and normals follow the inverse
// transpose of the blended matrix.
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

std::vector<glm::dmat4> nodeGlobalTransforms(const tinygltf::Model& model) {
    const size_t n = model.nodes.size();
    std::vector<int> parentOf(n, -1);
    for (size_t node = 0; node < n; ++node)
        for (int child : model.nodes[node].children)
            if (child >= 0 && size_t(child) < n) parentOf[size_t(child)] = int(node);
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

core::Result<std::vector<glm::dmat4>> jointMatrices(const tinygltf::Model& model, int skinIndex,
                                                    const std::vector<glm::dmat4>& globals, const std::string& where) {
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
    std::vector<glm::dmat4> out(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j) {
        const int joint = skin.joints[j];
        if (joint < 0 || size_t(joint) >= globals.size())
            return core::makeError(what + ": joint " + std::to_string(j) + " names node " + std::to_string(joint) +
                                   ", which is not a node");
        glm::dmat4 ibm(1.0);
        if (inverseBind)
            for (int c = 0; c < 16; ++c) ibm[c / 4][c % 4] = inverseBind->get(j, c); // column-major, as glTF
        out[j] = globals[size_t(joint)] * ibm;
        if (!core::isFinite(out[j]))
            return core::makeError(what + ": joint " + std::to_string(j) + "'s matrix is not finite");
    }
    return out;
}

core::Status applyMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                               const std::vector<double>& weights, Mesh& mesh, const std::string& where) {
    // Most primitives have no targets, or weights of 0: nothing to copy or allocate for them.
    if (std::none_of(weights.begin(), weights.begin() + std::ptrdiff_t(std::min(weights.size(), prim.targets.size())),
                     [](double w) { return w != 0.0; }))
        return core::Ok{};
    bool moved = false;
    std::vector<glm::dvec3> normals(mesh.vertices.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) normals[v] = glm::dvec3(mesh.vertices[v].normal);
    for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
        const double weight = weights[t];
        if (weight == 0.0) continue;
        const std::string what = where + " target " + std::to_string(t);
        if (!std::isfinite(weight)) return core::makeError(what + ": its weight is not finite");
        for (const char* attribute : {"POSITION", "NORMAL"}) {
            const auto a = prim.targets[t].find(attribute);
            if (a == prim.targets[t].end()) continue;
            auto reader = AccessorReader::open(model, a->second, what + " " + attribute);
            if (!reader) return reader.errorInfo();
            for (size_t v = 0; v < std::min(reader->count(), mesh.vertices.size()); ++v) {
                const glm::dvec3 d = weight * glm::dvec3(reader->read(v));
                if (attribute[0] == 'N') {
                    normals[v] += d;
                    continue;
                }
                const glm::dvec3 p = glm::dvec3(mesh.vertices[v].position) + d;
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    return core::makeError(what + ": vertex " + std::to_string(v) + " moves to a non-finite position");
                mesh.vertices[v].position = glm::vec3(p);
            }
            moved = true;
        }
    }
    if (!moved) return core::Ok{};
    if (prim.attributes.count("NORMAL") == 0) {
        computeNormals(mesh); // the faces' normals, from the moved positions
    } else {
        for (size_t v = 0; v < mesh.vertices.size(); ++v)
            if (const double length = glm::length(normals[v]); length > 0.0 && std::isfinite(length))
                mesh.vertices[v].normal = glm::vec3(normals[v] / length);
    }
    mesh.computeBounds();
    return core::Ok{};
}

core::Status applySkin(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                       const std::vector<glm::dmat4>& joints, Mesh& mesh, glm::dvec3& anchor,
                       const std::string& where) {
    std::vector<glm::dmat4> blend(mesh.vertices.size(), glm::dmat4(0.0));
    std::vector<double> weightSum(mesh.vertices.size(), 0.0);
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
        const size_t count = std::min({jointsOf->count(), weightsOf->count(), mesh.vertices.size()});
        for (size_t i = 0; i < count; ++i)
            for (int k = 0; k < 4; ++k) {
                const double weight = weightsOf->get(i, k);
                if (!(weight > 0.0)) continue; // no influence (a NaN weight neither)
                const double joint = jointsOf->get(i, k);
                if (!(joint >= 0.0 && joint < double(joints.size()))) {
                    // As written: a float accessor may hold 1e26 or NaN, which no integer holds.
                    char named[32];
                    std::snprintf(named, sizeof named, "%.6g", joint);
                    return core::makeError(where + ": vertex " + std::to_string(i) + " names joint " + named +
                                           " of a skin of " + std::to_string(joints.size()));
                }
                blend[i] += weight * joints[size_t(joint)];
                weightSum[i] += weight;
            }
    }
    // Each vertex's position under its pose (double until the anchor is known) and handedness:
    // -1 where its blended joints mirror it.
    std::vector<glm::dvec3> posed(mesh.vertices.size());
    std::vector<int> handedness(mesh.vertices.size(), 1);
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        Vertex& v = mesh.vertices[i];
        posed[i] = glm::dvec3(v.position);
        if (!(weightSum[i] > 0.0) || !std::isfinite(weightSum[i])) continue; // unweighted: as bound
        const glm::dmat4 m = blend[i] / weightSum[i];
        const glm::dvec3 p = glm::dvec3(m * glm::dvec4(posed[i], 1.0));
        if (!core::isFinite(m) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return core::makeError(where + ": vertex " + std::to_string(i) + " is skinned to a non-finite position");
        posed[i] = p;
        const glm::dmat3 linear(m);
        const double det = glm::determinant(linear);
        if (det < 0.0) handedness[i] = -1;
        if (std::abs(det) > 1e-12) {
            const glm::dvec3 n = glm::inverseTranspose(linear) * glm::dvec3(v.normal);
            if (glm::length(n) > 0.0) v.normal = glm::vec3(glm::normalize(n));
        }
    }
    core::Aabb bounds;
    for (const glm::dvec3& p : posed) bounds.extend(p);
    anchor = anchorOf(bounds);
    for (size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i].position = glm::vec3(posed[i] - anchor);
    // A pose that mirrors turns a triangle's winding as a mirrored node does (gltf_read.cpp), while
    // its normals, moved by the inverse transpose, keep pointing out: so a triangle whose corners
    // are mostly mirrored is reversed, and its front stays the side its normals face.
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        if (handedness[mesh.indices[t]] + handedness[mesh.indices[t + 1]] + handedness[mesh.indices[t + 2]] < 0)
            std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    mesh.computeBounds();
    return core::Ok{};
}

} // namespace shadowkit::scene::formats
