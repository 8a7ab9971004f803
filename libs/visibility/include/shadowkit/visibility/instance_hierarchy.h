// A bounding volume hierarchy over instance boxes: scene bounds in O(1), the instances that
// intersect a convex volume in time that follows the answer, and a refit that costs what
// moved, not what exists.
#pragma once

#include "shadowkit/visibility/core_types.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::visibility {

// A half-space a·x + b·y + c·z + d >= 0 (kept side positive), e.g. a row combination of a
// clip matrix: (row3 + row0) · (p, 1) >= 0 is x >= −w. Need not be normalised.
using HalfSpace = Vec4;

// The half-spaces of the clip volume of `clipFromWorld` (clip depth [0, 1]; rows combined
// as in Gribb & Hartmann 2001): left, right, bottom, top, far, and the near plane unless
// `withNear` is false. Exact for projective
// matrices: it is the set GL keeps before the divide. Without the near plane the volume is
// extended towards the light — what a depth-clamped shadow pass still draws.
std::vector<HalfSpace> clipVolume(const Mat4& clipFromWorld, bool withNear = true);

// Whether one half-space has all of the box outside (or the box is empty): the test the
// hierarchy's queries cull with. NaN-safe: NaN culls.
bool isOutside(std::span<const HalfSpace> volume, const Aabb& box);

class InstanceHierarchy {
public:
    InstanceHierarchy() = default;
    // Binned SAH build (16 bins per axis, leaves of up to 4 items) over `boxes`; item i is
    // boxes[i]. Empty boxes are kept (they never intersect anything).
    explicit InstanceHierarchy(std::span<const Aabb> boxes);

    size_t size() const { return m_itemBoxes.size(); }
    // Union of every item's box; O(1).
    const Aabb& bounds() const;
    const Aabb& itemBounds(uint32_t item) const { return m_itemBoxes[item]; }

    // Appends to `out` the items whose box may intersect the intersection of the half-spaces:
    // a box is left out only when one half-space has all of it outside, so no item that
    // intersects is ever lost. The order is the tree's, not the items'. Subtrees wholly
    // inside every half-space emit their items without further tests.
    void query(std::span<const HalfSpace> volume, std::vector<uint32_t>& out) const;
    // The same, keeping also only boxes `accept(box)` says may matter (a receiver mask,
    // an occlusion test): asked of nodes before their children, so a subtree it rejects
    // costs one call. It must be conservative for every box that contains a smaller one.
    template <class Accept>
    void query(std::span<const HalfSpace> volume, const Accept& accept, std::vector<uint32_t>& out) const {
        queryAccepting(
            volume, &accept, [](const void* f, const Aabb& b) { return (*static_cast<const Accept*>(f))(b); }, out);
    }

    // The nodes, for traversals of their own (occlusion culling): node 0 is the root, an
    // inner node's children are leftChild and leftChild + 1, a leaf holds items.
    static constexpr uint32_t kRoot = 0;
    bool isLeaf(uint32_t node) const { return m_nodes[node].count > 0 || m_nodes.size() == 1; }
    uint32_t leftChild(uint32_t node) const { return m_nodes[node].first; }
    uint32_t parent(uint32_t node) const { return m_nodes[node].parent; } // UINT32_MAX for the root
    const Aabb& nodeBounds(uint32_t node) const { return m_nodes[node].box; }
    std::span<const uint32_t> leafItems(uint32_t node) const {
        return {m_items.data() + m_nodes[node].first, m_nodes[node].count};
    }

    // Moves item i to newBox and refits its ancestors: O(changed × depth). The tree's
    // topology stays: many large moves degrade query cost (rebuild then).
    void update(uint32_t item, const Aabb& newBox);

    // The surface-area cost of the tree (Wald 2007): Σ over nodes of area(node) / area(root),
    // an inner node counting one traversal step and a leaf its items — the expected work of
    // a query for a random ray or small volume. O(nodes).
    double surfaceAreaCost() const;
    // surfaceAreaCost() now over what it was when the tree was built: how much the refits
    // have degraded it (1 when built; items that wander stretch their leaves).
    double degradation() const;
    // Builds the tree again over the items' current boxes (item indices stay; node indices
    // do not: anything keyed by node must be reset).
    void rebuild();

    // Number of nodes, for tests and reports.
    size_t nodeCount() const { return m_nodes.size(); }

private:
    struct Node {
        Aabb box;
        uint32_t first = 0; // leaf: first index into m_items; inner: left child (right = first + 1)
        uint32_t count = 0; // leaf: number of items; inner: 0
        uint32_t parent = UINT32_MAX;
    };
    void build(uint32_t node, uint32_t begin, uint32_t end, int depth, std::vector<Vec3>& centres);
    void collect(uint32_t node, std::vector<uint32_t>& out) const;
    void queryAccepting(std::span<const HalfSpace> volume, const void* accept, bool (*call)(const void*, const Aabb&),
                        std::vector<uint32_t>& out) const;

    std::vector<Node> m_nodes;      // m_nodes[0] is the root
    std::vector<uint32_t> m_items;  // leaf ranges index this
    std::vector<uint32_t> m_leafOf; // item -> its leaf node
    std::vector<Aabb> m_itemBoxes;
    double m_builtCost = 0.0; // surfaceAreaCost() when built
};

} // namespace shadowkit::visibility
