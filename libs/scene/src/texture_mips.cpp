#include "shadowkit/scene/texture_mips.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace shadowkit::scene {

namespace {

// A level kept in float while the chain is built, so that rounding does not accumulate.
struct FloatLevel {
    int width = 0, height = 0;
    std::vector<glm::vec4> texels;
};

FloatLevel toFloat(const Image& image) {
    FloatLevel level{image.width, image.height, std::vector<glm::vec4>(size_t(image.width) * size_t(image.height))};
    for (size_t i = 0; i < level.texels.size(); ++i) {
        const uint8_t* p = image.rgba.data() + 4 * i;
        level.texels[i] = glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    }
    return level;
}

// 2×2 box average; on an odd side the last row or column is read twice (clamped).
FloatLevel halve(const FloatLevel& from) {
    FloatLevel to{std::max(1, from.width / 2), std::max(1, from.height / 2), {}};
    to.texels.resize(size_t(to.width) * size_t(to.height));
    auto at = [&](int x, int y) {
        return from
            .texels[size_t(std::min(y, from.height - 1)) * size_t(from.width) + size_t(std::min(x, from.width - 1))];
    };
    for (int y = 0; y < to.height; ++y)
        for (int x = 0; x < to.width; ++x)
            to.texels[size_t(y) * size_t(to.width) + size_t(x)] =
                0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
    return to;
}

uint8_t toByte(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// The image of a level with its alpha scaled by `scale`.
Image toImage(const FloatLevel& level, float alphaScale) {
    Image image(level.width, level.height);
    for (size_t i = 0; i < level.texels.size(); ++i) {
        const glm::vec4& t = level.texels[i];
        uint8_t* p = image.rgba.data() + 4 * i;
        p[0] = toByte(t.r), p[1] = toByte(t.g), p[2] = toByte(t.b), p[3] = toByte(t.a * alphaScale);
    }
    return image;
}

} // namespace

double sampledAlphaCoverage(const Image& image, float cutoff) {
    const int w = image.width, h = image.height;
    if (w <= 0 || h <= 0) return 0.0;
    auto alpha = [&](int x, int y) {
        return float(image.rgba[(size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))) * 4 +
                                3]) /
               255.0f;
    };
    size_t covered = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int sy = 0; sy < 2; ++sy)
                for (int sx = 0; sx < 2; ++sx) {
                    // p = sample − ½: the texel below-left of the sample and the fraction past it.
                    const float px = float(x) + 0.25f + 0.5f * float(sx) - 0.5f,
                                py = float(y) + 0.25f + 0.5f * float(sy) - 0.5f;
                    const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
                    const float fx = px - float(x0), fy = py - float(y0);
                    const float a = (1 - fy) * ((1 - fx) * alpha(x0, y0) + fx * alpha(x0 + 1, y0)) +
                                    fy * ((1 - fx) * alpha(x0, y0 + 1) + fx * alpha(x0 + 1, y0 + 1));
                    covered += a >= cutoff;
                }
    return double(covered) / (4.0 * double(w) * double(h));
}

double alphaCoverage(const Image& image, float cutoff) {
    const size_t texels = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0));
    if (texels == 0) return 0.0;
    // Compared in bytes as the stored alpha is: a texel of alpha byte a covers where a / 255 ≥ cutoff.
    size_t covered = 0;
    for (size_t i = 0; i < texels; ++i) covered += float(image.rgba[4 * i + 3]) / 255.0f >= cutoff;
    return double(covered) / double(texels);
}

std::vector<Image> buildMipChain(const Image& level0, std::optional<float> alphaCutoff) {
    std::vector<Image> chain{level0};
    if (level0.width <= 0 || level0.height <= 0) return chain;
    const double target = alphaCutoff ? sampledAlphaCoverage(level0, *alphaCutoff) : 0.0;
    FloatLevel level = toFloat(level0);
    while (level.width > 1 || level.height > 1) {
        level = halve(level);
        float scale = 1.0f;
        if (alphaCutoff && *alphaCutoff > 0.0f) {
            // Bisection for the smallest scale whose sampled coverage reaches level 0's. Coverage
            // of the rounded bytes (what the GPU will compare), not of the floats.
            float lo = 0.0f, hi = 1.0f;
            while (sampledAlphaCoverage(toImage(level, hi), *alphaCutoff) < target && hi < 256.0f) hi *= 2.0f;
            for (int i = 0; i < 16; ++i) {
                const float mid = 0.5f * (lo + hi);
                (sampledAlphaCoverage(toImage(level, mid), *alphaCutoff) < target ? lo : hi) = mid;
            }
            scale = hi;
        }
        chain.push_back(toImage(level, scale));
    }
    return chain;
}

} // namespace shadowkit::scene
