// Bounding volume hierarchy over instance boxes.
//
// Based on: the binned surface-area-heuristic build (Wald, "On fast Construction of
// SAH-based Bounding Volume Hierarchies", IEEE Symposium on Interactive Ray Tracing 2007;
// docs/references.md): items are split by their box centres into 16 bins along the axis of
// largest centre extent, and the split with the lowest SA(left)·n(left) + SA(right)·n(right)
// wins; leaves hold up to 4 items. Refit walks from a moved item's leaf to the root.
// Culling tests a box against half-spaces with its "positive vertex" (the corner furthest
// along the plane's normal): outside when even that corner is outside; wholly inside when
// the "negative vertex" is inside every half-space.
#include "shadowkit/visibility/instance_hierarchy.h"

#include <algorithm>
#include <array>

namespace shadowkit::visibility {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr int kBins = 16;
// Below this depth splits are by count: the tree stays under kMaxSahDepth + log2(n / 4)
// levels, inside the query's fixed traversal stack.
constexpr int kMaxSahDepth = 40;
constexpr int kStackSize = 96;

double surfaceArea(const Aabb& b) {
    if (b.isEmpty()) return 0.0;
    const Vec3 e = b.extent();
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// Plane value at the box corner furthest along (positive) or against (negative) the normal.
double extremeValue(const HalfSpace& h, const Aabb& b, bool furthest) {
    const Vec3 n(h);
    const bool px = (n.x >= 0.0) == furthest, py = (n.y >= 0.0) == furthest, pz = (n.z >= 0.0) == furthest;
    return n.x * (px ? b.max.x : b.min.x) + n.y * (py ? b.max.y : b.min.y) + n.z * (pz ? b.max.z : b.min.z) + h.w;
}

enum class Overlap { Outside, Partial, Inside };

Overlap classify(std::span<const HalfSpace> volume, const Aabb& b) {
    if (b.isEmpty()) return Overlap::Outside;
    bool inside = true;
    for (const HalfSpace& h : volume) {
        if (!(extremeValue(h, b, true) >= 0.0)) return Overlap::Outside; // NaN-safe: NaN culls
        inside = inside && extremeValue(h, b, false) >= 0.0;
    }
    return inside ? Overlap::Inside : Overlap::Partial;
}

} // namespace

bool isOutside(std::span<const HalfSpace> volume, const Aabb& box) { return classify(volume, box) == Overlap::Outside; }

std::vector<HalfSpace> clipVolume(const Mat4& m, bool withNear) {
    // Rows of the matrix (glm is column-major: m[c][r]).
    auto row = [&m](int r) { return HalfSpace(m[0][r], m[1][r], m[2][r], m[3][r]); };
    const HalfSpace x = row(0), y = row(1), z = row(2), w = row(3);
    std::vector<HalfSpace> planes = {w + x, w - x, w + y, w - y, w - z}; // -w<=x<=w, -w<=y<=w, z<=w
    if (withNear) planes.push_back(z);                                   // z >= 0
    return planes;
}

InstanceHierarchy::InstanceHierarchy(std::span<const Aabb> boxes) : m_itemBoxes(boxes.begin(), boxes.end()) {
    const auto n = static_cast<uint32_t>(boxes.size());
    m_items.resize(n);
    m_leafOf.assign(n, 0);
    std::vector<Vec3> centres(n);
    for (uint32_t i = 0; i < n; ++i) {
        m_items[i] = i;
        centres[i] = boxes[i].isEmpty() ? Vec3(0.0) : boxes[i].center();
    }
    m_nodes.reserve(n > 0 ? 2 * n / kLeafSize + 1 : 1);
    m_nodes.push_back({});
    build(0, 0, n, 0, centres);
    m_builtCost = surfaceAreaCost();
}

double InstanceHierarchy::surfaceAreaCost() const {
    if (m_nodes.empty() || m_nodes[0].box.isEmpty()) return 0.0;
    auto area = [](const Aabb& b) {
        if (b.isEmpty()) return 0.0;
        const Vec3 e = b.extent();
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    };
    const double root = std::max(area(m_nodes[0].box), 1e-300);
    double cost = 0.0;
    for (const Node& n : m_nodes) cost += area(n.box) / root * (n.count > 0 ? double(n.count) : 1.0);
    return cost;
}

double InstanceHierarchy::degradation() const { return m_builtCost > 0.0 ? surfaceAreaCost() / m_builtCost : 1.0; }

void InstanceHierarchy::rebuild() {
    const std::vector<Aabb> boxes = std::move(m_itemBoxes);
    *this = InstanceHierarchy(boxes);
}

void InstanceHierarchy::build(uint32_t index, uint32_t begin, uint32_t end, int depth, std::vector<Vec3>& centres) {
    Aabb box, centreBox;
    for (uint32_t i = begin; i < end; ++i) {
        box.extend(m_itemBoxes[m_items[i]]);
        centreBox.extend(centres[m_items[i]]);
    }
    m_nodes[index].box = box;
    const uint32_t count = end - begin;
    if (count <= kLeafSize) {
        m_nodes[index].first = begin;
        m_nodes[index].count = count;
        for (uint32_t i = begin; i < end; ++i) m_leafOf[m_items[i]] = index;
        return;
    }

    // Binned SAH on the axis of largest centre extent.
    const Vec3 extent = centreBox.extent();
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const double lo = centreBox.min[axis], span = extent[axis];
    uint32_t mid = begin;
    if (span > 0.0 && depth < kMaxSahDepth) {
        std::array<Aabb, kBins> binBoxes;
        std::array<uint32_t, kBins> binCounts{};
        auto binOf = [&](uint32_t item) {
            return std::min(kBins - 1, static_cast<int>(kBins * (centres[item][axis] - lo) / span));
        };
        for (uint32_t i = begin; i < end; ++i) {
            const int b = binOf(m_items[i]);
            binBoxes[size_t(b)].extend(m_itemBoxes[m_items[i]]);
            ++binCounts[size_t(b)];
        }
        // Sweep: cost of splitting after bin s (left = bins 0..s).
        std::array<double, kBins - 1> leftCost{};
        Aabb acc;
        uint32_t accCount = 0;
        for (int s = 0; s < kBins - 1; ++s) {
            acc.extend(binBoxes[size_t(s)]);
            accCount += binCounts[size_t(s)];
            leftCost[size_t(s)] = surfaceArea(acc) * accCount;
        }
        acc = Aabb{};
        accCount = 0;
        double best = INFINITY;
        int bestSplit = -1;
        for (int s = kBins - 2; s >= 0; --s) {
            acc.extend(binBoxes[size_t(s) + 1]);
            accCount += binCounts[size_t(s) + 1];
            const double cost = leftCost[size_t(s)] + surfaceArea(acc) * accCount;
            if (accCount > 0 && accCount < count && cost < best) {
                best = cost;
                bestSplit = s;
            }
        }
        if (bestSplit >= 0) {
            const auto it = std::partition(m_items.begin() + begin, m_items.begin() + end,
                                           [&](uint32_t item) { return binOf(item) <= bestSplit; });
            mid = static_cast<uint32_t>(it - m_items.begin());
        }
    }
    if (mid == begin || mid == end) {
        // Coincident centres, or deep enough that SAH may have degenerated: split by count.
        mid = begin + count / 2;
        std::nth_element(m_items.begin() + begin, m_items.begin() + mid, m_items.begin() + end,
                         [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
    }
    // Children sit next to each other: left at `first`, right at `first + 1`.
    const auto left = static_cast<uint32_t>(m_nodes.size());
    m_nodes.push_back({.parent = index});
    m_nodes.push_back({.parent = index});
    m_nodes[index].first = left;
    m_nodes[index].count = 0;
    build(left, begin, mid, depth + 1, centres);
    build(left + 1, mid, end, depth + 1, centres);
}

const Aabb& InstanceHierarchy::bounds() const {
    static const Aabb kEmpty;
    return m_nodes.empty() ? kEmpty : m_nodes[0].box;
}

void InstanceHierarchy::collect(uint32_t node, std::vector<uint32_t>& out) const {
    const Node& n = m_nodes[node];
    if (n.count > 0) {
        for (uint32_t i = n.first; i < n.first + n.count; ++i)
            if (!m_itemBoxes[m_items[i]].isEmpty()) out.push_back(m_items[i]);
        return;
    }
    collect(n.first, out);
    collect(n.first + 1, out);
}

void InstanceHierarchy::query(std::span<const HalfSpace> volume, std::vector<uint32_t>& out) const {
    queryAccepting(volume, nullptr, nullptr, out);
}

void InstanceHierarchy::queryAccepting(std::span<const HalfSpace> volume, const void* accept,
                                       bool (*call)(const void*, const Aabb&), std::vector<uint32_t>& out) const {
    if (m_nodes.empty()) return;
    auto accepted = [&](const Aabb& box) { return call == nullptr || call(accept, box); };
    uint32_t stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const uint32_t index = stack[--top];
        const Node& node = m_nodes[index];
        const Overlap overlap = classify(volume, node.box);
        if (overlap == Overlap::Outside || !accepted(node.box)) continue;
        if (overlap == Overlap::Inside && call == nullptr) {
            collect(index, out);
            continue;
        }
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Aabb& box = m_itemBoxes[m_items[i]];
                if (classify(volume, box) != Overlap::Outside && accepted(box)) out.push_back(m_items[i]);
            }
            continue;
        }
        SK_ASSERT(top + 2 <= kStackSize, "InstanceHierarchy::query(): tree deeper than its traversal stack");
        stack[top++] = node.first + 1;
        stack[top++] = node.first;
    }
}

void InstanceHierarchy::update(uint32_t item, const Aabb& newBox) {
    SK_ASSERT(item < m_itemBoxes.size(), "InstanceHierarchy::update(): item out of range");
    m_itemBoxes[item] = newBox;
    for (uint32_t node = m_leafOf[item]; node != UINT32_MAX; node = m_nodes[node].parent) {
        Node& n = m_nodes[node];
        Aabb box;
        if (n.count > 0) {
            for (uint32_t i = n.first; i < n.first + n.count; ++i) box.extend(m_itemBoxes[m_items[i]]);
        } else {
            box.extend(m_nodes[n.first].box);
            box.extend(m_nodes[n.first + 1].box);
        }
        n.box = box;
    }
}

} // namespace shadowkit::visibility
