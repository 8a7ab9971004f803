// Coverage-keeping mip chains (texture_mips.h) against their definition computed the plain way:
// every bilinear sample read through its four texels, every sample of a level kept and sorted.
// The library computes the same figures in a cheaper order (rows of lerps, a selection by a
// histogram of the samples' bits); these tests hold it to the definition exactly.
#include "shadowkit/scene/texture_mips.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <thread>

using namespace shadowkit;

namespace {

// Random alpha (and colour) bytes; `sparse` leaves most texels open, as leaf textures do.
scene::Image randomImage(int w, int h, uint32_t seed, bool sparse) {
    scene::Image image(w, h);
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> byte(0, 255), open(0, 3);
    for (uint8_t& b : image.rgba) b = uint8_t(byte(random));
    if (sparse)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (open(random) != 0) image.pixel(x, y)[3] = 0;
    return image;
}

// A w × h level's alpha in float, texel (x, y) clamped to the edges.
struct Alphas {
    int w, h;
    std::vector<float> a;
    float at(int x, int y) const {
        return a[size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))];
    }
};

// GL's bilinear lookup at texel coordinates (u, v), texel centres at k + ½: the texel below-left of
// (u − ½, v − ½) and the fractions past it, for the four points x + ¼, x + ¾ (and so in y) of every texel.
std::vector<float> everySample(const Alphas& level) {
    std::vector<float> samples;
    for (int y = 0; y < level.h; ++y)
        for (int x = 0; x < level.w; ++x)
            for (const float v : {float(y) + 0.25f, float(y) + 0.75f})
                for (const float u : {float(x) + 0.25f, float(x) + 0.75f}) {
                    const int x0 = int(std::floor(u - 0.5f)), y0 = int(std::floor(v - 0.5f));
                    const float fx = u - 0.5f - float(x0), fy = v - 0.5f - float(y0);
                    const float below = (1 - fx) * level.at(x0, y0) + fx * level.at(x0 + 1, y0);
                    const float above = (1 - fx) * level.at(x0, y0 + 1) + fx * level.at(x0 + 1, y0 + 1);
                    samples.push_back((1 - fy) * below + fy * above);
                }
    return samples;
}

Alphas alphasOf(const scene::Image& image) {
    Alphas level{image.width, image.height, {}};
    for (size_t i = 0; i < size_t(image.width) * size_t(image.height); ++i)
        level.a.push_back(float(image.rgba[4 * i + 3]) / 255.0f);
    return level;
}

// Sizes with odd sides, single rows and columns, and a single texel: the clamped edges.
const std::pair<int, int> kSizes[] = {{1, 1}, {1, 7}, {9, 1}, {2, 2}, {37, 23}, {64, 48}, {101, 3}};

} // namespace

// The sampled coverage counts the four lookups of every texel. Cutoffs halfway between the values
// a sample can take (sums of bytes / 255 in sixteenths), so float rounding cannot tip a sample
// either way and the count is exact.
TEST(TextureMipsTest, SampledCoverageCountsTheFourBilinearLookupsOfEveryTexel) {
    uint32_t seed = 1;
    for (const auto& [w, h] : kSizes)
        for (const bool sparse : {false, true}) {
            const scene::Image image = randomImage(w, h, seed++, sparse);
            const std::vector<float> samples = everySample(alphasOf(image));
            ASSERT_EQ(samples.size(), size_t(4 * w * h));
            for (const int step : {1, 700, 2040, 3001, 4079}) {
                const float cutoff = (float(step) + 0.5f) / (255.0f * 16.0f);
                const auto covered =
                    std::count_if(samples.begin(), samples.end(), [&](float s) { return s >= cutoff; });
                EXPECT_EQ(scene::sampledAlphaCoverage(image, cutoff), double(covered) / double(samples.size()))
                    << w << " × " << h << (sparse ? " sparse" : "") << ", cutoff " << cutoff;
            }
        }
}

// Each level of a chain with a cutoff is the 2 × 2 box average of the level above, its alpha
// scaled so that the k = ⌈c n⌉ largest of its n samples reach the cutoff, c level 0's sampled
// coverage: the scale puts the k-th largest half a byte above it. Held to the byte against that
// definition with every sample sorted; without a cutoff, the box average alone.
TEST(TextureMipsTest, EveryLevelIsTheBoxAverageScaledByItsKthLargestSample) {
    uint32_t seed = 100;
    for (const auto& [w, h] : kSizes)
        for (const bool sparse : {false, true})
            for (const float cutoff : {0.0f, 0.5f, 0.3f}) {
                const scene::Image image = randomImage(w, h, seed++, sparse);
                const std::vector<scene::Image> chain =
                    scene::buildMipChain(image, cutoff > 0.0f ? std::optional(cutoff) : std::nullopt);
                const std::string what = std::to_string(w) + " × " + std::to_string(h) + (sparse ? " sparse" : "") +
                                         ", cutoff " + std::to_string(cutoff);
                ASSERT_EQ(chain.front().rgba, image.rgba) << what;
                const double target = cutoff > 0.0f ? scene::sampledAlphaCoverage(image, cutoff) : 0.0;
                // The levels in float, as the chain keeps them between levels.
                int lw = w, lh = h;
                std::vector<glm::vec4> texels;
                for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
                    const uint8_t* p = image.rgba.data() + 4 * i;
                    texels.push_back(glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f);
                }
                for (size_t l = 1; l < chain.size(); ++l) {
                    const int nw = std::max(1, lw / 2), nh = std::max(1, lh / 2);
                    std::vector<glm::vec4> next;
                    for (int y = 0; y < nh; ++y)
                        for (int x = 0; x < nw; ++x) {
                            auto t = [&](int dx, int dy) {
                                return texels[size_t(std::min(2 * y + dy, lh - 1)) * size_t(lw) +
                                              size_t(std::min(2 * x + dx, lw - 1))];
                            };
                            next.push_back(0.25f * (t(0, 0) + t(1, 0) + t(0, 1) + t(1, 1)));
                        }
                    texels = std::move(next), lw = nw, lh = nh;
                    float scale = 1.0f;
                    if (cutoff > 0.0f) {
                        Alphas alphas{lw, lh, {}};
                        for (const glm::vec4& t : texels) alphas.a.push_back(t.a);
                        std::vector<float> samples = everySample(alphas);
                        std::sort(samples.begin(), samples.end(), std::greater<float>());
                        const auto k = size_t(std::ceil(target * double(samples.size()) - 1e-9));
                        scale = k == 0                  ? 0.0f
                                : samples[k - 1] > 0.0f ? std::min((cutoff + 0.5f / 255.0f) / samples[k - 1], 256.0f)
                                                        : 256.0f;
                    }
                    ASSERT_EQ(chain[l].width, lw) << what;
                    ASSERT_EQ(chain[l].height, lh) << what;
                    auto toByte = [](float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
                    std::vector<uint8_t> expected;
                    for (const glm::vec4& t : texels)
                        expected.insert(expected.end(), {toByte(t.r), toByte(t.g), toByte(t.b), toByte(t.a * scale)});
                    ASSERT_EQ(chain[l].rgba, expected) << what << ", level " << l;
                }
                EXPECT_EQ(lw * lh, 1) << what << ": the chain goes down to 1 × 1";
            }
}

// A renderer's textures, their chains built on every core: each handed over once, in the
// requests' order, on the calling thread, as the levels below level 0 of the chain built alone —
// whatever the batch size (every request in one batch, one request per batch, batches that end
// mid-list) — and a texture without mipmaps with no level below.
TEST(TextureMipsTest, ChainsBuiltTogetherComeInOrderEachAsBuiltAlone) {
    std::vector<scene::Image> images;
    std::vector<scene::MipChainRequest> requests;
    for (const auto& [w, h] : kSizes)
        images.push_back(randomImage(w, h, uint32_t(20 + images.size()), images.size() % 2 == 0));
    for (size_t i = 0; i < images.size(); ++i)
        requests.push_back({&images[i], i % 3 == 1 ? std::nullopt : std::optional(0.5f), i % 4 != 2});
    std::vector<std::vector<scene::Image>> alone;
    for (const scene::MipChainRequest& r : requests)
        alone.push_back(r.mipmaps ? scene::buildMipChain(*r.level0, r.alphaCutoff) : std::vector{*r.level0});
    const std::thread::id caller = std::this_thread::get_id();
    // Batches: all in one; one each; the first five, then one each; the first six, then the last.
    size_t firstFive = 0;
    for (size_t i = 0; i < 5; ++i) firstFive += images[i].rgba.size();
    for (const size_t batchBytes : {scene::kMipBatchBytes, size_t{1}, firstFive, firstFive + images[5].rgba.size()}) {
        std::vector<size_t> order;
        scene::forEachMipChain(
            requests,
            [&](size_t i, const std::vector<scene::Image>& below) {
                const std::string where = "batch " + std::to_string(batchBytes) + ", chain " + std::to_string(i);
                EXPECT_EQ(std::this_thread::get_id(), caller) << where;
                order.push_back(i);
                ASSERT_EQ(below.size() + 1, alone[i].size()) << where;
                for (size_t l = 0; l < below.size(); ++l)
                    EXPECT_TRUE(below[l].rgba == alone[i][l + 1].rgba) << where << ", level " << l + 1;
            },
            batchBytes);
        std::vector<size_t> expected(requests.size());
        std::iota(expected.begin(), expected.end(), size_t{0});
        EXPECT_EQ(order, expected) << "batch " << batchBytes;
    }
}
