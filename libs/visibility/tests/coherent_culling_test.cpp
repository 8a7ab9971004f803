// CHC++ traversal against a stand-in for the GPU: a query says "visible" when a node holds
// an item of a known visible set, and its result arrives only once `latency` more queries
// have been issued after it (the GPU works through them in order), so the tests see the
// latency a real driver has. Reading a result that has not arrived blocks until the GPU has
// worked through that query (and every earlier one, in order); the read is counted. `leakyNodes` are inner nodes whose
// box passes though nothing under it is visible (a box holds empty space between its children's boxes).
#include "shadowkit/visibility/coherent_culling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

using namespace shadowkit::core;
using namespace shadowkit::visibility;

namespace {

class FakeQueries : public OcclusionQueries {
public:
    FakeQueries(const InstanceHierarchy& h, int latency) : m_h(h), m_latency(latency) {}

    std::set<uint32_t> visibleItems, leakyNodes;
    int frame = 0;
    size_t blockingReadsThisFrame = 0, blockingReadsOfEarlierFrames = 0, queries = 0, leakyQueries = 0;
    std::vector<uint32_t> drawnItems; // in the order draw() received them

    void draw(std::span<const uint32_t> items) override {
        drawnItems.insert(drawnItems.end(), items.begin(), items.end());
    }
    uint32_t issue(std::span<const uint32_t> nodes) override {
        bool any = false;
        for (const uint32_t n : nodes) any = any || holdsVisible(n) || leakyNodes.count(n);
        leakyQueries += std::any_of(nodes.begin(), nodes.end(), [this](uint32_t n) { return leakyNodes.count(n) > 0; });
        m_queries.push_back({any, m_queries.size() + size_t(m_latency), frame});
        ++queries;
        return static_cast<uint32_t>(m_queries.size() - 1);
    }
    bool available(uint32_t q) override { return m_queries[q].readyAt < m_queries.size(); }
    bool visible(uint32_t q) override {
        if (!available(q)) {
            ++(m_queries[q].frame == frame ? blockingReadsThisFrame : blockingReadsOfEarlierFrames);
            for (uint32_t earlier = 0; earlier <= q; ++earlier) m_queries[earlier].readyAt = 0; // worked through q
        }
        return m_queries[q].result;
    }

private:
    bool holdsVisible(uint32_t node) const {
        if (m_h.isLeaf(node)) {
            for (const uint32_t item : m_h.leafItems(node))
                if (visibleItems.count(item)) return true;
            return false;
        }
        return holdsVisible(m_h.leftChild(node)) || holdsVisible(m_h.leftChild(node) + 1);
    }
    struct Q {
        bool result;
        size_t readyAt; // arrived once more than this many queries exist (or the GPU was drained)
        int frame;
    };
    const InstanceHierarchy& m_h;
    int m_latency;
    std::vector<Q> m_queries;
};

// A 40 x 40 grid of 1 m boxes; the eye far off so nothing holds it.
InstanceHierarchy grid() {
    std::vector<Aabb> boxes;
    for (int z = 0; z < 40; ++z)
        for (int x = 0; x < 40; ++x)
            boxes.push_back(Aabb::fromMinMax(Vec3(3 * x, 0, 3 * z), Vec3(3 * x + 1, 1, 3 * z + 1)));
    return InstanceHierarchy(boxes);
}

const Vec3 kEye(60, 500, -400);

std::set<uint32_t> leafClosure(const InstanceHierarchy& h, const std::set<uint32_t>& items) {
    std::set<uint32_t> out;
    for (uint32_t node = 0; node < h.nodeCount(); ++node)
        if (h.isLeaf(node)) {
            const auto leaf = h.leafItems(node);
            if (std::any_of(leaf.begin(), leaf.end(), [&](uint32_t i) { return items.count(i) > 0; }))
                out.insert(leaf.begin(), leaf.end());
        }
    return out;
}

std::set<uint32_t> randomSubset(std::mt19937& rng, size_t n, double fraction) {
    std::bernoulli_distribution pick(fraction);
    std::set<uint32_t> s;
    for (uint32_t i = 0; i < n; ++i)
        if (pick(rng)) s.insert(i);
    return s;
}

} // namespace

TEST(CoherentCulling, FirstFrameDrawsTheWholeFrustumAndQueriesEveryLeaf) {
    const InstanceHierarchy h = grid();
    CoherentCulling chc(h);
    FakeQueries gpu(h, 2);
    gpu.visibleItems = {7};
    std::vector<uint32_t> drawn;
    // The frustum keeps x <= 60 (half the grid).
    const HalfSpace keepLeft(-1, 0, 0, 60);
    const CoherentCullingStats stats = chc.frame({&keepLeft, 1}, kEye, 0.5, gpu, drawn);
    std::vector<uint32_t> expected;
    h.query({&keepLeft, 1}, expected);
    std::sort(expected.begin(), expected.end());
    std::sort(drawn.begin(), drawn.end());
    EXPECT_EQ(drawn, expected);
    EXPECT_EQ(stats.waits, 0u); // nothing in the first frame needs a result
    EXPECT_GT(stats.queriesIssued, 0u);
    EXPECT_EQ(chc.pendingQueries(), stats.queriesIssued); // all read next frame
}

TEST(CoherentCulling, StaticViewConvergesToTheVisibleLeaves) {
    const InstanceHierarchy h = grid();
    std::mt19937 rng(3);
    CoherentCulling chc(h);
    FakeQueries gpu(h, 1);
    gpu.visibleItems = randomSubset(rng, h.size(), 0.05);
    std::vector<uint32_t> drawn;
    CoherentCullingStats stats;
    for (int f = 0; f < 30; ++f) {
        gpu.frame = f;
        stats = chc.frame({}, kEye, 0.5, gpu, drawn);
    }
    const std::set<uint32_t> got(drawn.begin(), drawn.end());
    EXPECT_EQ(got, leafClosure(h, gpu.visibleItems));
    EXPECT_EQ(got.size(), drawn.size()); // nothing drawn twice
    // Steady state: hidden subtrees cost one query each, far fewer than one per leaf.
    EXPECT_LT(stats.queriesIssued, h.nodeCount() / 4);
    EXPECT_EQ(gpu.blockingReadsOfEarlierFrames, 0u); // visible-leaf checks are never waited for
}

TEST(CoherentCulling, NeverMissesAnObjectThatBecameVisible) {
    const InstanceHierarchy h = grid();
    std::mt19937 rng(11);
    for (const bool multi : {true, false}) {
        CoherentCulling chc(h, {.multiQueries = multi});
        FakeQueries gpu(h, 3);
        std::vector<uint32_t> drawn;
        size_t waits = 0;
        for (int f = 0; f < 40; ++f) {
            gpu.frame = f;
            gpu.visibleItems = randomSubset(rng, h.size(), 0.03); // the view changes every frame
            waits += chc.frame({}, kEye, 0.5, gpu, drawn).waits;
            const std::set<uint32_t> got(drawn.begin(), drawn.end());
            for (const uint32_t item : gpu.visibleItems)
                ASSERT_TRUE(got.count(item)) << "frame " << f << " item " << item;
        }
        EXPECT_EQ(waits, gpu.blockingReadsThisFrame); // every wait is counted
        EXPECT_EQ(gpu.blockingReadsOfEarlierFrames, 0u);
    }
}

TEST(CoherentCulling, AFrameWaitsOncePerRoundTripNotOncePerQuery) {
    // A GPU so slow that no result arrives by itself within the frame: every result must be
    // waited for. After a static view has converged, a new set becomes visible: the hidden
    // nodes' results are all needed at the end of the frame. Results arrive in order, so a
    // wait for the newest brings every older one; more waits are needed only for what those
    // results open (children, a failed multi-query's nodes): at most two per tree level.
    const InstanceHierarchy h = grid();
    int depth = 0;
    for (uint32_t node = 0; node < h.nodeCount(); ++node) {
        int d = 0;
        for (uint32_t n = node; n != InstanceHierarchy::kRoot; n = h.parent(n)) ++d;
        depth = std::max(depth, d);
    }
    std::mt19937 rng(17);
    CoherentCulling chc(h);
    FakeQueries gpu(h, 1 << 20);
    gpu.visibleItems = randomSubset(rng, h.size(), 0.05);
    std::vector<uint32_t> drawn;
    for (int f = 0; f < 20; ++f) {
        gpu.frame = f;
        chc.frame({}, kEye, 0.5, gpu, drawn);
    }
    gpu.frame = 20;
    gpu.visibleItems = randomSubset(rng, h.size(), 0.05);
    const size_t readsBefore = gpu.blockingReadsThisFrame;
    const CoherentCullingStats stats = chc.frame({}, kEye, 0.5, gpu, drawn);
    const std::set<uint32_t> got(drawn.begin(), drawn.end());
    for (const uint32_t item : gpu.visibleItems) ASSERT_TRUE(got.count(item)) << item;
    EXPECT_GT(stats.queriesIssued, size_t(4 * depth)); // many results were needed...
    EXPECT_LE(stats.waits, size_t(2 * depth + 1));     // ...in few round trips
    EXPECT_EQ(stats.waits, gpu.blockingReadsThisFrame - readsBefore);
}

TEST(CoherentCulling, InnerBoxesThatPassOverHiddenChildrenStayOpenInsteadOfBeingAskedEveryFrame) {
    // Nothing is visible, but the top three levels' boxes pass (a box's empty space shows):
    // asked every frame they would pass, be opened, and cost a round trip per level before
    // their hidden children could be asked. Kept open, they are asked only at their due
    // frame (every visibleInterval frames), and the children are asked in the first round.
    const InstanceHierarchy h = grid();
    CoherentCulling chc(h);
    FakeQueries gpu(h, 2);
    const uint32_t left = h.leftChild(InstanceHierarchy::kRoot);
    gpu.leakyNodes = {InstanceHierarchy::kRoot, left, left + 1, h.leftChild(left), h.leftChild(left) + 1};
    std::vector<uint32_t> drawn;
    size_t leakyBefore = 0;
    for (int f = 0; f < 40; ++f) {
        gpu.frame = f;
        if (f == 20) leakyBefore = gpu.leakyQueries;
        chc.frame({}, kEye, 0.5, gpu, drawn);
        if (f >= 3) { // the first frame draws the frustum; its checks arrive over the next two
            EXPECT_TRUE(drawn.empty()) << "frame " << f;
        }
    }
    // In 20 frames each leaky node is due at most 3 times (CoherentCullingOptions::
    // visibleInterval = 8), asked in a multi-query and, when that passes, alone: at most 6
    // queries, against 20 if it were asked every frame.
    EXPECT_LE(gpu.leakyQueries - leakyBefore, gpu.leakyNodes.size() * 6);
    EXPECT_LT(gpu.leakyQueries - leakyBefore, gpu.leakyNodes.size() * 20 / 2);
}

TEST(CoherentCulling, MultiQueriesSaveQueriesOnLongHiddenNodes) {
    const InstanceHierarchy h = grid();
    std::mt19937 rng(5);
    const std::set<uint32_t> visible = randomSubset(rng, h.size(), 0.2);
    size_t queries[2] = {0, 0};
    for (const bool multi : {false, true}) {
        CoherentCulling chc(h, {.multiQueries = multi});
        FakeQueries gpu(h, 0);
        gpu.visibleItems = visible;
        std::vector<uint32_t> drawn;
        for (int f = 0; f < 40; ++f) {
            gpu.frame = f;
            const CoherentCullingStats stats = chc.frame({}, kEye, 0.5, gpu, drawn);
            if (f >= 20) queries[multi] += stats.queriesIssued;
        }
        EXPECT_EQ(std::set<uint32_t>(drawn.begin(), drawn.end()), leafClosure(h, visible));
    }
    EXPECT_LT(queries[1], queries[0]);
}

TEST(CoherentCulling, NodesHoldingTheEyeAreDrawnWithoutAQuery) {
    const InstanceHierarchy h = grid();
    CoherentCulling chc(h);
    FakeQueries gpu(h, 0); // nothing is visible to the queries
    std::vector<uint32_t> drawn;
    const Vec3 eye(0.5, 0.5, 0.5); // inside item 0's box
    for (int f = 0; f < 10; ++f) {
        gpu.frame = f;
        chc.frame({}, eye, 0.3, gpu, drawn);
    }
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), 0u), drawn.end());
}

TEST(CoherentCulling, ResetStartsOverConservatively) {
    const InstanceHierarchy h = grid();
    CoherentCulling chc(h);
    FakeQueries gpu(h, 0);
    std::vector<uint32_t> drawn;
    for (int f = 0; f < 10; ++f) {
        gpu.frame = f;
        chc.frame({}, kEye, 0.5, gpu, drawn);
    }
    EXPECT_TRUE(drawn.empty()); // nothing visible
    chc.reset();
    gpu.frame = 10;
    chc.frame({}, kEye, 0.5, gpu, drawn);
    EXPECT_EQ(drawn.size(), h.size());
}
