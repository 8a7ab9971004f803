// What --technique auto weighs for one view (`shadowkit analyze --candidates`): the receivers
// read back as a frame reads them, the sampling model built on them, and every candidate family
// ranked by predicted error with its optimised and its default parameters — the frame driver's
// own steps 2–3, listed instead of chosen from.
#pragma once

#include "shadowkit/core/error_driven.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/sampling_error.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"

#include <vector>

namespace shadowkit::frame {

struct AutoCandidate {
    core::ParameterChoice choice;   // the family with its optimised parameter, predicted
    core::SamplingFigures defaults; // the same family, maps and size with default parameters
};

struct AutoCandidates {
    std::vector<AutoCandidate> ranked; // best first
    size_t receivers = 0;              // receiver samples the model predicts at
    double milliseconds = 0.0;         // CPU: the ranking (model built, search), not the read-back
};

// `base`'s camera at width × height: receivers sampled (frame::sampleReceivers), then
// core::rankCandidates within `options`, each candidate also predicted with its defaults.
core::Result<AutoCandidates> autoCandidates(gl::Renderer& renderer, const core::ShadowSetupInputs& base,
                                            const core::AutoOptions& options, int width, int height);

} // namespace shadowkit::frame
