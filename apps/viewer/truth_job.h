// "Truth on demand": the evaluation of one frame with the ray tracer in a background thread,
// so the window keeps drawing while Embree works. The frame's GL evaluation buffers are taken
// at once on the calling (GL) thread; the ray-traced truth follows on another thread
// (measure::Measurer::truth, which touches no GL); the comparison runs back on the GL
// thread when it is done (poll()).
#pragma once

#include "shadowkit/measure/measurer.h"

#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <optional>

namespace shadowkit::viewer {

class TruthJob {
public:
    // Starts evaluating this frame (the renderer's frame: same camera, light, set-up, settings).
    core::Status start(measure::Measurer& measurer, const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                       const core::ShadowSetup& setup, const gl::RenderSettings& settings);
    bool running() const { return m_truth.valid(); }
    double progress() const { return m_progress.load(); }
    bool ready() const { return running() && m_truth.wait_for(std::chrono::seconds(0)) == std::future_status::ready; }
    int width() const { return m_raster.width; } // of the frame evaluated last
    int height() const { return m_raster.height; }
    // The comparison, once the truth is back (then the job is idle again).
    std::optional<eval::Comparison> poll();

private:
    core::RasterBuffers m_raster;
    std::future<std::shared_ptr<const eval::TruthBuffers>> m_truth;
    std::atomic<double> m_progress{0.0};
};

} // namespace shadowkit::viewer
