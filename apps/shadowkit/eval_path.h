// shadowkit eval --path: the usual figures frame by frame along a camera path, with the
// temporal ones (flicker against truth, truth change), a CSV per frame and a plot.
#pragma once

#include "local_light_options.h"
#include "options.h"
#include "timeline.h"

#include <string>

namespace shadowkit::app {

struct EvalPathArgs {
    const SceneOptions& scene;
    const ViewOptions& view;
    const TechniqueOptions& technique;
    const RenderOptions& render;
    const TimelineOptions& timeline;
    const LocalLightOptions& lights;
    std::string csv, plot, json, report;
    bool check = false;     // --check: validate the options, render nothing
    bool levelPops = false; // --level-pops: eval::levelPops per frame
};

int runEvalPath(const EvalPathArgs& args);

} // namespace shadowkit::app
