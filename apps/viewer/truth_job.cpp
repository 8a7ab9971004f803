#include "truth_job.h"

#include <chrono>

namespace shadowkit::viewer {

core::Status TruthJob::start(measure::Measurer& measurer, const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                             const core::ShadowSetup& setup, const gl::RenderSettings& settings) {
    if (running()) return core::makeError("truth: an evaluation is running already");
    auto raster = measurer.renderer().renderEvalBuffers(camera, light, setup, settings);
    if (!raster) return raster.errorInfo();
    m_raster = std::move(raster).value();
    m_progress = 0.0;
    m_truth = std::async(std::launch::async, [&measurer, camera, light, w = settings.width, h = settings.height, this] {
        return measurer.truth(camera, light, w, h, [this](double done) { m_progress = done; });
    });
    return core::Ok{};
}

std::optional<eval::Comparison> TruthJob::poll() {
    if (!running() || m_truth.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    const std::shared_ptr<const eval::TruthBuffers> truth = m_truth.get();
    auto comparison = eval::compare(m_raster, *truth);
    if (!comparison) return std::nullopt;
    return std::move(comparison).value();
}

} // namespace shadowkit::viewer
