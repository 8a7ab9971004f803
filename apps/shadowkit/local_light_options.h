// --light: spot and point lights from the command line (core/local_lights.h).
#pragma once

#include "shadowkit/core/local_lights.h"
#include "shadowkit/frame/frame_config.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/views.h"

#include <CLI/CLI.hpp>

#include <string>
#include <variant>
#include <vector>

namespace shadowkit::app {

using LocalLight = frame::LocalLight;

struct LocalLightOptions {
    // "point:x,y,z[,range]" or "spot:x,y,z,dx,dy,dz,angle[,range]", as given (repeatable).
    std::vector<std::string> specs;
    int mapSize = 1024; // --local-map-size: each spot map and cube face
    gl::LocalPass pass = gl::LocalPass::Layered;
    gl::LocalBiasSettings bias;

    // withMaps: also the flags of drawing them (pass, bias: render, eval, compare), not only
    // of setting them up (setup).
    void addTo(CLI::App& cmd, bool withMaps = true);
    // The lights, each validated; an error names --light and shows the text.
    core::Result<std::vector<LocalLight>> lights() const;
    // The lights' text, checked before a scene is loaded.
    core::Status check() const;
    // The frame's local lights: the view's (views.json), then --light's, set up for its camera
    // over these scene bounds.
    core::Result<core::LocalLighting> lightingFor(const scene::ResolvedView& view,
                                                  const core::Aabb& wsSceneBounds) const;
};

} // namespace shadowkit::app
