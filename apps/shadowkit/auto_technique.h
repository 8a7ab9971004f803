// --technique auto in the command line (issue 16): the choice itself is a phase of every frame
// (frame::FrameDriver: receivers read back, core::AutoChooser); here what the apps print of it.
#pragma once

#include "options.h"

#include "shadowkit/frame/frame_driver.h"

#include <string_view>

namespace shadowkit::app {

// With --technique auto, what the frame chose, on stderr ("paper: auto chose ..."); nothing
// for other techniques.
void printAutoChoice(std::string_view label, const frame::PreparedFrame& frame);

// `shadowkit analyze --candidates`: every candidate of --technique auto for the view, with
// its family's default parameters and the optimised ones, predicted from the view's
// receivers, best first (what auto would choose comes first).
core::Status printAutoCandidates(const SceneOptions& sceneOptions, const ViewOptions& viewOptions,
                                 const TechniqueOptions& technique);

} // namespace shadowkit::app
