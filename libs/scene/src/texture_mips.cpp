// Coverage-keeping mip chains (texture_mips.h; Castaño 2010, coverage counted as bilinear lookups).
#include "shadowkit/scene/texture_mips.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>

#include <glm/glm.hpp>
#include <tbb/parallel_for.h>

namespace shadowkit::scene {

namespace {

// A level kept in float while the chain is built, so that rounding does not accumulate.
struct FloatLevel {
    int width = 0, height = 0;
    std::vector<glm::vec4> texels;
};

// A byte's value in [0, 1], b / 255 as a float division gives it, looked up.
float unitOf(uint8_t byte) {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (size_t b = 0; b < t.size(); ++b) t[b] = float(b) / 255.0f;
        return t;
    }();
    return table[byte];
}

// 2×2 box average of a w × h level whose texel (x, y) is `at(x, y)`; on an odd side the last row
// or column is read twice (clamped).
template <class At>
FloatLevel halve(int w, int h, At at) {
    FloatLevel to{std::max(1, w / 2), std::max(1, h / 2), {}};
    to.texels.resize(size_t(to.width) * size_t(to.height));
    auto clamped = [&](int x, int y) { return at(std::min(x, w - 1), std::min(y, h - 1)); };
    for (int y = 0; y < to.height; ++y)
        for (int x = 0; x < to.width; ++x)
            to.texels[size_t(y) * size_t(to.width) + size_t(x)] =
                0.25f * (clamped(2 * x, 2 * y) + clamped(2 * x + 1, 2 * y) + clamped(2 * x, 2 * y + 1) +
                         clamped(2 * x + 1, 2 * y + 1));
    return to;
}
FloatLevel halve(const FloatLevel& from) {
    return halve(from.width, from.height,
                 [&](int x, int y) { return from.texels[size_t(y) * size_t(from.width) + size_t(x)]; });
}
// Level 1 straight from level 0's bytes, each read as the float it would have been kept as (a
// float copy of a 2048 × 1024 level 0 is 32 MiB, fresh pages for every chain).
FloatLevel halve(const Image& from) {
    return halve(from.width, from.height, [&](int x, int y) {
        const uint8_t* p = from.pixel(x, y);
        return glm::vec4(unitOf(p[0]), unitOf(p[1]), unitOf(p[2]), unitOf(p[3]));
    });
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

// Every alpha a bilinear lookup reads at 2 × 2 points inside a texel of a w × h level (texel
// units x + ¼ and x + ¾, centres at x + ½), each from its four nearest texels with clamped edges,
// passed to `visit(float)`; `alpha(texel)` gives a texel's alpha by its row-major index. The
// order is not the texels' (a count and a selection read them). Bilinear interpolation is a lerp
// along each of two rows, then one between them, and a texel row's lerps serve the sample rows on
// either side of it: each is computed once, kept for three rows, with the same operations in the
// same order as the four-tap form, so the same floats.
template <class Alpha, class Visit>
void forEachBilinearSample(int w, int h, Alpha alpha, Visit visit) {
    // Row r's lerps at x + ¼ (¼ of texel x − 1, ¾ of x) and x + ¾ (¾ of x, ¼ of x + 1), r clamped.
    // The row is read once into `padded`, its first and last texels repeated beyond its ends.
    std::vector<float> padded(size_t(w) + 2);
    auto lerpRow = [&](int r, std::vector<float>& out) {
        const size_t row = size_t(std::clamp(r, 0, h - 1)) * size_t(w);
        for (size_t x = 0; x < size_t(w); ++x) padded[x + 1] = alpha(row + x);
        padded.front() = padded[1], padded.back() = padded[size_t(w)];
        for (size_t x = 0; x < size_t(w); ++x) {
            out[2 * x] = 0.25f * padded[x] + 0.75f * padded[x + 1];
            out[2 * x + 1] = 0.75f * padded[x + 1] + 0.25f * padded[x + 2];
        }
    };
    std::vector<float> above(2 * size_t(w)), here(2 * size_t(w)), below(2 * size_t(w));
    lerpRow(-1, above), lerpRow(0, here);
    for (int y = 0; y < h; ++y) {
        lerpRow(y + 1, below);
        // The sample row at y + ¼ (¼ of the row above, ¾ of this one), then y + ¾.
        for (size_t i = 0; i < here.size(); ++i) visit(0.25f * above[i] + 0.75f * here[i]);
        for (size_t i = 0; i < here.size(); ++i) visit(0.75f * here[i] + 0.25f * below[i]);
        std::swap(above, here), std::swap(here, below);
    }
}

// The k-th largest (1 ≤ k ≤ 4 w h) of the samples forEachBilinearSample gives, exactly, without
// keeping them all (a level's are 16 bytes a texel): alphas are never negative, and non-negative
// floats order as their bit patterns do, so a count of the samples by their top 16 bits finds the
// bin that holds the k-th, and a second pass keeps that bin's samples alone to select from.
template <class Alpha>
float kthLargestSample(int w, int h, Alpha alpha, size_t k) {
    // Zero (and, were there any, negative values) in the lowest bin, where the selection orders them.
    auto bin = [](float a) { return a > 0.0f ? std::bit_cast<uint32_t>(a) >> 16 : 0u; };
    std::vector<size_t> count(size_t{1} << 16, 0);
    forEachBilinearSample(w, h, alpha, [&](float a) { ++count[bin(a)]; });
    size_t above = 0; // samples in the bins above the one searched
    uint32_t holding = 0xffff;
    while (above + count[holding] < k) above += count[holding--];
    std::vector<float> inBin;
    inBin.reserve(count[holding]);
    forEachBilinearSample(w, h, alpha, [&](float a) {
        if (bin(a) == holding) inBin.push_back(a);
    });
    const auto kth = inBin.begin() + std::ptrdiff_t(k - above - 1);
    std::nth_element(inBin.begin(), kth, inBin.end(), std::greater<float>());
    return *kth;
}

} // namespace

double sampledAlphaCoverage(const Image& image, float cutoff) {
    if (image.width <= 0 || image.height <= 0) return 0.0;
    size_t covered = 0;
    forEachBilinearSample(
        image.width, image.height, [&](size_t texel) { return unitOf(image.rgba[4 * texel + 3]); },
        [&](float a) { covered += a >= cutoff; });
    return double(covered) / (4.0 * double(image.width) * double(image.height));
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
    std::vector<Image> below = buildMipLevelsBelow(level0, alphaCutoff);
    chain.insert(chain.end(), std::make_move_iterator(below.begin()), std::make_move_iterator(below.end()));
    return chain;
}

std::vector<Image> buildMipLevelsBelow(const Image& level0, std::optional<float> alphaCutoff) {
    std::vector<Image> chain;
    if (level0.width <= 0 || level0.height <= 0 || (level0.width == 1 && level0.height == 1)) return chain;
    const double target = alphaCutoff ? sampledAlphaCoverage(level0, *alphaCutoff) : 0.0;
    for (FloatLevel level = halve(level0);; level = halve(level)) {
        float scale = 1.0f;
        if (alphaCutoff && *alphaCutoff > 0.0f) {
            // Interpolation is linear, so scaling alpha scales every sample: the scale that covers
            // the k = ⌈target · n⌉ highest samples puts the k-th highest at the cutoff (a selection,
            // not a search). Half a byte above it, so rounding to bytes does not undo it. Texels that
            // clamp at alpha 1 can pull a sample next to them back under the cutoff: what that costs
            // is bounded by TextureMipsTest (the bytes' sampled coverage, within 3 points).
            const double samples = 4.0 * double(level.width) * double(level.height);
            const auto covered = static_cast<size_t>(std::ceil(target * samples - 1e-9));
            if (covered == 0) {
                scale = 0.0f;
            } else {
                const float kth = kthLargestSample(
                    level.width, level.height, [&](size_t texel) { return level.texels[texel].a; }, covered);
                scale = kth > 0.0f ? std::min((*alphaCutoff + 0.5f / 255.0f) / kth, 256.0f) : 256.0f;
            }
        }
        chain.push_back(toImage(level, scale));
        if (level.width == 1 && level.height == 1) return chain;
    }
}

void forEachMipChain(std::span<const MipChainRequest> requests,
                     const std::function<void(size_t, const std::vector<Image>&)>& use, size_t batchBytes) {
    std::vector<std::vector<Image>> chains;
    for (size_t first = 0; first < requests.size();) {
        size_t end = first, bytes = 0;
        do bytes += requests[end++].level0->rgba.size();
        while (end < requests.size() && bytes + requests[end].level0->rgba.size() <= batchBytes);
        // Each chain depends on its own level 0 alone: built in any order, the same bytes. Level 0
        // itself is not copied: the caller has it.
        chains.assign(end - first, {});
        tbb::parallel_for(first, end, [&](size_t i) {
            const MipChainRequest& request = requests[i];
            if (request.mipmaps) chains[i - first] = buildMipLevelsBelow(*request.level0, request.alphaCutoff);
        });
        for (size_t i = first; i < end; ++i) use(i, chains[i - first]);
        first = end;
    }
}

} // namespace shadowkit::scene
