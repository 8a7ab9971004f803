// CPU cost of steps 1-2 of the pipeline (focus body + parameterization) per technique,
// on the standard views over the default forest's bounds (docs/references.md, evaluation §4).
//   build/bench/shadowkit_setup_bench
#include "bench_scenes.h"
#include "shadowkit/core/shadow_setup.h"

#include <benchmark/benchmark.h>

#include <string>

namespace {

using namespace shadowkit;

void setupForView(benchmark::State& state, core::Technique technique, const std::string& viewName) {
    const auto resolved = bench::standardView(viewName);
    if (!resolved) {
        state.SkipWithError(resolved.error().c_str());
        return;
    }
    const scene::ResolvedView& view = *resolved;
    const core::ShadowSetupInputs inputs{.camera = view.camera,
                                         .light = view.light,
                                         .wsSceneBounds = bench::defaultForest().wsBounds(),
                                         .technique = technique};
    for (auto _ : state) {
        auto setup = core::computeShadowSetup(inputs);
        benchmark::DoNotOptimize(setup);
    }
}

void registerAll() {
    for (const core::TechniqueInfo& t : core::allTechniques())
        for (const char* view : {"perpendicular", "sun-behind", "aerial"})
            benchmark::RegisterBenchmark(("setup/" + std::string(t.name) + "/" + view).c_str(), setupForView,
                                         t.technique, std::string(view))
                ->Unit(benchmark::kMicrosecond);
}

} // namespace

int main(int argc, char** argv) {
    registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
