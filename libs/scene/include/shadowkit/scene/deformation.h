// Meshes a file's animations deform — a glTF skin's joints, a mesh's morph weights — posed at any
// time t, so that a character walks along a camera path rather than standing in one pose
// (animation.h's animate() poses each, and reports its instances as moved).
//
// Based on: the glTF 2.0 specification, "Morph Targets" (§3.7.2.2): a morphed vertex is
//     p_m = p + Σ_k w_k(t) · Δp_k      (normals likewise, renormalised)
// with the node's weights, else the mesh's defaults, where no channel moves them; then "Skins"
// (§3.7.3) and "Skinned Mesh Attributes" (§3.7.3.3):
//     p' = Σ_i w_i · J(j_i, t) · p_m,   J(j, t) = G(joint j, t) · IBM(j)
// with G a node's global transform (its chain of nodes, some moved by keys: keyframes.h) and IBM
// the skin's inverse bind matrix; the weights divided by their sum (exporters round), normals by
// the inverse transpose of the blended matrix. The node holding a skinned mesh places nothing:
// only its joints do. Everything in double; the mesh receives meshFromPosed · p', in float.
#pragma once

#include "shadowkit/scene/keyframes.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace shadowkit::scene {

struct Mesh; // scene.h, which holds a scene's deformations

// One joint's share of a skinned vertex.
struct JointWeight {
    uint32_t joint = 0;  // into MeshDeformation::joints
    double weight = 0.0; // divided by the vertex's sum: a vertex's weights add up to 1
};

// A morph target's moves, one per vertex (glTF's POSITION and NORMAL of a target; either may be empty).
struct MorphTarget {
    std::vector<glm::vec3> positions, normals;
};

struct MeshDeformation {
    uint32_t batch = 0; // Scene::batches: a dynamic batch whose mesh this reshapes (every instance of it)

    // The mesh's first bindPositions.size() vertices as the file binds them: positions and
    // normals before any target or joint moves them (any after them are left alone).
    std::vector<glm::vec3> bindPositions, bindNormals;
    bool normalsFromFaces = false; // the file gives no normals: the posed faces give them

    std::vector<MorphTarget> targets;
    std::vector<double> weights;                                    // per target, where no key moves it
    std::vector<std::shared_ptr<const KeyframeChannel>> weightKeys; // per target (null: weights[k]), or empty

    // The skin; none where `joints` is empty. joints[j].sceneFromObjectAt(t) is G(joint j, t).
    std::vector<NodeMotion> joints;
    std::vector<glm::dmat4> inverseBind;  // one per joint
    std::vector<uint32_t> firstInfluence; // per vertex, and one past the last: its range of `influences`
    std::vector<JointWeight> influences;  // a vertex with none keeps its morphed bind position

    // From the posed (file) coordinates to the mesh's: the loader's moves of the mesh towards its
    // own origin and up-axis turn (affine, rigid).
    glm::dmat4 meshFromPosed{1.0};

    bool skinned() const { return !joints.empty(); }

    // The bind vertices posed at time t (seconds), in double. `mirrored`, when given, receives
    // per vertex whether its blended joints mirror it (a negative determinant).
    std::vector<glm::dvec3> posedPositions(double t, std::vector<glm::dvec3>& normals,
                                           std::vector<bool>* mirrored = nullptr) const;
    // Writes the pose at t into `mesh` (positions, normals, bounds). A vertex whose pose is not
    // finite keeps where it was; the triangles keep their winding (a pose that mirrors a part
    // does not turn its faces back: the loader does at the first pose, gltf_read.cpp).
    void poseInto(Mesh& mesh, double t) const;
    // Writes a pose posedPositions gave (`positions`, `normals`) into `mesh`, as poseInto does.
    void writePose(Mesh& mesh, std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals) const;
};

} // namespace shadowkit::scene
