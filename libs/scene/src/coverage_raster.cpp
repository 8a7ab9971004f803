// Coverage rasterisation for the far levels' bakers (coverage_raster.h).
#include "coverage_raster.h"

#include "shadowkit/scene/material.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace shadowkit::scene::coverage {
namespace {

// A source's texel at uv (nearest, wrapped as its texture is; v runs down the image, glTF's
// convention), as an index into its texels.
size_t texelIndexAt(const CloudSource& source, glm::vec2 uv) {
    const Image& texture = *source.texture;
    // Clamped where a float has no fraction left (and an int conversion would overflow).
    const glm::vec2 st = glm::clamp(uv * glm::vec2(float(texture.width), float(texture.height)),
                                    glm::vec2(-16777216.0f), glm::vec2(16777216.0f));
    return size_t(wrapTexelIndex(int(std::floor(st.y)), texture.height, source.wrapT)) * size_t(texture.width) +
           size_t(wrapTexelIndex(int(std::floor(st.x)), texture.width, source.wrapS));
}

std::vector<uint8_t> texelsKept(const CloudSource& source, float alphaCutoff255) {
    const Image& texture = *source.texture;
    std::vector<uint8_t> kept(size_t(texture.width) * size_t(texture.height));
    for (int y = 0; y < texture.height; ++y)
        for (int x = 0; x < texture.width; ++x)
            kept[size_t(y) * size_t(texture.width) + size_t(x)] =
                source.alphaFactor * float(texture.pixel(x, y)[3]) < alphaCutoff255 ? 0 : 1;
    return kept;
}

constexpr int kSamples = kSamplesPerSide * kSamplesPerSide;
constexpr uint16_t kEverySample = uint16_t((1u << kSamples) - 1u);
// Sample s's place inside its texel (texel units): the middles of the texel's quarters, row by row.
constexpr std::array<glm::vec2, kSamples> kSampleAt = [] {
    std::array<glm::vec2, kSamples> at{};
    for (int s = 0; s < kSamples; ++s)
        at[size_t(s)] = {(float(s % kSamplesPerSide) + 0.5f) / kSamplesPerSide,
                         (float(s / kSamplesPerSide) + 0.5f) / kSamplesPerSide};
    return at;
}();

// The texel columns of row `ty` that can hold a sample of the triangle `q` (texel units): its
// x-extent over the rows either side as well, and a column either side of that. A sample the
// span leaves out lies more than a texel from the triangle, where its barycentric test (a
// rounding error below a thousandth of a texel on planes of a few thousand texels) cannot pass:
// the bake is the same, texel for texel, as testing every texel of the bounding box.
std::pair<int, int> rowReach(const std::array<glm::vec2, 3>& q, int ty) {
    const double bandLo = double(ty) - 1.0, bandHi = double(ty) + 2.0;
    double lo = INFINITY, hi = -INFINITY;
    auto take = [&](double x) { lo = std::min(lo, x), hi = std::max(hi, x); };
    for (size_t a = 0; a < 3; ++a) {
        const glm::dvec2 p(q[a]), r(q[(a + 1) % 3]);
        if (p.y >= bandLo && p.y <= bandHi) take(p.x);
        for (const double y : {bandLo, bandHi}) // where the edge crosses the band's sides
            if ((p.y - y) * (r.y - y) < 0.0) take(p.x + (r.x - p.x) * (y - p.y) / (r.y - p.y));
    }
    if (!(lo <= hi)) return {1, 0}; // the triangle misses the band: no column
    return {int(std::floor(std::max(lo, -1e9))) - 1, int(std::floor(std::min(hi, 1e9))) + 1};
}

// 4 × 4 ordered-dither thresholds (Bayer), in sixteenths: a region of coverage c/16 keeps
// exactly c texels of every 16.
constexpr std::array<int, 16> kBayer{0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

} // namespace

KeptTexels keptTexelsOf(std::span<const CloudSource> sources, float alphaCutoff) {
    KeptTexels keptOf;
    for (const CloudSource& source : sources)
        if (source.texture) keptOf.emplace(&source, texelsKept(source, alphaCutoff * 255.0f));
    return keptOf;
}

void rasterise(SampleGrid& grid, const std::array<glm::vec2, 3>& q, const CloudSource& source,
               const std::array<const Vertex*, 3>& corners, const KeptTexels& keptOf) {
    const int w = grid.width, h = grid.height;
    const float twiceArea = (q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (q[1].y - q[0].y);
    if (std::abs(twiceArea) < 1e-12f) return;
    // What every sample of the triangle reads, read once (the stores below could alias it).
    const glm::vec2 uv0 = corners[0]->uv, uv1 = corners[1]->uv, uv2 = corners[2]->uv;
    const glm::vec3 albedo = corners[0]->albedo;
    const uint8_t* kept = source.texture ? keptOf.at(&source).data() : nullptr;
    const glm::vec2 boxLo = glm::min(q[0], glm::min(q[1], q[2])), boxHi = glm::max(q[0], glm::max(q[1], q[2]));
    for (int ty = std::max(0, int(boxLo.y)); ty <= std::min(h - 1, int(boxHi.y)); ++ty) {
        const auto [spanLo, spanHi] = rowReach(q, ty);
        for (int tx = std::max({0, int(boxLo.x), spanLo}); tx <= std::min({w - 1, int(boxHi.x), spanHi}); ++tx) {
            uint16_t& m = grid.mask[size_t(ty) * size_t(w) + size_t(tx)];
            if (m == kEverySample) continue;
            // Barycentric weights of corners 1 and 2 at all 16 samples at once (no branch: the
            // compiler's vector lanes), inside when all three lie in [0, 1]; then the samples
            // inside and not yet covered, in order.
            std::array<float, kSamples> b1, b2;
            for (size_t s = 0; s < size_t(kSamples); ++s) {
                const float px = float(tx) + kSampleAt[s].x, py = float(ty) + kSampleAt[s].y;
                b1[s] = ((px - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (py - q[0].y)) / twiceArea;
                b2[s] = ((q[1].x - q[0].x) * (py - q[0].y) - (px - q[0].x) * (q[1].y - q[0].y)) / twiceArea;
            }
            uint32_t inside = 0;
            for (size_t s = 0; s < size_t(kSamples); ++s) { // | of ints, not ||: no branch
                const int out = int(b1[s] < 0.0f) | int(b2[s] < 0.0f) | int(b1[s] + b2[s] > 1.0f);
                inside |= uint32_t(out == 0) << s;
            }
            for (uint32_t open = inside & ~uint32_t(m); open != 0; open &= open - 1) {
                const int s = std::countr_zero(open);
                const float b1s = b1[size_t(s)], b2s = b2[size_t(s)];
                glm::vec3 rgb;
                if (source.texture) {
                    const glm::vec2 uv = (1.0f - b1s - b2s) * uv0 + b1s * uv1 + b2s * uv2;
                    const size_t k = texelIndexAt(source, uv);
                    if (!kept[k]) continue;
                    const uint8_t* texel = source.texture->rgba.data() + 4 * k;
                    rgb = glm::vec3(texel[0], texel[1], texel[2]) * albedo;
                } else {
                    rgb = 255.0f * albedo;
                }
                m = uint16_t(m | (1u << s));
                grid.colour[size_t(ty) * size_t(w) + size_t(tx)] += rgb;
            }
        }
    }
}

size_t writeDithered(const SampleGrid& grid, int border, Image& target, int x, int y) {
    size_t opaque = 0;
    for (int ty = border; ty < grid.height - border; ++ty)
        for (int tx = border; tx < grid.width - border; ++tx) {
            const size_t k = size_t(ty) * size_t(grid.width) + size_t(tx);
            const int covered = std::popcount(grid.mask[k]);
            if (covered == 0) continue;
            uint8_t* out = target.pixel(x + tx, y + ty);
            const glm::vec3 mean = glm::clamp(grid.colour[k] / float(covered), 0.0f, 255.0f);
            out[0] = uint8_t(mean.r), out[1] = uint8_t(mean.g), out[2] = uint8_t(mean.b);
            const bool keep = covered > kBayer[size_t((ty % 4) * 4 + tx % 4)];
            out[3] = keep ? 255 : 0;
            opaque += keep ? 1 : 0;
        }
    return opaque;
}

} // namespace shadowkit::scene::coverage
