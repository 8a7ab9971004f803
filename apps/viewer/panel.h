// The options panel: Dear ImGui widgets that edit the viewer's options as text
// (app::StateOptions), one widget per option of `render`. Each returns true when it changed
// something; an option the widget has never touched keeps its default (absent from the state).
#pragma once

#include "state.h"

namespace shadowkit::viewer {

// Draws the panel's sections; true when any option changed.
bool drawOptionsPanel(app::StateOptions& state);

} // namespace shadowkit::viewer
