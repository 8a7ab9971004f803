// Line plots as PNG images: axes with ticks and numbers, axis labels, a title, a legend.
#pragma once

#include "shadowkit/scene/image.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace shadowkit::imaging {

struct PlotSeries {
    std::string name;
    std::array<uint8_t, 3> rgb{0, 0, 0};
    std::vector<double> x, y; // same length, x ascending
};

struct PlotOptions {
    std::string title, xLabel, yLabel;
    int width = 800, height = 500; // pixels
    // Axis ranges; NaN: from the data (y from 0 when every y >= 0).
    double xMin = NAN, xMax = NAN, yMin = NAN, yMax = NAN;
};

scene::Image plotLines(const std::vector<PlotSeries>& series, const PlotOptions& options);

} // namespace shadowkit::imaging
