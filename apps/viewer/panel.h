// The options panel: Dear ImGui widgets that edit the viewer's options as text
// (app::StateOptions), one widget per option of `render`. Each returns true when it changed
// something; an option the widget has never touched keeps its default (absent from the state).
#pragma once

#include "state.h"

namespace shadowkit::viewer {

// What the widgets show for options the state does not set: the values the last frame was
// drawn with (the view's sun, the technique's recommended bias).
struct PanelDefaults {
    double sunElevationDegrees = 30.0, sunAzimuthDegrees = 90.0;
    double biasSlope = 1.0, biasConstant = 2.0, normalOffset = 0.0, normalOffsetFootprint = 0.0;
};

// Draws the panel's sections; true when any option changed.
bool drawOptionsPanel(app::StateOptions& state, const PanelDefaults& defaults);

} // namespace shadowkit::viewer
