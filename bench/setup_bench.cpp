// CPU cost of steps 1-2 of the pipeline (focus body + parameterization) per technique,
// on the standard views over the default forest's bounds (docs/references.md, evaluation §4).
//   build/bench/shadowkit_setup_bench
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <benchmark/benchmark.h>

#include <string>

namespace {

using namespace shadowkit;

// The default forest is built once: only its bounds and ground height matter here.
const scene::Scene& forest() {
    static const scene::Scene s = [] {
        scene::ForestOptions o;
        o.trees = 10000;
        return scene::makeForest(o);
    }();
    return s;
}

void setupForView(benchmark::State& state, core::Technique technique, const std::string& viewName) {
    const auto views = scene::loadViews(scene::dataDirectory() / "views.json");
    if (!views) {
        state.SkipWithError(views.error().c_str());
        return;
    }
    const scene::ResolvedView view = scene::resolveView(*scene::findView(*views, viewName), forest());
    const core::ShadowSetupInputs inputs{.camera = view.camera, .light = view.light,
                                         .wsSceneBounds = forest().wsBounds(), .technique = technique};
    for (auto _ : state) {
        auto setup = core::computeShadowSetup(inputs);
        benchmark::DoNotOptimize(setup);
    }
}

void registerAll() {
    for (const core::TechniqueInfo& t : core::allTechniques())
        for (const char* view : {"perpendicular", "sun-behind", "aerial"})
            benchmark::RegisterBenchmark(("setup/" + std::string(t.name) + "/" + view).c_str(), setupForView, t.technique,
                                         std::string(view))
                ->Unit(benchmark::kMicrosecond);
}

} // namespace

int main(int argc, char** argv) {
    registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
