// --technique auto (issue 16): each frame, receivers read back from the renderer at a low
// resolution (gl::sampleReceivers), the sampling model over them (core/sampling_error.h) and
// the family and parameters it predicts best within the texel budget: the full search on the
// first frame, then each candidate's optimum tracked a step a frame (core::AutoChooser).
#pragma once

#include "options.h"

#include "shadowkit/core/auto_chooser.h"
#include "shadowkit/gl/receiver_samples.h"
#include "shadowkit/gl/renderer.h"

#include <optional>
#include <string_view>
#include <vector>

namespace shadowkit::app {

class AutoTechnique {
public:
    explicit AutoTechnique(core::AutoOptions options) : m_chooser(options) {}

    // `inputs` with this frame's family, map size and parameters (camera, light and scene box
    // as given), drawn with `settings`' image size, culling and levels of detail.
    core::Result<core::ShadowSetupInputs> choose(gl::Renderer& renderer, const core::ShadowSetupInputs& inputs,
                                                 const gl::RenderSettings& settings);

    const std::optional<core::ParameterChoice>& last() const { return m_last; }
    // CPU time of the last choice: the model and the search, not the read-back.
    double lastMilliseconds() const { return m_milliseconds; }

private:
    core::AutoChooser m_chooser; // the full search on the first frame, tracking after it
    std::optional<core::ParameterChoice> m_last;
    double m_milliseconds = 0.0;
};

// A command's frame under --technique auto: `inputs` become this frame's choice and `settings`
// take the bias flags from the chosen technique's recommendation. With a `label`, the choice
// is printed to stderr ("paper: auto chose ...").
core::Status chooseForFrame(AutoTechnique& automatic, gl::Renderer& renderer, const RenderOptions& render,
                            const scene::ResolvedView& view, core::ShadowSetupInputs& inputs, gl::RenderSettings& settings,
                            std::string_view label);

// `shadowkit analyze --candidates`: every candidate of --technique auto for the view, with
// its family's default parameters and the optimised ones, predicted from the view's
// receivers, best first (what auto would choose comes first).
core::Status printAutoCandidates(const SceneOptions& sceneOptions, const ViewOptions& viewOptions, const TechniqueOptions& technique);

} // namespace shadowkit::app
