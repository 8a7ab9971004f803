// glTF nodes (glTF 2.0, Concepts, "Nodes and Hierarchy"): the hierarchy checked once, the
// roots a scene starts from, the materials its meshes use.
#include "gltf_nodes.h"

#include "scene_formats.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

// "node 3 'wheel'", as every message below names a node.
std::string nodeNamed(const tinygltf::Model& model, size_t node) {
    const std::string& name = model.nodes[node].name;
    return "node " + std::to_string(node) + (name.empty() ? "" : " '" + printable(name) + "'");
}

} // namespace

// glTF 2.0 (Concepts, "Nodes and Hierarchy"): "the node hierarchy MUST be a set of disjoint
// strict trees": no cycles and each node with at most one parent (a scene's roots, which must
// have none, are sceneRoots' to place).
// tinygltf does not check it, and a file that breaks it can place a node exponentially often:
// a chain of nodes each naming the next twice places 2^depth instances, and a node that is its
// own child recursed to the old depth limit of 64, doubling at every level (fuzz_gltf hung on
// both). Checked before anything is placed, each node walked over once.
core::Result<NodeTrees> checkNodeTrees(const tinygltf::Model& model, const fs::path& file) {
    const auto named = [&](size_t node) { return nodeNamed(model, node); };
    std::vector<int> parentOf(model.nodes.size(), -1);
    for (size_t node = 0; node < model.nodes.size(); ++node)
        for (int child : model.nodes[node].children) {
            if (child < 0 || size_t(child) >= model.nodes.size())
                return core::makeError(file.string() + ": " + named(node) + " lists child " + std::to_string(child) +
                                       ", which is not a node");
            if (parentOf[size_t(child)] >= 0)
                return core::makeError(file.string() + ": " + named(size_t(child)) + " is a child of " +
                                       named(size_t(parentOf[size_t(child)])) + " and again of " + named(node) +
                                       " (glTF's nodes form trees: one parent each)");
            parentOf[size_t(child)] = int(node);
        }
    // Every node's parents lead up to a node that has none. A loop of nodes each the child of
    // the next has no root above it: no scene lists it, yet a skin may name its nodes as joints,
    // and walking up from one (the animations' reader does) would never end — a hang found by
    // fuzz_gltf in a file whose `scenes` were mangled away. Each node is walked over once.
    enum : int8_t { kUnknown, kOnThisWalk, kReachesARoot };
    std::vector<int8_t> state(model.nodes.size(), kUnknown);
    std::vector<size_t> walk;
    for (size_t start = 0; start < model.nodes.size(); ++start) {
        walk.clear();
        int node = int(start);
        for (; node >= 0 && state[size_t(node)] == kUnknown; node = parentOf[size_t(node)]) {
            state[size_t(node)] = kOnThisWalk;
            walk.push_back(size_t(node));
        }
        if (node >= 0 && state[size_t(node)] == kOnThisWalk)
            return core::makeError(file.string() + ": " + named(size_t(node)) +
                                   " is its own ancestor (a cycle in the node hierarchy)");
        for (size_t visited : walk) state[visited] = kReachesARoot;
    }
    return NodeTrees{std::move(parentOf)};
}

core::Status checkNodeTransforms(const tinygltf::Model& model, const fs::path& file) {
    for (size_t node = 0; node < model.nodes.size(); ++node) {
        const tinygltf::Node& n = model.nodes[node];
        if (n.matrix.size() != 16) continue; // TRS, or none (nodeLocalMatrix reads a matrix of another size as none)
        // Column-major: the last row is elements 3, 7, 11 and 15. Exporters write floats, so a
        // row of rounding noise is read as the affine row it means.
        constexpr double kNoise = 1e-6;
        const double row[4] = {n.matrix[3], n.matrix[7], n.matrix[11], n.matrix[15]};
        if (std::abs(row[0]) > kNoise || std::abs(row[1]) > kNoise || std::abs(row[2]) > kNoise ||
            std::abs(row[3] - 1.0) > kNoise) {
            char text[160];
            std::snprintf(text, sizeof text, "its matrix's last row is (%g, %g, %g, %g), not (0, 0, 0, 1)", row[0],
                          row[1], row[2], row[3]);
            return core::makeError(file.string() + ": " + nodeNamed(model, node) + ": " + text +
                                   ": glTF asks for a matrix made of translation, rotation and scale");
        }
    }
    return core::Ok{};
}

void warnOfNodeRotations(const tinygltf::Model& model, const fs::path& file, std::vector<std::string>& warnings) {
    std::vector<size_t> nodes;
    double farthest = 1.0; // the length farthest from 1
    for (size_t node = 0; node < model.nodes.size(); ++node) {
        const std::vector<double>& q = model.nodes[node].rotation;
        if (q.size() != 4) continue;
        const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (std::abs(length - 1.0) <= 1e-3) continue;
        nodes.push_back(node);
        if (std::abs(length - 1.0) > std::abs(farthest - 1.0)) farthest = length;
    }
    if (nodes.empty()) return;
    char length[32];
    std::snprintf(length, sizeof length, "%.3g", farthest);
    warnings.push_back(file.string() + ": " + nodeNamed(model, nodes.front()) +
                       (nodes.size() > 1 ? " and " + std::to_string(nodes.size() - 1) + " more" : std::string()) +
                       ": a rotation that is not a unit quaternion (length " + length +
                       "; glTF requires one), placed by the formula as it stands, which for another length "
                       "need not be a rotation");
}

// The nodes the loaded scene starts from: its default scene's roots (scene 0's where the file
// names none). A file with no scene at all is, in glTF's words, a library of entities (§3.5:
// "a glTF asset that does not contain any scenes should be treated as a library"); Blender's
// exporter writes one when told to export no scene. A viewer is free to show it as it likes
// (§3.5.1): shadowkit places every node that is no other's child, as Blender's importer does,
// and says so — a file of meshes must not be refused as holding none.
//
// A scene's nodes "MUST be root nodes" (§3.5.2), and exporters break it: Kenney's kits list a
// mesh node as the root though a `tmpParent` node (never placed) names it as its child, and
// viewers draw such files. So each node listed is placed once, where the file places it: below a
// listed ancestor if it has one (its listing dropped: placed twice, a chain of n listed nodes
// would cost n²/2 placements), else as a root with its own transform, as viewers draw it — and
// then cut from its parent in `trees`, so that poses and animations compose its transform as it
// is placed. A node listed twice is placed once. Each case is said in one warning.
std::vector<int> sceneRoots(const tinygltf::Model& model, NodeTrees& trees, const fs::path& file,
                            std::vector<std::string>& warnings) {
    std::vector<int>& parentOf = trees.parentOf;
    if (model.scenes.empty()) {
        std::vector<int> roots;
        for (size_t node = 0; node < model.nodes.size(); ++node)
            if (parentOf[node] < 0) roots.push_back(int(node));
        if (!roots.empty())
            warnings.push_back(file.string() + ": it has no scene (a library of entities); " +
                               (roots.size() == 1
                                    ? std::string("its root node stands")
                                    : "its " + std::to_string(roots.size()) + " root nodes stand together") +
                               " as the scene");
        return roots;
    }
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(sceneIndex) >= model.scenes.size()) return {};
    const size_t n = model.nodes.size();
    std::vector<bool> listed(n, false);
    std::vector<int> candidates;
    size_t repeated = 0;
    for (int node : model.scenes[size_t(sceneIndex)].nodes) {
        if (node < 0 || size_t(node) >= n) continue; // placed nowhere
        if (listed[size_t(node)]) {
            ++repeated;
            continue;
        }
        listed[size_t(node)] = true;
        candidates.push_back(node);
    }
    // Whether a listed node lies below another listed one, each node's answer found once
    // (checkNodeTrees: every walk up ends).
    enum class Below : int8_t { Unknown, AListedNode, Nothing };
    std::vector<Below> below(n, Below::Unknown);
    std::vector<size_t> walk;
    const auto belowAListedNode = [&](size_t start) {
        walk.clear();
        Below answer = Below::Nothing;
        for (int node = parentOf[start]; node >= 0; node = parentOf[size_t(node)]) {
            if (below[size_t(node)] != Below::Unknown) {
                answer = listed[size_t(node)] ? Below::AListedNode : below[size_t(node)];
                break;
            }
            if (listed[size_t(node)]) {
                answer = Below::AListedNode;
                break;
            }
            walk.push_back(size_t(node));
        }
        for (size_t visited : walk) below[visited] = answer;
        return answer == Below::AListedNode;
    };
    std::vector<int> roots;
    std::vector<size_t> underListed, cut;
    for (int node : candidates) {
        if (parentOf[size_t(node)] < 0)
            roots.push_back(node);
        else if (belowAListedNode(size_t(node)))
            underListed.push_back(size_t(node));
        else {
            cut.push_back(size_t(node));
            roots.push_back(node);
        }
    }
    const auto named = [&](size_t node) { return nodeNamed(model, node); };
    const auto firstAnd = [&](const std::vector<size_t>& nodes) {
        return named(nodes.front()) +
               (nodes.size() > 1 ? " and " + std::to_string(nodes.size() - 1) + " more" : std::string());
    };
    const std::string where = file.string() + ": scene " + std::to_string(sceneIndex) + " lists ";
    if (!cut.empty()) {
        const std::string parent = named(size_t(parentOf[cut.front()]));
        warnings.push_back(where + firstAnd(cut) +
                           (cut.size() == 1
                                ? " as a root though it is a child of " + parent
                                : " as roots though each is a child (" + named(cut.front()) + " of " + parent + ")") +
                           "; a scene's roots have no parent in glTF: drawn as " +
                           (cut.size() == 1 ? "a root with its own transform, as viewers draw it"
                                            : "roots with their own transforms, as viewers draw them"));
    }
    if (!underListed.empty())
        warnings.push_back(where + firstAnd(underListed) + " as " + (underListed.size() > 1 ? "roots" : "a root") +
                           " below another node it lists: placed once, below it");
    if (repeated > 0)
        warnings.push_back(where + std::to_string(repeated) + (repeated > 1 ? " nodes" : " node") +
                           " more than once: placed once");
    for (size_t node : cut) parentOf[node] = -1;
    return roots;
}

// Which materials the primitives of the meshes placed below `roots` use. Each node is met
// once: checkNodeTrees has made the nodes below the roots trees.
bool hiddenByItself(const tinygltf::Node& node) {
    const auto ext = node.extensions.find(kNodeVisibility);
    if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("visible")) return false;
    const tinygltf::Value& visible = ext->second.Get("visible");
    return visible.IsBool() && !visible.Get<bool>();
}

std::vector<bool> materialsPlaced(const tinygltf::Model& model, const std::vector<int>& roots) {
    std::vector<bool> used(model.materials.size(), false);
    std::vector<int> toVisit(roots.begin(), roots.end());
    while (!toVisit.empty()) {
        const int index = toVisit.back();
        toVisit.pop_back();
        if (index < 0 || size_t(index) >= model.nodes.size()) continue;
        const tinygltf::Node& node = model.nodes[size_t(index)];
        if (hiddenByItself(node)) continue; // nothing below it is drawn: its textures are not needed
        if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size())
            for (const tinygltf::Primitive& primitive : model.meshes[size_t(node.mesh)].primitives)
                if (primitive.material >= 0 && size_t(primitive.material) < used.size())
                    used[size_t(primitive.material)] = true;
        toVisit.insert(toVisit.end(), node.children.begin(), node.children.end());
    }
    return used;
}

} // namespace shadowkit::scene::formats
