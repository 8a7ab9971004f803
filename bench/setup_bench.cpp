// CPU cost of steps 1-2 of the pipeline (focus body + parameterization) per technique, as a
// running application pays it: every iteration is the next camera of the `flythrough` path
// (240 frames, round and round), so no two consecutive iterations share their inputs and no
// remembered focus body (computeFocusBody keeps the last one per thread) is ever reused.
//   setup/<technique>/flythrough           the path's own sun, rising 10° over the path
//   setup/<technique>/flythrough-sun-held  the sun held where it stands at the first frame
//   setup/csm-<N>/...                      cascades, N splits
//   setup/still-cached/<technique>/<view>  one still camera: after the first iteration the
//                                          focus body is the remembered one — the cached path,
//                                          what a paused frame costs, not a moving one
//   body/visible/flythrough                the focus body's first half alone, V ∩ S
//   body/focus/flythrough                  the whole focus body B (V ∩ S, then its sweep)
//   build/bench/shadowkit_setup_bench [--benchmark_repetitions=5]
#include "bench_scenes.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/camera_path.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

using namespace shadowkit;

struct Technique {
    std::string name;
    core::Technique technique;
    int cascades = 4;
};

std::vector<Technique> techniques() {
    std::vector<Technique> out;
    for (const core::TechniqueInfo& t : core::allTechniques())
        if (t.technique != core::Technique::Csm) out.push_back({std::string(t.name), t.technique});
    for (const int splits : {2, 4, 8}) out.push_back({"csm-" + std::to_string(splits), core::Technique::Csm, splits});
    return out;
}

core::ShadowSetupInputs inputsFor(const Technique& t, const core::PerspectiveCamera& camera,
                                  const core::DirectionalLight& light) {
    core::ShadowSetupInputs in{
        .camera = camera, .light = light, .wsSceneBounds = bench::defaultForest().wsBounds(), .technique = t.technique};
    in.cascades.count = t.cascades;
    return in;
}

// The flythrough's frames as set-up inputs; with `holdSun`, every frame under the first one's sun.
std::vector<core::ShadowSetupInputs> pathFrames(const Technique& t, bool holdSun, std::string& error) {
    const auto views = bench::flythroughViews(bench::defaultForest());
    if (!views) {
        error = views.error();
        return {};
    }
    std::vector<core::ShadowSetupInputs> frames;
    for (const scene::ResolvedView& view : *views) {
        const core::DirectionalLight light = holdSun && !frames.empty() ? frames.front().light : view.light;
        frames.push_back(inputsFor(t, view.camera, light));
    }
    return frames;
}

// Each iteration `work(frame)` on the next of the path's frames, round and round.
template <class Work>
void alongPath(benchmark::State& state, const Technique& t, bool holdSun, Work work) {
    std::string error;
    const std::vector<core::ShadowSetupInputs> frames = pathFrames(t, holdSun, error);
    if (frames.empty()) {
        state.SkipWithError(error.c_str());
        return;
    }
    size_t frame = 0;
    for (auto _ : state) {
        auto result = work(frames[frame]);
        benchmark::DoNotOptimize(result);
        frame = (frame + 1) % frames.size();
    }
    state.counters["frames"] = double(frames.size());
}

void setupAlongPath(benchmark::State& state, const Technique& t, bool holdSun) {
    alongPath(state, t, holdSun, [](const core::ShadowSetupInputs& in) { return core::computeShadowSetup(in); });
}

// The parts of a set-up that build the focus body, along the same path (sun moving).
void bodyAlongPath(benchmark::State& state, bool wholeBody) {
    alongPath(state, {"focused", core::Technique::Focused}, false, [wholeBody](const core::ShadowSetupInputs& in) {
        return wholeBody ? core::computeFocusBody(in.camera, in.light, in.wsSceneBounds)
                         : core::visibleSceneBody(in.camera, in.wsSceneBounds);
    });
}

void setupStillCached(benchmark::State& state, const Technique& t, const std::string& viewName) {
    const auto resolved = bench::standardView(viewName);
    if (!resolved) {
        state.SkipWithError(resolved.error().c_str());
        return;
    }
    const core::ShadowSetupInputs inputs = inputsFor(t, resolved->camera, resolved->light);
    for (auto _ : state) {
        auto setup = core::computeShadowSetup(inputs);
        benchmark::DoNotOptimize(setup);
    }
}

void registerAll() {
    for (const Technique& t : techniques())
        for (const bool holdSun : {false, true})
            benchmark::RegisterBenchmark(
                ("setup/" + t.name + (holdSun ? "/flythrough-sun-held" : "/flythrough")).c_str(), setupAlongPath, t,
                holdSun)
                ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("body/visible/flythrough", bodyAlongPath, false)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("body/focus/flythrough", bodyAlongPath, true)->Unit(benchmark::kMicrosecond);
    for (const Technique& t : techniques())
        for (const char* view : {"perpendicular", "sun-behind", "aerial"})
            benchmark::RegisterBenchmark(("setup/still-cached/" + t.name + "/" + view).c_str(), setupStillCached, t,
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
