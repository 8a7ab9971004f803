#include "auto_technique.h"

#include <chrono>

namespace shadowkit::app {

core::Result<core::ShadowSetupInputs> AutoTechnique::choose(gl::Renderer& renderer, const core::ShadowSetupInputs& inputs,
                                                            const gl::RenderSettings& settings) {
    gl::ReceiverSampling sampling;
    sampling.width = std::min(sampling.width, settings.width);
    auto samples = gl::sampleReceivers(renderer, inputs, settings, sampling);
    if (!samples) return samples.errorInfo();
    const auto start = std::chrono::steady_clock::now();
    auto model = core::SamplingErrorModel::create(inputs.camera, settings.width, settings.height, *samples);
    if (!model) return model.errorInfo();
    auto choice = core::chooseAuto(inputs, m_options, *model, m_last ? &*m_last : nullptr);
    if (!choice) return choice.errorInfo();
    m_milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    m_model = std::move(model).value();
    m_last = std::move(choice).value();
    return m_last->inputs;
}

} // namespace shadowkit::app
