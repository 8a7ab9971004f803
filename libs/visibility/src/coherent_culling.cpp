// Coherent hierarchical culling, revisited.
//
// Based on: Mattausch, Bittner, Wimmer, "CHC++: Coherent Hierarchical Culling Revisited",
// Eurographics 2008, which refines Bittner, Wimmer, Piringer, Purgathofer, "Coherent
// Hierarchical Culling: Hardware Occlusion Queries Made Useful", Eurographics 2004 — the
// visibility algorithm Scherzer's 10,000-tree forest ran on (docs/references.md).
//
// The hierarchy is walked front to back (a priority queue on the distance from the eye to
// each node's box). Temporal coherence decides what is queried:
//  - a node found visible last frame is not queried: an inner node is opened, a leaf is
//    drawn at once (its depth then occludes what lies behind). Every `visibleInterval`
//    frames, at a per-leaf random phase, a drawn leaf is queried again (the v-queue) to
//    learn that it became hidden; those queries are issued after everything is drawn and
//    read in the NEXT frame, so nothing ever waits for them.
//  - a node invisible last frame, or never seen, is queried (the i-queue): a hidden subtree
//    costs one query at its highest hidden node, since visibility is "pulled up" from the
//    visible leaves each frame (an opened inner node starts hidden and becomes visible
//    only through a visible descendant), and hidden nodes are not opened.
// The i-queue is issued in batches (CHC++ §4.1), after drawing what has been found visible
// so far, and its results are read when they have arrived, while the traversal goes on.
// The frame waits for a result only when there is nothing else to do: a hidden node that
// has become visible must be drawn in this frame, so the frame is never missing an object
// (unlike one-frame-late schemes, which pop). Those waits are counted. A wait is for the
// newest query, not the oldest: results arrive in issue order, so one wait brings them all,
// and a frame waits once per round trip (what a result opens must be asked again), not once
// per submission the driver made (measured on llvmpipe, 10,000 trees, the frames after a
// camera cut: 23-27 waits -> 5). While nodes remain to visit, results are polled every few
// visits (kVisitsPerPoll) rather than at each.
// Multi-queries (CHC++ §4.3): nodes hidden for i frames stay hidden with probability
// p(i) = 0.99 − 0.7 e^(−i) (the paper's fit). A group of n nodes costs one query if it stays
// hidden and 1 + n if not, so the expected cost is C(n) = 1 + (1 − ∏p)·n; a group grows
// while n / C(n), the queries saved per query spent, improves. A group that comes back
// visible has its nodes queried one by one.
// Choices of ours: an inner node opened last frame stays open (its children are visited
// without asking it again) until its due frame, though no visible leaf pulled it up: its
// box holds empty space between its children's and can pass while every child fails, and
// asking it each frame would open it each frame, one GPU round trip per level at the end of
// the frame (measured on the 100,000-tree forest: 1032 -> 168 queries, 7 -> 1 waits a frame).
// The first frame after reset() (and so after a camera cut) assumes every
// node visible — it draws exactly the frustum's contents and queries every leaf, so it is
// correct and the next frame is already coherent; nodes whose box holds the eye (grown by
// the near-plane margin) are drawn unqueried, as their boxes would be clipped.
#include "shadowkit/visibility/coherent_culling.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::visibility {
namespace {

// The distance queue is a min-heap on the distance from the eye.
constexpr auto kFarther = [](const std::pair<double, uint32_t>& a, const std::pair<double, uint32_t>& b) {
    return a.first > b.first;
};

// A leaf's phase in its re-query cycle: a fixed hash, so the checks spread over frames.
uint32_t phaseOf(uint32_t node) {
    uint32_t x = node * 0x9E3779B1u;
    x ^= x >> 15;
    return x * 0x85EBCA77u;
}

// Visits between polls of the oldest query while the traversal has nodes to visit.
constexpr uint32_t kVisitsPerPoll = 4;

double stayHiddenOdds(uint16_t invisibleFrames) { return 0.99 - 0.7 * std::exp(-double(invisibleFrames)); }

} // namespace

CoherentCulling::CoherentCulling(const InstanceHierarchy& hierarchy, CoherentCullingOptions options)
    : m_hierarchy(&hierarchy), m_options(options), m_nodes(hierarchy.nodeCount()) {
    m_options.visibleInterval = std::clamp(m_options.visibleInterval, 1, 1000);
    m_options.batchSize = std::clamp(m_options.batchSize, 1, 4096);
}

void CoherentCulling::reset() {
    m_nodes.assign(m_hierarchy ? m_hierarchy->nodeCount() : 0, NodeState{}); // a rebuilt tree may have more or fewer
    m_assumeVisible = true;
    m_discardLate = true;
}

void CoherentCulling::readLateChecks() {
    m_stillLate.clear();
    for (const LateCheck& check : m_lateQueries) {
        if (!m_discardLate && !m_queries->available(check.handle)) {
            m_stillLate.push_back(check); // not back yet: the leaf stays visible meanwhile
            continue;
        }
        const bool visible = m_queries->visible(check.handle);
        if (m_discardLate) continue;
        NodeState& s = m_nodes[check.node];
        s.checkPending = false;
        if (!visible) { // hidden now: this frame it is an i-queue node like any other
            s.visible = false;
            s.invisibleFrames = 1;
        }
    }
    m_lateQueries.swap(m_stillLate);
    m_discardLate = false;
}

CoherentCullingStats CoherentCulling::frame(std::span<const HalfSpace> frustum, const Vec3& wsEye, double nearMargin,
                                            OcclusionQueries& queries, std::vector<uint32_t>& drawn) {
    m_stats = {};
    drawn.clear();
    if (m_hierarchy == nullptr || m_nodes.empty()) return m_stats;
    ++m_frame;
    m_queries = &queries;
    m_frustum = frustum;
    m_wsEye = wsEye;
    m_nearMargin = std::max(nearMargin, 0.0);
    m_drawn = &drawn;
    m_queryNodes.clear();
    readLateChecks();

    m_distanceQueue.clear();
    m_distanceQueue.emplace_back(0.0, InstanceHierarchy::kRoot);
    uint32_t visitsSincePoll = 0;
    while (!m_distanceQueue.empty() || !m_invisibleQueue.empty() || !m_queryQueue.empty()) {
        // Results first, in issue order, as far as they have arrived; wait only when the
        // traversal has nothing left to do. While there is, results are polled every few
        // visits: a poll is a driver call, and a result a few nodes late costs nothing.
        const bool poll = m_distanceQueue.empty() || ++visitsSincePoll >= kVisitsPerPoll;
        if (poll) visitsSincePoll = 0;
        while (poll && !m_queryQueue.empty()) {
            if (!m_queryQueue.front().read && !queries.available(m_queryQueue.front().handle)) {
                if (!m_distanceQueue.empty()) break;
                if (!m_invisibleQueue.empty()) {
                    issueBatch();
                    continue;
                }
                // Results arrive in issue order: one wait, for the newest, brings every
                // older one with it (waiting for the oldest would wait once per submission).
                ++m_stats.waits;
                Query& newest = m_queryQueue.back();
                if (!newest.read) {
                    newest.visible = queries.visible(newest.handle);
                    newest.read = true;
                }
            }
            const Query query = m_queryQueue.front();
            m_queryQueue.pop_front();
            handle(query, query.read ? query.visible : queries.visible(query.handle));
        }
        if (!m_distanceQueue.empty()) {
            std::pop_heap(m_distanceQueue.begin(), m_distanceQueue.end(), kFarther);
            const uint32_t node = m_distanceQueue.back().second;
            m_distanceQueue.pop_back();
            visit(node);
        } else if (!m_invisibleQueue.empty()) {
            issueBatch();
        }
    }
    flushDraws();
    // The v-queue: drawn leaves due for a check, against the finished depth buffer.
    for (const uint32_t node : m_visibleQueue) {
        m_lateQueries.push_back({queries.issue({&node, 1}), node});
        ++m_stats.queriesIssued;
        ++m_stats.nodesQueried;
    }
    m_visibleQueue.clear();
    m_assumeVisible = false;
    m_queries = nullptr;
    m_drawn = nullptr;
    return m_stats;
}

void CoherentCulling::visit(uint32_t node) {
    ++m_stats.nodesVisited;
    const Aabb& box = m_hierarchy->nodeBounds(node);
    NodeState& s = m_nodes[node];
    const bool coherent = s.lastVisited + 1 == m_frame;
    const bool previouslyVisible = s.visible && coherent;
    const bool due = (m_frame + phaseOf(node)) % uint32_t(m_options.visibleInterval) == 0;
    // An inner node opened last frame stays open, though pull-up left it hidden (its box can
    // pass a query while every child's fails): asking it again would only open it again, a
    // round trip to the GPU per level at the end of every frame. It is asked again at its
    // due frame, and closes if hidden then.
    const bool keptOpen = s.open && coherent && !due;
    s.lastVisited = m_frame;
    if (isOutside(m_frustum, box)) {
        s.visible = s.open = false;
        return;
    }
    const bool holdsEye = box.distanceSquared(m_wsEye) <= m_nearMargin * m_nearMargin;
    if (!(m_assumeVisible || holdsEye || previouslyVisible || keptOpen)) {
        m_invisibleQueue.push_back(node);
        if (m_invisibleQueue.size() >= size_t(m_options.batchSize)) issueBatch();
        return;
    }
    if (m_hierarchy->isLeaf(node)) {
        drawLeaf(node);
        if (!holdsEye && !s.checkPending && (m_assumeVisible || due)) {
            m_visibleQueue.push_back(node);
            s.checkPending = true;
        }
        return;
    }
    s.visible = false; // until a descendant turns out visible (pullUpVisibility)
    s.open = true;
    pushChildren(node);
}

void CoherentCulling::pushChildren(uint32_t node) {
    const uint32_t left = m_hierarchy->leftChild(node);
    for (const uint32_t child : {left, left + 1}) {
        m_distanceQueue.emplace_back(m_hierarchy->nodeBounds(child).distanceSquared(m_wsEye), child);
        std::push_heap(m_distanceQueue.begin(), m_distanceQueue.end(), kFarther);
    }
}

void CoherentCulling::drawLeaf(uint32_t node) {
    for (const uint32_t item : m_hierarchy->leafItems(node)) {
        if (isOutside(m_frustum, m_hierarchy->itemBounds(item))) continue;
        m_pendingDraw.push_back(item);
        m_drawn->push_back(item);
        ++m_stats.itemsDrawn;
    }
    pullUpVisibility(node);
}

void CoherentCulling::pullUpVisibility(uint32_t node) {
    for (; node != UINT32_MAX && !m_nodes[node].visible; node = m_hierarchy->parent(node)) {
        m_nodes[node].visible = true;
        m_nodes[node].invisibleFrames = 0;
    }
}

void CoherentCulling::flushDraws() {
    if (m_pendingDraw.empty()) return;
    m_queries->draw(m_pendingDraw);
    m_pendingDraw.clear();
}

void CoherentCulling::issueBatch() {
    if (m_invisibleQueue.empty()) return;
    flushDraws(); // the queries must see every object found visible so far
    std::vector<uint32_t>& batch = m_invisibleQueue;
    // Long-hidden nodes together: they are the ones worth grouping.
    if (m_options.multiQueries)
        std::stable_sort(batch.begin(), batch.end(), [this](uint32_t a, uint32_t b) {
            return m_nodes[a].invisibleFrames > m_nodes[b].invisibleFrames;
        });
    size_t i = 0;
    while (i < batch.size()) {
        size_t n = 1;
        if (m_options.multiQueries) {
            double allHidden = stayHiddenOdds(m_nodes[batch[i]].invisibleFrames);
            double value = 1.0 / (1.0 + (1.0 - allHidden));
            while (i + n < batch.size()) {
                const double odds = allHidden * stayHiddenOdds(m_nodes[batch[i + n]].invisibleFrames);
                const double grown = double(n + 1) / (1.0 + (1.0 - odds) * double(n + 1));
                if (!(grown > value)) break;
                allHidden = odds;
                value = grown;
                ++n;
            }
        }
        const auto first = static_cast<uint32_t>(m_queryNodes.size());
        m_queryNodes.insert(m_queryNodes.end(), batch.begin() + std::ptrdiff_t(i),
                            batch.begin() + std::ptrdiff_t(i + n));
        const uint32_t handle = m_queries->issue({m_queryNodes.data() + first, n});
        m_queryQueue.push_back({handle, first, static_cast<uint32_t>(n)});
        ++m_stats.queriesIssued;
        m_stats.nodesQueried += n;
        i += n;
    }
    batch.clear();
}

void CoherentCulling::handle(const Query& query, bool visible) {
    if (visible && query.nodeCount > 1) {
        // Some node of the group is visible: ask each one (CHC++ §4.3).
        ++m_stats.multiQueryFailures;
        flushDraws();
        for (uint32_t k = 0; k < query.nodeCount; ++k) {
            const uint32_t node = m_queryNodes[query.firstNode + k];
            const auto first = static_cast<uint32_t>(m_queryNodes.size());
            m_queryNodes.push_back(node);
            m_queryQueue.push_back({m_queries->issue({&m_queryNodes[first], 1}), first, 1});
            ++m_stats.queriesIssued;
            ++m_stats.nodesQueried;
        }
        return;
    }
    for (uint32_t k = 0; k < query.nodeCount; ++k) {
        const uint32_t node = m_queryNodes[query.firstNode + k];
        NodeState& s = m_nodes[node];
        if (!visible) {
            s.visible = s.open = false;
            s.invisibleFrames = static_cast<uint16_t>(std::min<int>(s.invisibleFrames + 1, 1000));
            continue;
        }
        pullUpVisibility(node);
        if (m_hierarchy->isLeaf(node)) {
            drawLeaf(node);
            continue;
        }
        s.open = true;
        pushChildren(node); // opened now: its children were not visited last frame, so each is queried
    }
}

} // namespace shadowkit::visibility
