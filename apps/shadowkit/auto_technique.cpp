#include "auto_technique.h"

#include "shadowkit/gl/context.h"

#include <fmt/format.h>

#include <chrono>

namespace shadowkit::app {

void printAutoChoice(std::string_view label, const frame::PreparedFrame& frame) {
    if (!frame.autoChoice) return;
    const core::ParameterChoice& c = *frame.autoChoice;
    fmt::print(stderr, "{}: auto chose {}, predicted p95 {:.3g} ({} samples, {:.2f} ms)\n", label, core::describe(c),
               c.predicted.p95, c.predicted.samples, frame.autoMilliseconds);
}

core::Status printAutoCandidates(const SceneOptions& sceneOptions, const ViewOptions& viewOptions,
                                 const TechniqueOptions& technique) {
    auto options = technique.autoOptions();
    if (!options) return options.errorInfo();
    auto sceneData = sceneOptions.load();
    if (!sceneData) return sceneData.errorInfo();
    auto view = viewOptions.resolve(*sceneData);
    if (!view) return view.errorInfo();
    auto context = gl::Context::createHeadless();
    if (!context) return context.errorInfo();
    auto renderer = gl::Renderer::create(*sceneData);
    if (!renderer) return renderer.errorInfo();
    auto base = technique.inputsFor(*view, (*renderer)->wsSceneBounds());
    if (!base) return base.errorInfo();
    gl::RenderSettings settings;
    settings.width = view->width;
    settings.height = view->height;
    auto samples = frame::sampleReceivers(**renderer, *base, settings);
    if (!samples) return samples.errorInfo();
    auto model = core::SamplingErrorModel::create(base->camera, settings.width, settings.height, *samples);
    if (!model) return model.errorInfo();
    const auto start = std::chrono::steady_clock::now();
    auto ranked = core::rankCandidates(*base, *options, *model);
    if (!ranked) return withFlagName(ranked.errorInfo());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    fmt::print(
        "Candidates of --technique auto for view '{}' at {}x{}, {} texels, predicted at {} receivers ({:.1f} ms):\n",
        viewOptions.view, settings.width, settings.height, options->texelBudget, model->size(), ms);
    fmt::print("  {:<54} {:>9} {:>9}   {:>9} {:>9}\n", "candidate (optimised parameters)", "def p50", "def p95", "p50",
               "p95");
    for (const core::ParameterChoice& c : *ranked) {
        // The same family, maps and size with its default parameters.
        core::ShadowSetupInputs defaults = *base;
        defaults.technique = c.inputs.technique;
        defaults.mapSize = c.inputs.mapSize;
        defaults.cascades.count = c.inputs.cascades.count;
        defaults.cascades.warp = c.inputs.cascades.warp;
        auto setup = core::computeShadowSetup(defaults);
        if (!setup) return withFlagName(setup.errorInfo());
        const core::SamplingFigures d = model->figures(*setup);
        fmt::print("  {:<54} {:>9.3f} {:>9.3f}   {:>9.3f} {:>9.3f}\n", core::describe(c), d.p50, d.p95, c.predicted.p50,
                   c.predicted.p95);
    }
    return core::Ok{};
}

} // namespace shadowkit::app
