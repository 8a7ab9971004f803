// CPU cost of --technique auto's choice per frame (issue 16): the sampling model over the
// receivers and the parameter search. auto/full: the full search (core::chooseAuto, what the
// first frame of a path and every still view costs) on standard views; auto/path: a frame
// along the flythrough path once its candidates are tracked (core::AutoChooser). The receivers
// are the ground the camera sees (rays through a grid of pixels meeting the terrain's mean
// height), as many as a read-back gives.
//   build/bench/shadowkit_error_driven_bench
#include "bench_scenes.h"
#include "shadowkit/core/auto_chooser.h"
#include "shadowkit/scene/camera_path.h"

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <string>

namespace {

using namespace shadowkit;

std::vector<core::ReceiverSample> groundSamples(const core::PerspectiveCamera& camera, double groundY, int count) {
    std::vector<core::ReceiverSample> out;
    const core::Mat4 worldFromView = glm::inverse(camera.viewFromWorld());
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
    const int columns = static_cast<int>(std::sqrt(count * camera.aspect)) + 1, rows = count / columns + 1;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < columns; ++x) {
            const double ndcX = 2.0 * (x + 0.5) / columns - 1.0, ndcY = 1.0 - 2.0 * (y + 0.5) / rows;
            const core::Vec3 d(worldFromView * core::Vec4(ndcX * tanY * camera.aspect, ndcY * tanY, -1.0, 0.0));
            if (d.y >= 0.0) continue;
            const double t = (groundY - camera.wsEye.y) / d.y;
            if (t * glm::length(d) < camera.zFar) out.push_back({camera.wsEye + t * d, core::Vec3(0.0, 1.0, 0.0)});
        }
    return out;
}

void chooseForView(benchmark::State& state, const std::string& viewName, int samples, int cascades) {
    const auto resolved = bench::standardView(viewName);
    if (!resolved) {
        state.SkipWithError(resolved.error().c_str());
        return;
    }
    const scene::ResolvedView& view = *resolved;
    const core::Aabb bounds = bench::defaultForest().wsBounds();
    const core::ShadowSetupInputs inputs{.camera = view.camera, .light = view.light, .wsSceneBounds = bounds};
    const auto receivers =
        groundSamples(view.camera, 0.5 * (bounds.min.y + bounds.max.y) - 0.25 * (bounds.max.y - bounds.min.y), samples);
    core::AutoOptions options;
    options.texelBudget = int64_t(4) << 20;
    options.cascades = cascades;
    for (auto _ : state) {
        auto model = core::SamplingErrorModel::create(view.camera, 1280, 720, receivers);
        auto choice = core::chooseAuto(inputs, options, *model);
        benchmark::DoNotOptimize(choice);
    }
    state.counters["samples"] = double(receivers.size());
}

// Every frame of the flythrough after the first, in order, round and round: the per-frame cost
// of tracking. The first frame's full search (and the one after each wrap) is not timed.
void trackAlongPath(benchmark::State& state, int cascades) {
    const auto views = bench::flythroughViews(bench::defaultForest());
    if (!views) {
        state.SkipWithError(views.error().c_str());
        return;
    }
    const core::Aabb bounds = bench::defaultForest().wsBounds();
    const double groundY = 0.5 * (bounds.min.y + bounds.max.y) - 0.25 * (bounds.max.y - bounds.min.y);
    std::vector<core::ShadowSetupInputs> frames;
    std::vector<std::vector<core::ReceiverSample>> receivers;
    for (const scene::ResolvedView& view : *views) {
        frames.push_back({.camera = view.camera, .light = view.light, .wsSceneBounds = bounds});
        receivers.push_back(groundSamples(view.camera, groundY, 4096));
    }
    const int width = views->front().width, height = views->front().height;
    core::AutoOptions options;
    options.texelBudget = int64_t(4) << 20;
    options.cascades = cascades;
    core::AutoChooser chooser(options);
    size_t frame = 0;
    for (auto _ : state) {
        if (frame == 0) {
            state.PauseTiming();
            chooser.reset();
            benchmark::DoNotOptimize(chooser.choose(frames[0], width, height, receivers[0]));
            frame = 1;
            state.ResumeTiming();
        }
        auto choice = chooser.choose(frames[frame], width, height, receivers[frame]);
        benchmark::DoNotOptimize(choice);
        frame = (frame + 1) % frames.size();
    }
    state.counters["receivers"] = double(receivers[1].size());
}

void registerAll() {
    for (const int cascades : {1, 0, 4}) {
        const std::string maps = cascades == 1   ? "single"
                                 : cascades == 0 ? "any-count"
                                                 : std::to_string(cascades) + "-cascades";
        benchmark::RegisterBenchmark(("auto/path/" + maps + "/flythrough").c_str(), trackAlongPath, cascades)
            ->Unit(benchmark::kMillisecond);
    }
    for (const char* view : {"perpendicular", "aerial"})
        for (const int samples : {4096, 512})
            for (const int cascades : {1, 0})
                benchmark::RegisterBenchmark(("auto/full/" + std::string(cascades == 1 ? "single" : "any-count") + "/" +
                                              std::to_string(samples) + "/" + view)
                                                 .c_str(),
                                             chooseForView, std::string(view), samples, cascades)
                    ->Unit(benchmark::kMillisecond);
}

} // namespace

int main(int argc, char** argv) {
    registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    return 0;
}
