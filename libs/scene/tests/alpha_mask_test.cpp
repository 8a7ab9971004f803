// AlphaMask answers the alpha test as sampling level 0 does, for every uv, wrap mode and factor,
// and answers it from its table wherever a leaf texture is not at an edge.
#include "shadowkit/scene/alpha_mask.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace shadowkit {
namespace {

// The definition the truth used before the table: glTF's test on level 0's bilinear sample.
bool coversBySampling(const scene::Texture& t, float baseAlpha, float cutoff, glm::vec2 uv) {
    return baseAlpha * (t.image.width > 0 ? scene::sampleLevel0(t, uv).a : 1.0f) >= cutoff;
}

// A leaf-like mask: opaque inside a disc, empty outside, a soft rim of a texel or two, and a
// few texels at 127 and 128 (either side of 0.5) where bilinear samples land on the cutoff.
scene::Texture leafTexture(int width, int height) {
    scene::Texture t;
    t.image = scene::Image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float r =
                std::hypot((float(x) + 0.5f) / float(width) - 0.5f, (float(y) + 0.5f) / float(height) - 0.45f) * 2.0f;
            const float a = std::clamp((0.8f - r) * 12.0f + 0.5f, 0.0f, 1.0f);
            t.image.pixel(x, y)[3] = uint8_t(std::lround(a * 255.0f));
        }
    }
    if (width >= 3 && height >= 3) t.image.pixel(1, 2)[3] = 127, t.image.pixel(2, 2)[3] = 128;
    return t;
}

// Random uvs over [-2, 3]² (far beyond the table's ring too), a share of them on exact texel
// centres and cell edges of the texture, where the bilinear weights are 0 or ½.
std::vector<glm::vec2> testUvs(int width, int height, int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> wide(-2.0f, 3.0f);
    std::uniform_int_distribution<int> texel(-2, 2 * std::max(width, height));
    std::vector<glm::vec2> uvs;
    for (int k = 0; k < count; ++k) {
        if (k % 4 == 0)
            uvs.push_back({float(texel(rng)) * 0.5f / float(width), float(texel(rng)) * 0.5f / float(height)});
        else
            uvs.push_back({wide(rng), wide(rng)});
    }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (const glm::vec2 odd : {glm::vec2(nan, 0.5f), glm::vec2(0.5f, inf), glm::vec2(-inf, nan),
                                glm::vec2(1e30f, -1e30f), glm::vec2(0.0f), glm::vec2(1.0f)})
        uvs.push_back(odd);
    return uvs;
}

TEST(AlphaMaskTest, AnswersAsLevel0SamplingDoesForEveryUvWrapModeAndFactor) {
    using scene::TextureWrap;
    for (const auto& [width, height] : {std::pair{32, 24}, std::pair{7, 5}, std::pair{1, 1}}) {
        for (const TextureWrap wrapS : {TextureWrap::Repeat, TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge}) {
            for (const TextureWrap wrapT : {TextureWrap::Repeat, TextureWrap::ClampToEdge}) {
                for (const bool nearest : {false, true}) {
                    scene::Texture t = leafTexture(width, height);
                    t.wrapS = wrapS, t.wrapT = wrapT, t.nearest = nearest;
                    for (const auto& [baseAlpha, cutoff] :
                         {std::pair{1.0f, 0.5f}, std::pair{0.6f, 0.3f}, std::pair{1.0f, 0.0f}, std::pair{1.0f, 1.0f},
                          std::pair{0.0f, 0.5f}, std::pair{-1.0f, -0.5f}, std::pair{NAN, 0.5f}, std::pair{1.0f, NAN}}) {
                        const scene::AlphaMask mask(t, baseAlpha, cutoff);
                        int mismatches = 0;
                        for (const glm::vec2 uv : testUvs(width, height, 4000, uint32_t(width * 131 + height)))
                            mismatches += mask.covers(uv) != coversBySampling(t, baseAlpha, cutoff, uv);
                        EXPECT_EQ(mismatches, 0)
                            << width << "×" << height << " wrap " << int(wrapS) << int(wrapT)
                            << (nearest ? " nearest" : "") << " factor " << baseAlpha << " cutoff " << cutoff;
                    }
                }
            }
        }
    }
}

TEST(AlphaMaskTest, AnUntexturedSurfaceIsItsFactorsAlpha) {
    EXPECT_TRUE(scene::AlphaMask(scene::Texture{}, 0.7f, 0.5f).covers({0.3f, 0.3f}));
    EXPECT_FALSE(scene::AlphaMask(scene::Texture{}, 0.4f, 0.5f).covers({0.3f, 0.3f}));
}

TEST(AlphaMaskTest, ALeafTextureIsAnsweredByTheTableAwayFromItsEdge) {
    const scene::Texture t = leafTexture(64, 64);
    const scene::AlphaMask mask(t, 1.0f, 0.5f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int decided = 0, count = 20000;
    for (int k = 0; k < count; ++k) decided += mask.decidedByTable({unit(rng), unit(rng)});
    // The rim (alpha between 0 and 1) is about 2 texels of a 64-texel disc of radius 26: some
    // 3 % of the square's cells straddle it once each cell's four texels are counted.
    EXPECT_GT(decided, count * 9 / 10);
    // A texture that really is all edge (every texel at the cutoff) is never decided by the table.
    scene::Texture flat = t;
    for (size_t i = 3; i < flat.image.rgba.size(); i += 4) flat.image.rgba[i] = 128;
    EXPECT_FALSE(scene::AlphaMask(flat, 1.0f, 128.0f / 255.0f).decidedByTable({0.5f, 0.5f}));
}

} // namespace
} // namespace shadowkit
