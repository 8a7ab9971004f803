// "Truth on demand": the evaluation of one frame with the ray tracer in a background thread,
// so the window keeps drawing while Embree works. The frame's GL evaluation buffers — the
// sun's and each local light's — are taken at once on the calling (GL) thread; the ray-traced
// truth, each light's reach and the comparisons follow on another thread (Measurer::truth and
// eval::underLight touch no GL); poll() hands the result back on the GL thread.
#pragma once

#include "shadowkit/measure/measurer.h"

#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::viewer {

struct TruthResult {
    std::vector<std::pair<std::string, eval::Comparison>> lights; // "sun", "point[0]", ...
    eval::Comparison combined;                                    // every light together (eval::combine)
    int width = 0, height = 0;
};

class TruthJob {
public:
    // Starts evaluating this frame (the renderer's frame: same camera, light, set-up,
    // settings, and the renderer's local lights).
    core::Status start(measure::Measurer& measurer, const core::PerspectiveCamera& camera,
                       const core::DirectionalLight& light, const core::ShadowSetup& setup,
                       const gl::RenderSettings& settings);
    bool running() const { return m_result.valid(); }
    bool ready() const { return running() && m_result.wait_for(std::chrono::seconds(0)) == std::future_status::ready; }
    double progress() const { return m_progress.load(); }
    // The result once it is back (then the job is idle again); an error string if it failed.
    std::optional<core::Result<TruthResult>> poll();

private:
    std::future<core::Result<TruthResult>> m_result;
    std::atomic<double> m_progress{0.0};
};

} // namespace shadowkit::viewer
