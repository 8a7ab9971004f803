// Culling's own CPU cost, without a GPU: the CHC++ traversal (visibility::CoherentCulling) and
// the shadow pass's hierarchy query against a receiver mask (visibility::ReceiverMask), over the
// default forest at 10,000 and 100,000 trees, on the `perpendicular` view. The GPU's
// answers come from a stand-in: a node is visible when its box comes within 80 m of the
// eye (the forest hides what lies farther), answered at once, so the figures are the
// traversal's own work and none of the driver's. `shadowkit bench` measures the same steps
// with the GPU (its "cull" line).
//   build/bench/shadowkit_culling_bench
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"
#include "shadowkit/visibility/coherent_culling.h"
#include "shadowkit/visibility/instance_hierarchy.h"
#include "shadowkit/visibility/receiver_mask.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

namespace {

using namespace shadowkit;

constexpr double kHorizon = 80.0; // metres: the stand-in's occlusion

struct World {
    scene::Scene scene;
    visibility::InstanceHierarchy hierarchy;
    scene::ResolvedView view;
};

const World& world(int trees) {
    static std::map<int, std::unique_ptr<World>> worlds;
    auto& w = worlds[trees];
    if (!w) {
        scene::ForestOptions o;
        o.trees = trees;
        w = std::make_unique<World>();
        w->scene = scene::makeForest(o);
        w->hierarchy = visibility::InstanceHierarchy(w->scene.instanceBounds());
        const auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json").value();
        w->view = scene::resolveView(*scene::findView(views, "perpendicular"), w->scene);
    }
    return *w;
}

// Answers every query at once: visible when any node's box is within the horizon.
class HorizonQueries final : public visibility::OcclusionQueries {
public:
    HorizonQueries(const visibility::InstanceHierarchy& h, const core::Vec3& eye) : m_hierarchy(h), m_eye(eye) {}
    void draw(std::span<const uint32_t> items) override { benchmark::DoNotOptimize(items.data()); }
    uint32_t issue(std::span<const uint32_t> nodes) override {
        bool any = false;
        for (const uint32_t n : nodes) any |= m_hierarchy.nodeBounds(n).distanceSquared(m_eye) < kHorizon * kHorizon;
        m_results.push_back(any);
        return static_cast<uint32_t>(m_results.size() - 1);
    }
    bool available(uint32_t) override { return true; }
    bool visible(uint32_t query) override { return m_results[query]; }

private:
    const visibility::InstanceHierarchy& m_hierarchy;
    core::Vec3 m_eye;
    std::vector<bool> m_results;
};

void coherentCulling(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(0)));
    const core::PerspectiveCamera& camera = w.view.camera;
    const auto frustum = visibility::clipVolume(camera.clipFromWorld());
    visibility::CoherentCulling chc(w.hierarchy);
    HorizonQueries queries(w.hierarchy, camera.wsEye);
    std::vector<uint32_t> drawn;
    for (int warm = 0; warm < 10; ++warm)
        chc.frame(frustum, camera.wsEye, camera.zNear * 2.0, queries, drawn); // steady state
    visibility::CoherentCullingStats stats;
    for (auto _ : state) stats = chc.frame(frustum, camera.wsEye, camera.zNear * 2.0, queries, drawn);
    state.counters["nodes_visited"] = double(stats.nodesVisited);
    state.counters["queries"] = double(stats.queriesIssued);
    state.counters["items_drawn"] = double(stats.itemsDrawn);
}

void receiverMaskQuery(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(0)));
    const core::PerspectiveCamera& camera = w.view.camera;
    const core::ShadowSetupInputs inputs{.camera = camera,
                                         .light = w.view.light,
                                         .wsSceneBounds = w.scene.wsBounds(),
                                         .technique = core::Technique::Tsm};
    const core::ShadowSetup setup = core::computeShadowSetup(inputs).value();
    const core::ShadowView& view = setup.views[0];
    // The visible receivers: terrain within the horizon and the view frustum, every metre.
    visibility::ReceiverMask mask(128, view.clipFromWorld, view.linearDepthFromWorld);
    const auto frustum = visibility::clipVolume(camera.clipFromWorld());
    for (double x = -kHorizon; x <= kHorizon; x += 1.0)
        for (double z = -kHorizon; z <= kHorizon; z += 1.0) {
            const core::Vec3 p(camera.wsEye.x + x, 0.0, camera.wsEye.z + z);
            const core::Vec3 ground(p.x, w.scene.terrain->heightAt(p.x, p.z), p.z);
            if (!visibility::isOutside(frustum, core::Aabb::fromMinMax(ground, ground))) mask.mark(ground);
        }
    mask.finish(2);
    const auto volume = visibility::clipVolume(view.clipFromWorld, false);
    std::vector<uint32_t> casters;
    for (auto _ : state) {
        casters.clear();
        w.hierarchy.query(
            volume, [&mask](const core::Aabb& box) { return mask.mayShadow(box); }, casters);
        benchmark::DoNotOptimize(casters.data());
    }
    state.counters["casters"] = double(casters.size());
}

} // namespace

BENCHMARK(coherentCulling)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(receiverMaskQuery)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
