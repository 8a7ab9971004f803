#include "auto_technique.h"

#include "shadowkit/frame/auto_candidates.h"
#include "shadowkit/gl/context.h"

#include <fmt/format.h>

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
    if (auto s = viewOptions.check(); !s) return s;
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
    auto candidates = frame::autoCandidates(**renderer, *base, *options, view->width, view->height);
    if (!candidates) return withFlagName(candidates.errorInfo());
    fmt::print(
        "Candidates of --technique auto for view '{}' at {}x{}, {} texels, predicted at {} receivers ({:.1f} ms):\n",
        viewOptions.view, view->width, view->height, options->texelBudget, candidates->receivers,
        candidates->milliseconds);
    fmt::print("  {:<54} {:>9} {:>9}   {:>9} {:>9}\n", "candidate (optimised parameters)", "def p50", "def p95", "p50",
               "p95");
    for (const frame::AutoCandidate& c : candidates->ranked)
        fmt::print("  {:<54} {:>9.3f} {:>9.3f}   {:>9.3f} {:>9.3f}\n", core::describe(c.choice), c.defaults.p50,
                   c.defaults.p95, c.choice.predicted.p50, c.choice.predicted.p95);
    return core::Ok{};
}

} // namespace shadowkit::app
