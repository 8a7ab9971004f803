// The option groups of `render` (technique, render, local lights) as the typed
// frame::FrameConfig every front end draws with.
#pragma once

#include "local_light_options.h"
#include "options.h"

#include "shadowkit/frame/frame_config.h"

namespace shadowkit::app {

// The flags' FrameConfig, unchecked: FrameDriver::create (or frame::firstSetup) checks it, once;
// errors (of parsing here) name the flag.
core::Result<frame::FrameConfig> frameConfigOf(const TechniqueOptions& technique, const RenderOptions& render,
                                               const LocalLightOptions& lights);

} // namespace shadowkit::app
