// Coherent hierarchical culling (CHC++) over an InstanceHierarchy: which instances a camera
// pass must draw, found with occlusion queries whose results are reused from frame to
// frame. The traversal is pure logic; a renderer supplies the queries (OcclusionQueries).
#pragma once

#include "shadowkit/visibility/instance_hierarchy.h"

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

namespace shadowkit::visibility {

// What the traversal asks of a renderer. Query handles are the renderer's; each is read
// exactly once (visible()) and may be recycled after that.
class OcclusionQueries {
public:
    virtual ~OcclusionQueries() = default;
    // Draws these items now: their depth occludes the queries issued after.
    virtual void draw(std::span<const uint32_t> items) = 0;
    // Starts one query over the union of these nodes' boxes (depth-tested, no writes).
    virtual uint32_t issue(std::span<const uint32_t> nodes) = 0;
    // Whether a query's result has arrived. Never blocks.
    virtual bool available(uint32_t query) = 0;
    // The result — true when any sample passed —, waiting for it if it has not arrived.
    virtual bool visible(uint32_t query) = 0;
};

struct CoherentCullingOptions {
    // A visible leaf is assumed visible for this many frames before it is queried again
    // (CHC++ §4.2, n_av), each leaf at its own random phase so the queries spread evenly.
    int visibleInterval = 8; // [1, 1000]
    // Previously invisible nodes are queried in batches of this size (CHC++ §4.1, b).
    int batchSize = 32;       // [1, 4096]
    bool multiQueries = true; // CHC++ §4.3: one query for several nodes expected to stay hidden
};

struct CoherentCullingStats {
    size_t nodesVisited = 0;
    size_t queriesIssued = 0;      // occlusion queries started (a multi-query counts once)
    size_t nodesQueried = 0;       // nodes inside those queries
    size_t multiQueryFailures = 0; // multi-queries that came back visible (nodes re-queried)
    size_t waits = 0;              // results read in this frame that had not arrived: the CPU waited
    size_t itemsDrawn = 0;
};

class CoherentCulling {
public:
    CoherentCulling() = default;
    explicit CoherentCulling(const InstanceHierarchy& hierarchy, CoherentCullingOptions options = {});

    // Forget every node's history: the next frame draws everything in the frustum and
    // queries it (the conservative start after a camera cut, and after the hierarchy was
    // rebuilt: its nodes are new).
    void reset();

    // One frame. `frustum`: the camera's clip volume; `wsEye`: its centre; nodes whose box,
    // grown by `nearMargin` (the distance from the eye to the near plane's corners), holds the
    // eye are drawn without a query — their boxes would be clipped by the near plane. Draws
    // through `queries` and leaves in `drawn` every item it drew, in drawing order.
    CoherentCullingStats frame(std::span<const HalfSpace> frustum, const Vec3& wsEye, double nearMargin,
                               OcclusionQueries& queries, std::vector<uint32_t>& drawn);

    // Queries left running at the end of a frame (visible leaves' checks): read next frame.
    size_t pendingQueries() const { return m_lateQueries.size(); }

private:
    struct NodeState {
        uint32_t lastVisited = 0;     // frame number; 0: never
        uint16_t invisibleFrames = 0; // consecutive frames found invisible (multi-query odds)
        bool visible = false;
        bool checkPending = false; // a visible leaf's query is in flight
        bool open = false;         // an inner node opened last frame: its children are visited unqueried
    };
    struct Query {
        uint32_t handle = 0;
        uint32_t firstNode = 0, nodeCount = 0; // into m_queryNodes
        bool read = false, visible = false;    // read ahead of its turn (the newest, waited for)
    };
    struct LateCheck { // a visible leaf's query, read in a later frame
        uint32_t handle = 0, node = 0;
    };

    void readLateChecks();
    void visit(uint32_t node);
    void pushChildren(uint32_t node);
    void drawLeaf(uint32_t node);
    void pullUpVisibility(uint32_t node);
    void issueBatch();
    void handle(const Query& query, bool visible);
    void flushDraws();

    const InstanceHierarchy* m_hierarchy = nullptr;
    CoherentCullingOptions m_options;
    std::vector<NodeState> m_nodes;
    uint32_t m_frame = 0;
    bool m_assumeVisible = true; // first frame after a reset

    // Per frame.
    OcclusionQueries* m_queries = nullptr;
    std::span<const HalfSpace> m_frustum;
    Vec3 m_wsEye{0.0};
    double m_nearMargin = 0.0;
    std::vector<std::pair<double, uint32_t>> m_distanceQueue; // min-heap on distance
    std::vector<uint32_t> m_invisibleQueue, m_visibleQueue;   // CHC++'s i-queue and v-queue
    std::deque<Query> m_queryQueue;                           // issued, results awaited in order
    std::vector<uint32_t> m_queryNodes;                       // node lists of the frame's queries
    std::vector<LateCheck> m_lateQueries, m_stillLate;        // earlier frames' visible-leaf checks
    bool m_discardLate = false;                               // reset() since they were issued
    std::vector<uint32_t> m_pendingDraw, *m_drawn = nullptr;
    CoherentCullingStats m_stats;
};

} // namespace shadowkit::visibility
