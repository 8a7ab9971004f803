#include "truth_job.h"

#include "shadowkit/eval/truth.h"

#include <memory>

namespace shadowkit::viewer {

core::Status TruthJob::start(measure::Measurer& measurer, const core::PerspectiveCamera& camera,
                             const core::DirectionalLight& light, const core::ShadowSetup& setup,
                             const gl::RenderSettings& settings) {
    if (running()) return core::makeError("truth: an evaluation is running already");
    gl::Renderer& renderer = measurer.renderer();
    // GL work now: every light's evaluation buffers.
    struct Part {
        std::string name;
        core::RasterBuffers raster;
    };
    auto parts = std::make_shared<std::vector<Part>>();
    if (settings.sun) {
        auto raster = renderer.renderEvalBuffers(camera, light, setup, settings);
        if (!raster) return raster.errorInfo();
        parts->push_back({"sun", std::move(raster).value()});
    }
    const core::LocalLighting local = renderer.localLights();
    for (size_t i = 0; i < local.size(); ++i) {
        auto raster = renderer.renderEvalBuffers(camera, light, setup, settings, static_cast<int>(i));
        if (!raster) return raster.errorInfo();
        const bool point = i < local.points.size();
        parts->push_back(
            {(point ? "point[" + std::to_string(i) : "spot[" + std::to_string(i - local.points.size())) + "]",
             std::move(raster).value()});
    }
    if (parts->empty()) return core::makeError("truth: no light to evaluate");
    m_progress = 0.0;
    // Then the rays, off the GL thread.
    m_result = std::async(
        std::launch::async,
        [&measurer, camera, light, local, parts, w = settings.width, h = settings.height,
         this]() -> core::Result<TruthResult> {
            const std::shared_ptr<const eval::TruthBuffers> truth =
                measurer.truth(camera, light, w, h, [this](double done) { m_progress = 0.8 * done; });
            TruthResult result{.width = w, .height = h};
            std::vector<const eval::Comparison*> all;
            size_t localIndex = 0;
            for (const Part& part : *parts) {
                eval::TruthBuffers lightTruth;
                if (part.name != "sun") {
                    const size_t i = localIndex++;
                    lightTruth = i < local.points.size()
                                     ? eval::underLight(measurer.rays(), *truth, local.points[i])
                                     : eval::underLight(measurer.rays(), *truth, local.spots[i - local.points.size()]);
                }
                auto comparison = eval::compare(part.raster, part.name == "sun" ? *truth : lightTruth);
                if (!comparison) return comparison.errorInfo();
                result.lights.emplace_back(part.name, std::move(comparison).value());
                m_progress = 0.8 + 0.2 * static_cast<double>(result.lights.size()) / static_cast<double>(parts->size());
            }
            for (const auto& [name, comparison] : result.lights) all.push_back(&comparison);
            auto combined = eval::combine(all);
            if (!combined) return combined.errorInfo();
            result.combined = std::move(combined).value();
            return result;
        });
    return core::Ok{};
}

std::optional<core::Result<TruthResult>> TruthJob::poll() {
    if (!ready()) return std::nullopt;
    return m_result.get();
}

} // namespace shadowkit::viewer
