// --technique auto (issue 16): each frame, receivers read back from the renderer at a low
// resolution (gl::sampleReceivers), the sampling model over them (core/sampling_error.h) and
// the family and parameters it predicts best within the texel budget (core::chooseAuto),
// holding the last frame's choice unless clearly beaten.
#pragma once

#include "options.h"

#include "shadowkit/core/error_driven.h"
#include "shadowkit/gl/receiver_samples.h"
#include "shadowkit/gl/renderer.h"

#include <optional>
#include <string_view>
#include <vector>

namespace shadowkit::app {

class AutoTechnique {
public:
    explicit AutoTechnique(core::AutoOptions options) : m_options(options) {}

    // `inputs` with this frame's family, map size and parameters (camera, light and scene box
    // as given), drawn with `settings`' image size, culling and levels of detail.
    core::Result<core::ShadowSetupInputs> choose(gl::Renderer& renderer, const core::ShadowSetupInputs& inputs,
                                                 const gl::RenderSettings& settings);

    const std::optional<core::ParameterChoice>& last() const { return m_last; }
    // The model built for the last frame (its samples), for listing candidates.
    const std::optional<core::SamplingErrorModel>& model() const { return m_model; }
    // CPU time of the last choice: the model and the search, not the read-back.
    double lastMilliseconds() const { return m_milliseconds; }
    const core::AutoOptions& options() const { return m_options; }

private:
    core::AutoOptions m_options;
    std::optional<core::ParameterChoice> m_last;
    std::optional<core::SamplingErrorModel> m_model;
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
