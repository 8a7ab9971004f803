#include "shadowkit/imaging/plot.h"

#include "shadowkit/imaging/bitmap_font.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadowkit::imaging {
namespace {

constexpr uint8_t kInk[3] = {30, 30, 30};
constexpr uint8_t kGrid[3] = {225, 225, 225};

void fill(scene::Image& image, int x0, int y0, int x1, int y1, const uint8_t rgb[3]) {
    for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
            uint8_t* p = image.pixel(x, y);
            p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
        }
}

// A 2-pixel-wide line by stepping along its longer axis.
void line(scene::Image& image, double x0, double y0, double x1, double y1, const uint8_t rgb[3]) {
    const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0))),
                  y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
        fill(image, x, y, x + 2, y + 2, rgb);
    }
}

// "Nice" tick spacing: 1, 2 or 5 times a power of ten, about `count` ticks over the range.
double tickStep(double range, int count) {
    const double raw = range / count;
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * decade >= raw) return m * decade;
    return 10.0 * decade;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

} // namespace

scene::Image plotLines(const std::vector<PlotSeries>& series, const PlotOptions& o) {
    scene::Image image(o.width, o.height);
    std::fill(image.rgba.begin(), image.rgba.end(), uint8_t{255});

    double xMin = o.xMin, xMax = o.xMax, yMin = o.yMin, yMax = o.yMax;
    double dataXMin = INFINITY, dataXMax = -INFINITY, dataYMin = INFINITY, dataYMax = -INFINITY;
    for (const PlotSeries& s : series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            dataXMin = std::min(dataXMin, s.x[i]), dataXMax = std::max(dataXMax, s.x[i]);
            dataYMin = std::min(dataYMin, s.y[i]), dataYMax = std::max(dataYMax, s.y[i]);
        }
    if (std::isnan(xMin)) xMin = dataXMin;
    if (std::isnan(xMax)) xMax = dataXMax;
    if (std::isnan(yMin)) yMin = dataYMin >= 0.0 ? 0.0 : dataYMin;
    if (std::isnan(yMax)) yMax = dataYMax;
    if (!(xMax > xMin)) xMax = xMin + 1.0;
    if (!(yMax > yMin)) yMax = yMin + 1.0;

    const int left = 70, right = o.width - 20, top = 40, bottom = o.height - 55;
    auto px = [&](double x) { return left + (x - xMin) / (xMax - xMin) * (right - left); };
    auto py = [&](double y) { return bottom - (y - yMin) / (yMax - yMin) * (bottom - top); };

    // Grid, ticks and numbers.
    const double xStep = tickStep(xMax - xMin, 8), yStep = tickStep(yMax - yMin, 6);
    for (double x = std::ceil(xMin / xStep) * xStep; x <= xMax + 1e-9 * xStep; x += xStep) {
        const int X = static_cast<int>(std::lround(px(x)));
        fill(image, X, top, X + 1, bottom, kGrid);
        fill(image, X, bottom, X + 1, bottom + 5, kInk);
        const std::string label = number(x);
        drawText(image, X - textWidth(label) / 2, bottom + 9, label, kInk);
    }
    for (double y = std::ceil(yMin / yStep) * yStep; y <= yMax + 1e-9 * yStep; y += yStep) {
        const int Y = static_cast<int>(std::lround(py(y)));
        fill(image, left, Y, right, Y + 1, kGrid);
        fill(image, left - 5, Y, left, Y + 1, kInk);
        const std::string label = number(y);
        drawText(image, left - 9 - textWidth(label), Y - kGlyphHeight / 2, label, kInk);
    }
    fill(image, left, top, left + 1, bottom + 1, kInk); // y axis
    fill(image, left, bottom, right, bottom + 1, kInk); // x axis

    // Curves, clipped to the plot area by clamping (the axes bound what is shown).
    for (const PlotSeries& s : series)
        for (size_t i = 1; i < s.x.size(); ++i) {
            auto clampY = [&](double y) { return std::clamp(py(y), double(top), double(bottom)); };
            line(image, px(s.x[i - 1]), clampY(s.y[i - 1]), px(s.x[i]), clampY(s.y[i]), s.rgb.data());
        }

    // Title, axis labels, legend (top of the plot, a quarter in: away from the corners,
    // where curves of decreasing or increasing error start and end).
    drawText(image, (o.width - textWidth(o.title, 2)) / 2, 10, o.title, kInk, 2);
    drawText(image, (left + right - textWidth(o.xLabel)) / 2, bottom + 30, o.xLabel, kInk);
    drawText(image, 8, top - 16, o.yLabel, kInk);
    int legendY = top + 10;
    for (const PlotSeries& s : series) {
        const int x = left + (right - left) / 4;
        fill(image, x, legendY + 3, x + 22, legendY + 5, s.rgb.data());
        drawText(image, x + 28, legendY, s.name, kInk);
        legendY += 14;
    }
    return image;
}

} // namespace shadowkit::imaging
