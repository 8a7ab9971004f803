// The cells of `shadowkit compare --configs`: render options as text ("a=1,b=2;c=3") or a JSON
// file ([{"a": 1, "b": 2}, {"c": 3}]), each parsed by the option groups `render` uses. In the
// options library so the fuzz target reads them exactly as the command does.
#pragma once

#include "local_light_options.h"
#include "options.h"

#include <string>
#include <utility>
#include <vector>

namespace shadowkit::app {

using Cell = std::vector<std::pair<std::string, std::string>>; // render long options, without "--"

core::Result<std::vector<Cell>> parseConfigs(const std::string& text);

// One cell's options, parsed by the same option groups as `render`.
struct CellOptions {
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    LocalLightOptions lights; // light=point:..., local-map-size=..., sun=off
};

// One cell over the command's own --view and --size (empty: the view's); errors name --configs.
core::Result<CellOptions> parseCell(const Cell& cell, const std::string& view, const std::string& size);

} // namespace shadowkit::app
