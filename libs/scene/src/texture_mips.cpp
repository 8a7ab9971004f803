#include "shadowkit/scene/texture_mips.h"

#include <algorithm>
#include <cmath>
#include <functional>

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

// The alpha a bilinear lookup reads at 2 × 2 points inside every texel of a w × h level (texel
// units x + ¼ and x + ¾, centres at x + ½), each from its four nearest texels with clamped
// edges; `alpha(texel)` gives a texel's alpha by its row-major index.
template <class Alpha>
std::vector<float> bilinearSamples(int w, int h, Alpha alpha) {
    auto at = [&](int x, int y) {
        return alpha(size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1)));
    };
    std::vector<float> samples;
    samples.reserve(size_t(w) * size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int sy = 0; sy < 2; ++sy)
                for (int sx = 0; sx < 2; ++sx) {
                    // The texel below-left of the sample (sample − ½) and the fraction past it: ¾ or ¼.
                    const int x0 = x - 1 + sx, y0 = y - 1 + sy;
                    const float fx = sx == 0 ? 0.75f : 0.25f, fy = sy == 0 ? 0.75f : 0.25f;
                    samples.push_back((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                                      fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1)));
                }
    return samples;
}

} // namespace

double sampledAlphaCoverage(const Image& image, float cutoff) {
    if (image.width <= 0 || image.height <= 0) return 0.0;
    const std::vector<float> samples = bilinearSamples(
        image.width, image.height, [&](size_t texel) { return float(image.rgba[4 * texel + 3]) / 255.0f; });
    const auto covered = std::count_if(samples.begin(), samples.end(), [&](float a) { return a >= cutoff; });
    return double(covered) / double(samples.size());
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
            // Interpolation is linear, so scaling alpha scales every sample: the scale that covers
            // the k = ⌈target · n⌉ highest samples puts the k-th highest at the cutoff (a selection,
            // not a search). Half a byte above it, so rounding to bytes does not undo it. Texels that
            // clamp at alpha 1 can pull a sample next to them back under the cutoff: what that costs
            // is bounded by TextureMipsTest (the bytes' sampled coverage, within 3 points).
            std::vector<float> samples =
                bilinearSamples(level.width, level.height, [&](size_t texel) { return level.texels[texel].a; });
            const auto covered = static_cast<size_t>(std::ceil(target * double(samples.size()) - 1e-9));
            if (covered == 0) {
                scale = 0.0f;
            } else {
                const auto kth = samples.begin() + std::ptrdiff_t(covered - 1);
                std::nth_element(samples.begin(), kth, samples.end(), std::greater<float>());
                scale = *kth > 0.0f ? std::min((*alphaCutoff + 0.5f / 255.0f) / *kth, 256.0f) : 256.0f;
            }
        }
        chain.push_back(toImage(level, scale));
    }
    return chain;
}

} // namespace shadowkit::scene
