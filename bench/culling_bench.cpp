// Culling's own CPU cost, without a GPU: the CHC++ traversal (visibility::CoherentCulling) and
// the shadow pass's hierarchy query against a receiver mask (visibility::ReceiverMask), over the
// default forest at 10,000 and 100,000 trees. The GPU's answers come from a stand-in: a node
// is visible when its box comes within 80 m of the eye (the forest hides what lies farther),
// answered at once, so the figures are the traversal's own work and none of the driver's.
// `shadowkit bench` measures the same steps with the GPU (its "cull" line).
//   build/bench/shadowkit_culling_bench
//   culling/chc/flythrough/N          each iteration the next camera of the `flythrough` path,
//                                     round and round: what a moving camera pays a frame
//   culling/chc/still-perpendicular/N one still camera, after 10 frames: CHC++'s best case (its
//                                     queries' answers never change), as `shadowkit bench`'s
//                                     still view measures it in docs/scale-and-visibility.md
//   culling/mask-query/...            the same two for the caster query against a receiver mask
//                                     (each frame's own TSM map and mask, built untimed)
#include "bench_scenes.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"
#include "shadowkit/visibility/coherent_culling.h"
#include "shadowkit/visibility/instance_hierarchy.h"
#include "shadowkit/visibility/receiver_mask.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace shadowkit;

constexpr double kHorizon = 80.0; // metres: the stand-in's occlusion

struct World {
    scene::Scene scene;
    visibility::InstanceHierarchy hierarchy;
    std::vector<scene::ResolvedView> path;  // the flythrough's frames
    std::vector<scene::ResolvedView> still; // `perpendicular`
    const std::vector<scene::ResolvedView>& frames(bool moving) const { return moving ? path : still; }
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
        w->path = bench::flythroughViews(w->scene).value();
        const auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json").value();
        w->still = {scene::resolveView(*scene::findView(views, "perpendicular"), w->scene)};
    }
    return *w;
}

// Answers every query at once: visible when any node's box is within the horizon of the eye of
// the frame being culled.
class HorizonQueries final : public visibility::OcclusionQueries {
public:
    explicit HorizonQueries(const visibility::InstanceHierarchy& h) : m_hierarchy(h) {}
    void setEye(const core::Vec3& eye) { m_eye = eye; }
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
    core::Vec3 m_eye{0.0};
    std::vector<bool> m_results;
};

void coherentCulling(benchmark::State& state, int trees, bool moving) {
    const World& w = world(trees);
    const std::vector<scene::ResolvedView>& views = w.frames(moving);
    std::vector<std::vector<visibility::HalfSpace>> frustums;
    for (const scene::ResolvedView& v : views) frustums.push_back(visibility::clipVolume(v.camera.clipFromWorld()));
    visibility::CoherentCulling chc(w.hierarchy);
    HorizonQueries queries(w.hierarchy);
    std::vector<uint32_t> drawn;
    size_t frame = 0;
    const auto cull = [&] {
        const core::PerspectiveCamera& camera = views[frame].camera;
        queries.setEye(camera.wsEye);
        const auto stats = chc.frame(frustums[frame], camera.wsEye, camera.zNear * 2.0, queries, drawn);
        frame = (frame + 1) % views.size();
        return stats;
    };
    for (int warm = 0; warm < 10; ++warm) cull(); // past the first frame's full traversal
    double nodes = 0.0, issued = 0.0, items = 0.0;
    for (auto _ : state) {
        const visibility::CoherentCullingStats stats = cull();
        nodes += double(stats.nodesVisited), issued += double(stats.queriesIssued), items += double(stats.itemsDrawn);
    }
    const double n = std::max<double>(double(state.iterations()), 1.0);
    state.counters["nodes_visited"] = nodes / n;
    state.counters["queries"] = issued / n;
    state.counters["items_drawn"] = items / n;
}

// A frame's shadow-caster query: its TSM map's volume and the mask of its visible receivers.
struct MaskFrame {
    std::vector<visibility::HalfSpace> volume;
    visibility::ReceiverMask mask;
};

MaskFrame maskFrame(const World& w, const scene::ResolvedView& v) {
    const core::PerspectiveCamera& camera = v.camera;
    const core::ShadowSetupInputs inputs{
        .camera = camera, .light = v.light, .wsSceneBounds = w.scene.wsBounds(), .technique = core::Technique::Tsm};
    const core::ShadowView view = core::computeShadowSetup(inputs).value().views[0];
    // The visible receivers: terrain within the horizon and the view frustum, every metre.
    MaskFrame f{visibility::clipVolume(view.clipFromWorld, false),
                visibility::ReceiverMask(128, view.clipFromWorld, view.linearDepthFromWorld)};
    const auto frustum = visibility::clipVolume(camera.clipFromWorld());
    for (double x = -kHorizon; x <= kHorizon; x += 1.0)
        for (double z = -kHorizon; z <= kHorizon; z += 1.0) {
            const core::Vec3 p(camera.wsEye.x + x, 0.0, camera.wsEye.z + z);
            const core::Vec3 ground(p.x, w.scene.terrain->heightAt(p.x, p.z), p.z);
            if (!visibility::isOutside(frustum, core::Aabb::fromMinMax(ground, ground))) f.mask.mark(ground);
        }
    f.mask.finish(2);
    return f;
}

void receiverMaskQuery(benchmark::State& state, int trees, bool moving) {
    const World& w = world(trees);
    std::vector<MaskFrame> frames;
    for (const scene::ResolvedView& v : w.frames(moving)) frames.push_back(maskFrame(w, v));
    std::vector<uint32_t> casters;
    size_t frame = 0;
    double found = 0.0;
    for (auto _ : state) {
        const MaskFrame& f = frames[frame];
        casters.clear();
        w.hierarchy.query(
            f.volume, [&f](const core::Aabb& box) { return f.mask.mayShadow(box); }, casters);
        benchmark::DoNotOptimize(casters.data());
        found += double(casters.size());
        frame = (frame + 1) % frames.size();
    }
    state.counters["casters"] = found / std::max<double>(double(state.iterations()), 1.0);
}

void registerAll() {
    for (const bool moving : {true, false})
        for (const int trees : {10000, 100000}) {
            const std::string where = (moving ? "flythrough/" : "still-perpendicular/") + std::to_string(trees);
            benchmark::RegisterBenchmark(("culling/chc/" + where).c_str(), coherentCulling, trees, moving)
                ->Unit(benchmark::kMicrosecond);
            benchmark::RegisterBenchmark(("culling/mask-query/" + where).c_str(), receiverMaskQuery, trees, moving)
                ->Unit(benchmark::kMicrosecond);
        }
}

} // namespace

int main(int argc, char** argv) {
    registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
