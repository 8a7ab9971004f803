#include "shadowkit/frame/auto_candidates.h"

#include "shadowkit/frame/frame_driver.h"

#include <chrono>

namespace shadowkit::frame {

core::Result<AutoCandidates> autoCandidates(gl::Renderer& renderer, const core::ShadowSetupInputs& base,
                                            const core::AutoOptions& options, int width, int height) {
    gl::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    auto samples = sampleReceivers(renderer, base, settings);
    if (!samples) return samples.errorInfo();
    auto model = core::SamplingErrorModel::create(base.camera, width, height, *samples);
    if (!model) return model.errorInfo();
    const auto start = std::chrono::steady_clock::now();
    auto ranked = core::rankCandidates(base, options, *model);
    if (!ranked) return ranked.errorInfo();
    AutoCandidates out;
    out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out.receivers = model->size();
    for (const core::ParameterChoice& c : *ranked) {
        core::ShadowSetupInputs defaults = base;
        defaults.technique = c.inputs.technique;
        defaults.mapSize = c.inputs.mapSize;
        defaults.cascades.count = c.inputs.cascades.count;
        defaults.cascades.warp = c.inputs.cascades.warp;
        auto setup = core::computeShadowSetup(defaults);
        if (!setup) return setup.errorInfo();
        out.ranked.push_back({c, model->figures(*setup)});
    }
    return out;
}

} // namespace shadowkit::frame
