// Mipmaps for alpha-tested textures that keep their coverage.
//
// Based on: I. Castaño, "Computing Alpha Mipmaps" (2010), and its use for foliage in The
// Witness. A box-filtered mip level averages alpha: leaves covering 40 % of a texture at
// alpha 1 become a level of alpha ≈ 0.4 everywhere, below a cutoff of 0.5, and the canopy
// of a distant tree — or of any tree in a shadow map whose texels are larger than its
// leaves — vanishes. Each level's alpha is therefore scaled by the factor s that makes its
// coverage at the cutoff equal to level 0's (a selection: bilinear interpolation is linear, so
// the scale putting the right quantile of the level's samples at the cutoff). Colour is
// box-filtered as usual.
//
// Deviation: Castaño counts stored texels. We count what a bilinear lookup covers
// (sampledAlphaCoverage): a sparse canopy's isolated covered texels shrink under
// interpolation — a covered texel among open ones is above the cutoff over less than its area
// — and a shadow map read at mip level 4 of a 30 %-covered card came out 17 % shadowed against
// the truth's 30 % with texel counts (tests/alpha_shadows_test.cpp).
#pragma once

#include "shadowkit/scene/image.h"

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace shadowkit::scene {

// Fraction of texels whose alpha is at least `cutoff` (in [0, 1]); 0 for an empty image.
double alphaCoverage(const Image& image, float cutoff);
// The fraction a bilinear lookup covers: the alpha test at 2 × 2 points inside every texel
// (texel units x + ¼ and x + ¾, centres at x + ½), each interpolated from its four nearest
// texels, edges clamped.
double sampledAlphaCoverage(const Image& image, float cutoff);

// The full chain down to 1×1, level 0 first (GL's sizes: each side halved, rounded down, at
// least 1). With a cutoff, every level's alpha is scaled to keep level 0's coverage at it;
// without, plain 2×2 box filtering.
std::vector<Image> buildMipChain(const Image& level0, std::optional<float> alphaCutoff);

// The same chain without level 0: levels 1 to the last (empty for a 1 × 1 or empty image).
std::vector<Image> buildMipLevelsBelow(const Image& level0, std::optional<float> alphaCutoff);

// One texture of forEachMipChain: the levels below *level0 (buildMipLevelsBelow at
// `alphaCutoff`), or none without mipmaps.
struct MipChainRequest {
    const Image* level0 = nullptr;
    std::optional<float> alphaCutoff;
    bool mipmaps = true;
};
// Builds the levels below level 0 of every request on every core and hands them to
// `use(index, levels)` in the requests' order, on the calling thread (a GL upload may follow;
// level 0 is the caller's own image, not copied). The levels are built a batch at a time, a batch
// being as many requests in a row as hold up to `batchBytes` of level 0 (at least one), so a scene
// of many large textures never holds all of its chains at once.
inline constexpr size_t kMipBatchBytes = size_t{64} << 20;
void forEachMipChain(std::span<const MipChainRequest> requests,
                     const std::function<void(size_t, const std::vector<Image>&)>& use,
                     size_t batchBytes = kMipBatchBytes);

} // namespace shadowkit::scene
