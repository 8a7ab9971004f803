// --light: spot and point lights from the command line (core/local_lights.h).
#pragma once

#include "shadowkit/core/local_lights.h"

#include <CLI/CLI.hpp>

#include <string>
#include <variant>
#include <vector>

namespace shadowkit::app {

using LocalLight = std::variant<core::PointLight, core::SpotLight>;

struct LocalLightOptions {
    // "point:x,y,z[,range]" or "spot:x,y,z,dx,dy,dz,angle[,range]", as given (repeatable).
    std::vector<std::string> specs;

    void addTo(CLI::App& cmd);
    // The lights, each validated; an error names --light and shows the text.
    core::Result<std::vector<LocalLight>> lights() const;
};

} // namespace shadowkit::app
