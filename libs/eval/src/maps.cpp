#include "shadowkit/eval/maps.h"

#include "shadowkit/imaging/bitmap_font.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace shadowkit::eval {
namespace {

// A perceptually ordered dark-blue → green → yellow ramp (viridis-like), t in [0,1].
std::array<uint8_t, 3> ramp(double t) {
    static constexpr double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    t = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(3, static_cast<int>(t));
    const double f = t - i;
    std::array<uint8_t, 3> c;
    for (int k = 0; k < 3; ++k)
        c[size_t(k)] = static_cast<uint8_t>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
    return c;
}

constexpr double kLog2Min = -6.0, kLog2Max = 6.0; // 1/64 .. 64 pixels per texel

// One pixel of a sun-shaded picture; `visibility` in [0, 1], NaN where the picture has none.
void shade(scene::Image& image, const TruthBuffers& truth, const core::DirectionalLight& light, size_t i,
           float visibility) {
    static constexpr uint8_t sky[3] = {150, 180, 215};
    static constexpr uint8_t missing[3] = {230, 0, 230};
    static constexpr double ambient = 0.25;
    const int x = static_cast<int>(i % size_t(truth.width)), y = static_cast<int>(i / size_t(truth.width));
    if (truth.surfaceId[i] == 0) return image.setOpaque(x, y, sky);
    if (std::isnan(visibility)) return image.setOpaque(x, y, missing);
    const double nDotL = std::max(0.0, glm::dot(core::Vec3(truth.wsNormal[i]), light.wsTowardsLight()));
    const double v = truth.facesLight[i] ? std::clamp(double(visibility), 0.0, 1.0) : 0.0;
    const auto grey = static_cast<uint8_t>(std::lround(255.0 * (ambient + (1.0 - ambient) * nDotL * v)));
    const uint8_t rgb[3] = {grey, grey, grey};
    image.setOpaque(x, y, rgb);
}

} // namespace

scene::Image errorMapImage(const Comparison& comparison, int width, int height) {
    scene::Image image(width, height);
    using C = ErrorMapColors;
    const uint8_t* colors[] = {C::notEvaluated, C::litCorrect, C::shadowCorrect,
                               C::falseShadow,  C::falseLit,   C::excluded};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            image.setOpaque(
                x, y, colors[static_cast<int>(comparison.classes[static_cast<size_t>(y) * size_t(width) + size_t(x)])]);
    return image;
}

scene::Image softErrorMapImage(std::span<const float> shadowTerm, const SoftTruth& soft, const Comparison& comparison) {
    using C = ErrorMapColors;
    scene::Image image(soft.width, soft.height);
    for (int y = 0; y < soft.height; ++y)
        for (int x = 0; x < soft.width; ++x) {
            const size_t i = static_cast<size_t>(y) * size_t(soft.width) + size_t(x);
            const PixelClass c = comparison.classes[i];
            const bool valid = c == PixelClass::LitCorrect || c == PixelClass::ShadowCorrect ||
                               c == PixelClass::FalseShadow || c == PixelClass::FalseLit;
            if (!valid || std::isnan(soft.visibility[i])) {
                image.setOpaque(x, y, C::notEvaluated);
                continue;
            }
            // Linear from the grey of a right pixel to the full colour at an error of 1.
            const double e = std::clamp(double(shadowTerm[i]) - soft.visibility[i], -1.0, 1.0);
            const uint8_t* to = e < 0.0 ? C::falseShadow : C::falseLit;
            uint8_t rgb[3];
            for (int k = 0; k < 3; ++k)
                rgb[k] = static_cast<uint8_t>(std::lround(C::litCorrect[k] + std::abs(e) * (to[k] - C::litCorrect[k])));
            image.setOpaque(x, y, rgb);
        }
    return image;
}

scene::Image aliasingMapImage(const Comparison& comparison, int width, int height) {
    const int scale = std::max(1, width / 640); // label size
    const int barHeight = 6 * scale + (imaging::kGlyphHeight + 4) * scale + 6;
    scene::Image image(width, height + barHeight);
    static constexpr uint8_t black[3] = {0, 0, 0};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float p = comparison.pixelsPerTexel[static_cast<size_t>(y) * size_t(width) + size_t(x)];
            if (std::isnan(p)) {
                image.setOpaque(x, y, black);
                continue;
            }
            const auto c = ramp((std::log2(std::max(double(p), 1e-9)) - kLog2Min) / (kLog2Max - kLog2Min));
            image.setOpaque(x, y, c.data());
        }
    // Colour bar with ticks at every power of eight and labels 1/64 … 64.
    const int barTop = height + 2, barBottom = height + 2 + 6 * scale;
    for (int y = height; y < height + barHeight; ++y)
        for (int x = 0; x < width; ++x) image.setOpaque(x, y, black);
    for (int x = 0; x < width; ++x) {
        const auto c = ramp((x + 0.5) / width);
        for (int y = barTop; y < barBottom; ++y) image.setOpaque(x, y, c.data());
    }
    const char* labels[] = {"1/64", "1/8", "1", "8", "64"};
    for (int k = 0; k < 5; ++k) {
        const double t = k / 4.0;
        const int x = std::clamp(static_cast<int>(t * (width - 1)), 0, width - 1);
        static constexpr uint8_t white[3] = {255, 255, 255};
        for (int y = barTop; y < barBottom + 2 * scale; ++y)
            for (int w = 0; w < (k == 2 ? 2 * scale : scale); ++w)
                image.setOpaque(std::min(width - 1, x + w), y, white);
        const int labelWidth = imaging::textWidth(labels[k], scale);
        imaging::drawText(image, std::clamp(x - labelWidth / 2, 0, width - labelWidth), barBottom + 3 * scale,
                          labels[k], white, scale);
    }
    return image;
}

scene::Image truthShadowImage(const TruthBuffers& truth, const core::DirectionalLight& light) {
    scene::Image image(truth.width, truth.height);
    for (size_t i = 0; i < truth.surfaceId.size(); ++i) shade(image, truth, light, i, truth.lit[i] ? 1.0f : 0.0f);
    return image;
}

scene::Image softTruthShadowImage(const TruthBuffers& truth, const SoftTruth& soft,
                                  const core::DirectionalLight& light) {
    scene::Image image(truth.width, truth.height);
    for (size_t i = 0; i < truth.surfaceId.size(); ++i) {
        // NaN where the surface faces away from the sun: unlit whatever the disk does.
        const float v = i < soft.visibility.size() && truth.facesLight[i] ? soft.visibility[i] : 0.0f;
        shade(image, truth, light, i, v);
    }
    return image;
}

scene::Image renderedShadowImage(const TruthBuffers& truth, const core::RasterBuffers& raster,
                                 const core::DirectionalLight& light) {
    scene::Image image(truth.width, truth.height);
    for (size_t i = 0; i < truth.surfaceId.size(); ++i)
        shade(image, truth, light, i, i < raster.surfaceId.size() && raster.surfaceId[i] ? raster.shadowTerm[i] : NAN);
    return image;
}

} // namespace shadowkit::eval
