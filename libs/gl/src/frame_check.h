// A frame's inputs checked before anything is drawn: the set-up's maps and the image within
// this driver's limits, every range RenderSettings' fields and the frame's bias must keep, and
// the local lights drawn with it.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/render_settings.h"

namespace shadowkit::gl {

// The first thing wrong, as one error naming the field (environment errors for the driver's
// limits), or Ok.
core::Status checkFrame(const core::ShadowSetup& setup, const RenderSettings& settings, const core::BiasSettings& bias);

// The local lights a renderer is given (Renderer::setLocalLights): at most kMaxLocalLights of
// each kind, each with its set-up, their maps within this driver's cube-map limit.
core::Status checkLocalLights(const core::LocalLighting& lights);

} // namespace shadowkit::gl
