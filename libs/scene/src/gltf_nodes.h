// A glTF file's node hierarchy, checked once (gltf_nodes.cpp), and what the loader reads from
// it before any mesh: which nodes the scene starts from and which materials they use.
// Internal to libs/scene.
#pragma once

#include "shadowkit/core/result.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

/// The nodes of a file whose hierarchy is what glTF requires (disjoint strict trees): every
/// child index names a node, each node has at most one parent, and every node's parents lead
/// up to a root. Walking up from any node through `parentOf` ends.
struct NodeTrees {
    std::vector<int> parentOf; // node index -> its parent's, −1 for a root
};

/// The file's hierarchy checked (and refused in one line naming the node where it is not a set
/// of trees: a loop, a second parent, a child that is not a node).
core::Result<NodeTrees> checkNodeTrees(const tinygltf::Model& model, const std::filesystem::path& file);

/// Every node's matrix what glTF allows (2.0, §5.25 "Node"): its last row (0, 0, 0, 1), as glTF
/// asks that it decompose into translation, rotation and scale; refused in one line naming the
/// node otherwise. A matrix whose last row is (0, 0, 0, 0) divides every point it places by zero.
/// (JSON holds no infinite number: the parser refuses one that overflows a double.)
core::Status checkNodeTransforms(const tinygltf::Model& model, const std::filesystem::path& file);

/// One line in `warnings` naming the nodes whose rotation is not a unit quaternion (glTF 2.0,
/// §5.25: it must be). Such a node is placed by the unit quaternion's matrix formula as it stands
/// — in general a scale and shear, not a rotation — in the maps and the truth alike. Exporters'
/// float rounding (a length within 10⁻³ of 1) is not named.
void warnOfNodeRotations(const tinygltf::Model& model, const std::filesystem::path& file,
                         std::vector<std::string>& warnings);

/// The nodes the loaded scene starts from: its default scene's roots (scene 0's where the file
/// names none), or, in a file with no scene, every root node, with one line in `warnings`.
/// Each node is placed once: a listed node below another listed one is left to it, one whose
/// parent is not placed stands as a root with its own transform and is cut from that parent
/// in `trees` (each said in one warning).
std::vector<int> sceneRoots(const tinygltf::Model& model, NodeTrees& trees, const std::filesystem::path& file,
                            std::vector<std::string>& warnings);

/// KHR_node_visibility (ratified): a node whose `visible` is false hides itself and everything
/// below it — a child cannot show itself again under a hidden parent. A hidden mesh is neither
/// drawn nor cast, as an engine that reads the extension shows the file; a hidden light is off;
/// cameras stay.
inline constexpr const char* kNodeVisibility = "KHR_node_visibility";
bool hiddenByItself(const tinygltf::Node& node);

/// Which of the file's materials the primitives of the meshes placed and not hidden below `roots` use.
std::vector<bool> materialsPlaced(const tinygltf::Model& model, const std::vector<int>& roots);

} // namespace shadowkit::scene::formats
