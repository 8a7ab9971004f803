#include "shadowkit/eval/maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace shadowkit::eval {
namespace {

void put(scene::Image& image, int x, int y, const uint8_t rgb[3]) {
    uint8_t* p = image.pixel(x, y);
    p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
}

// A perceptually ordered dark-blue → green → yellow ramp (viridis-like), t in [0,1].
std::array<uint8_t, 3> ramp(double t) {
    static constexpr double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    t = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(3, static_cast<int>(t));
    const double f = t - i;
    std::array<uint8_t, 3> c;
    for (int k = 0; k < 3; ++k) c[size_t(k)] = static_cast<uint8_t>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
    return c;
}

constexpr double kLog2Min = -6.0, kLog2Max = 6.0; // 1/64 .. 64 pixels per texel

// 3x5 pixel glyphs for the colour-bar labels: each row is 3 bits, top row first.
int glyphRows(char c, int row) {
    static constexpr int digits[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
                                          {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
    static constexpr int slash[5] = {1, 1, 2, 4, 4};
    if (c >= '0' && c <= '9') return digits[c - '0'][row];
    if (c == '/') return slash[row];
    return 0;
}

void drawText(scene::Image& image, int x, int y, const std::string& text, int scale) {
    static constexpr uint8_t white[3] = {235, 235, 235};
    for (char c : text) {
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col)
                if (glyphRows(c, row) & (4 >> col))
                    for (int sy = 0; sy < scale; ++sy)
                        for (int sx = 0; sx < scale; ++sx) {
                            const int px = x + col * scale + sx, py = y + row * scale + sy;
                            if (px >= 0 && py >= 0 && px < image.width && py < image.height) put(image, px, py, white);
                        }
        x += 4 * scale;
    }
}

} // namespace

scene::Image errorMapImage(const Comparison& comparison, int width, int height) {
    scene::Image image(width, height);
    using C = ErrorMapColors;
    const uint8_t* colors[] = {C::notEvaluated, C::litCorrect, C::shadowCorrect, C::falseShadow, C::falseLit, C::excluded};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            put(image, x, y, colors[static_cast<int>(comparison.classes[static_cast<size_t>(y) * size_t(width) + size_t(x)])]);
    return image;
}

scene::Image aliasingMapImage(const Comparison& comparison, int width, int height) {
    const int scale = std::max(1, width / 400); // label size
    const int barHeight = 6 * scale + 6 * scale + 8;
    scene::Image image(width, height + barHeight);
    static constexpr uint8_t black[3] = {0, 0, 0};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float p = comparison.pixelsPerTexel[static_cast<size_t>(y) * size_t(width) + size_t(x)];
            if (std::isnan(p)) {
                put(image, x, y, black);
                continue;
            }
            const auto c = ramp((std::log2(std::max(double(p), 1e-9)) - kLog2Min) / (kLog2Max - kLog2Min));
            put(image, x, y, c.data());
        }
    // Colour bar with ticks at every power of eight and labels 1/64 … 64.
    const int barTop = height + 2, barBottom = height + 2 + 6 * scale;
    for (int y = height; y < height + barHeight; ++y)
        for (int x = 0; x < width; ++x) put(image, x, y, black);
    for (int x = 0; x < width; ++x) {
        const auto c = ramp((x + 0.5) / width);
        for (int y = barTop; y < barBottom; ++y) put(image, x, y, c.data());
    }
    const char* labels[] = {"1/64", "1/8", "1", "8", "64"};
    for (int k = 0; k < 5; ++k) {
        const double t = k / 4.0;
        const int x = std::clamp(static_cast<int>(t * (width - 1)), 0, width - 1);
        static constexpr uint8_t white[3] = {255, 255, 255};
        for (int y = barTop; y < barBottom + 2 * scale; ++y)
            for (int w = 0; w < (k == 2 ? 2 * scale : scale); ++w) put(image, std::min(width - 1, x + w), y, white);
        const int textWidth = static_cast<int>(std::string(labels[k]).size()) * 4 * scale;
        drawText(image, std::clamp(x - textWidth / 2, 0, width - textWidth), barBottom + 3 * scale, labels[k], scale);
    }
    return image;
}

} // namespace shadowkit::eval
