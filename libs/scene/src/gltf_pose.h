// glTF nodes and skinned meshes at the file's rest pose (gltf_pose.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace shadowkit::scene::formats {

/// A node's transform relative to its parent: its matrix, or T · R · S (in double, as the file
/// writes its numbers: a node may stand a thousand kilometres out).
glm::dmat4 nodeLocalMatrix(const tinygltf::Node& node);

/// Every node's global transform at the rest pose (the nodes' TRS or matrices as written), for
/// a file whose nodes form trees (checkNodeTrees).
std::vector<glm::dmat4> nodeGlobalTransforms(const tinygltf::Model& model);

/// Skin `skin`'s joint matrices: each joint's global transform times its inverse bind matrix.
core::Result<std::vector<glm::dmat4>> jointMatrices(const tinygltf::Model& model, int skin,
                                                    const std::vector<glm::dmat4>& globals, const std::string& where);

/// The primitive's morph targets (§3.7.2.2) at `weights` (the node's, else the mesh's defaults):
/// p' = p + Σ w_t · POSITION_t, normals likewise and renormalised (recomputed from the faces for a
/// primitive without normals); nothing where every weight is 0.
core::Status applyMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                               const std::vector<double>& weights, Mesh& mesh, const std::string& where);

/// The primitive's vertices (`mesh`, as convertPrimitive read them) moved by their joints:
/// p' = Σ w_k · joint[j_k] · p over every JOINTS_n / WEIGHTS_n set, normals by the inverse
/// transpose of the blend; a triangle whose corners are mostly mirrored by their blends
/// (negative determinant) reversed, as a mirrored node's are; bounds recomputed. The posed
/// positions are kept relative to `anchor`, which it sets: anchorOf() their box, subtracted in
/// double (a skin posed far out keeps its precision); the mesh is to be placed there.
core::Status applySkin(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                       const std::vector<glm::dmat4>& joints, Mesh& mesh, glm::dvec3& anchor, const std::string& where);

} // namespace shadowkit::scene::formats
