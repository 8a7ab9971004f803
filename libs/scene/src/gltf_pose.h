// glTF nodes, and the skins and morph targets that deform meshes (gltf_pose.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/deformation.h"
#include "shadowkit/scene/scene.h"

#include "gltf_animation.h"
#include "gltf_nodes.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

/// A node's transform relative to its parent: its matrix, or T · R · S (in double, as the file
/// writes its numbers: a node may stand a thousand kilometres out).
glm::dmat4 nodeLocalMatrix(const tinygltf::Node& node);

/// Every node's global transform at the rest pose (the nodes' TRS or matrices as written).
std::vector<glm::dmat4> nodeGlobalTransforms(const tinygltf::Model& model, const NodeTrees& trees);

/// A skin's joints, each placed over time by the chain of nodes above it (`moving`: the nodes
/// animations move, as motionAlong takes them; file coordinates), and their inverse bind
/// matrices. A joint's matrix that is not finite at `t` is refused.
struct SkinJoints {
    std::vector<NodeMotion> joints;
    std::vector<glm::dmat4> inverseBind;
};
core::Result<SkinJoints> readSkinJoints(const tinygltf::Model& model, const NodeTrees& trees, int skin,
                                        const AnimatedNodes& moving, double t, const std::string& where);

/// What deforms a primitive's vertices (`mesh`, as convertPrimitive read them; its batch left
/// for the caller), read and checked: its morph targets at `weights` (the node's, else the mesh's
/// defaults), each moved by `weightKeys[k]` where given; and, with `skin` (readSkinJoints, read
/// once a skin), its joints and every JOINTS_n / WEIGHTS_n set.
core::Result<MeshDeformation> readDeformation(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                              const Mesh& mesh, const std::vector<double>& weights,
                                              const std::vector<std::shared_ptr<const KeyframeChannel>>& weightKeys,
                                              const SkinJoints* skin, const std::string& where);

/// Poses `mesh` as `deformation` stands at t, the first time (at load): a skinned mesh's positions
/// kept relative to `anchor`, which it sets — anchorOf() their box, subtracted in double (a skin
/// posed far out keeps its precision; the mesh is to be placed there, and deformation.meshFromPosed
/// moves by it) —, and a triangle whose corners are mostly mirrored by their blends reversed, as a
/// mirrored node's are.
/// A vertex posed at `t` to a non-finite position is refused, naming `where`.
core::Status poseAtLoad(MeshDeformation& deformation, double t, Mesh& mesh, glm::dvec3& anchor,
                        const std::string& where);

} // namespace shadowkit::scene::formats
