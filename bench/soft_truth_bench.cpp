// The soft truth's cost (issue 34's target: a 1280 x 720 view at 256 samples in the penumbrae
// in at most 10 s here): the real sun (0.53°) over the default forest, and over the leafy one
// (leaf cards: an alpha test on every candidate hit, and most of the ground under a canopy in a
// penumbra), each of the six sunlit standard views in turn, so no iteration repeats the last
// one's rays. The surface points come from the hard truth, computed once per view outside the
// timing.
#include "bench_scenes.h"

#include "shadowkit/eval/soft_truth.h"

#include <benchmark/benchmark.h>

#include <memory>

namespace {

using namespace shadowkit;

struct ViewPoints {
    std::string name;
    eval::TruthBuffers hits;
    core::Vec3 wsTowardsSun;
};

// range(0): samples per penumbra point; range(1): 1 for the leafy forest.
void softTruth(benchmark::State& state) {
    const scene::Scene& forest = state.range(1) != 0 ? bench::leafyForest() : bench::defaultForest();
    auto rays = eval::RayScene::build(forest);
    if (!rays) return state.SkipWithError(rays.error().c_str());
    std::vector<ViewPoints> views;
    for (const char* name : {"paper", "perpendicular", "into-sun", "sun-behind", "noon", "aerial"}) {
        auto view = bench::standardView(name, forest);
        if (!view) return state.SkipWithError(view.error().c_str());
        views.push_back({name, eval::computeTruth(**rays, view->camera, view->light, view->width, view->height),
                         view->light.wsTowardsLight()});
    }
    eval::SoftTruthOptions options;
    options.samples = static_cast<int>(state.range(0));
    size_t next = 0;
    uint64_t rayCount = 0, penumbra = 0, points = 0;
    for (auto _ : state) {
        const ViewPoints& v = views[next++ % views.size()];
        const eval::SoftTruth soft = eval::computeSoftTruth(**rays, v.hits, {v.wsTowardsSun, 0.53}, options);
        benchmark::DoNotOptimize(soft.visibility.data());
        rayCount += soft.rays;
        penumbra += soft.penumbraPoints;
        points += soft.visibility.size();
    }
    state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rayCount), benchmark::Counter::kIsRate);
    state.counters["penumbra_pct"] = 100.0 * static_cast<double>(penumbra) / static_cast<double>(points);
    state.counters["rays_per_pixel"] = static_cast<double>(rayCount) / static_cast<double>(points);
}

} // namespace

// One iteration is one view (1280 x 720 or the view's own size), six iterations all six.
BENCHMARK(softTruth)
    ->ArgNames({"samples", "leafy"})
    ->Args({64, 0})
    ->Args({256, 0})
    ->Args({256, 1})
    ->Iterations(6)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

BENCHMARK_MAIN();
