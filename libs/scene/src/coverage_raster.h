// Coverage rasterisation for the bakers of far levels (billboard_cloud.cpp, octahedral_impostor.cpp):
// triangles of CloudSources, already placed in a grid's texel units, drawn at 4 × 4 samples a
// texel with their own alpha test, then written into an RGBA8 target as a dithered 0/255 alpha
// that keeps each texel's covered fraction on average. Internal to libs/scene.
#pragma once

#include "shadowkit/scene/billboard_cloud.h"

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace shadowkit::scene::coverage {

constexpr int kSamplesPerSide = 4; // per texel side: 16 coverage samples a texel

// Which texels of each alpha-tested source pass its cutoff, a byte each: most samples of a leaf
// card fall on its texture's holes, and this table is a quarter of the texture's bytes to touch.
using KeptTexels = std::map<const CloudSource*, std::vector<uint8_t>>;
KeptTexels keptTexelsOf(std::span<const CloudSource> sources, float alphaCutoff);

// A grid of texels being drawn: which of each texel's 16 samples are covered (one bit each) and
// the sum of the covered samples' colours (0–255 a channel).
struct SampleGrid {
    int width = 0, height = 0;
    std::vector<uint16_t> mask;
    std::vector<glm::vec3> colour;
    SampleGrid(int w, int h) : width(w), height(h), mask(size_t(w) * size_t(h), 0), colour(mask.size(), glm::vec3(0)) {}
};

// Covers the samples of `grid` inside the triangle whose corners lie at `q` (grid texel
// units) and are `corners` of `source`, where its alpha test passes (an untextured source covers
// wherever it lies) and no triangle drawn before covered them: the first triangle drawn over a
// sample gives its colour.
void rasterise(SampleGrid& grid, const std::array<glm::vec2, 3>& q, const CloudSource& source,
               const std::array<const Vertex*, 3>& corners, const KeptTexels& kept);

// Writes the grid's texels at least `border` from its edge into `target` at (x + tx, y + ty):
// the mean colour of the covered samples, alpha 255 where the covered fraction passes a 4 × 4
// ordered dither (so a region of coverage c/16 keeps exactly c texels of every 16), the texels
// with no covered sample left as they are. Returns how many texels it keeps.
size_t writeDithered(const SampleGrid& grid, int border, Image& target, int x, int y);

} // namespace shadowkit::scene::coverage
