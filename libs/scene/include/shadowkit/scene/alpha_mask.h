// The alpha test of a masked material (glTF 2.0 §3.9.4) at texture level 0, answered from a
// table where it can be: what the ray-traced truth asks on every hit of a leaf card.
//
// Exactly `baseAlpha · sampleLevel0(texture, uv).a ≥ cutoff`, but a bilinear sample is a convex
// combination of its four texels, so where all four lie on one side of the cutoff the answer is
// known without sampling. Leaf textures are nearly all opaque or empty texels: the table of
// bilinear cells answers most hits with one byte, and only cells straddling a leaf's edge sample.
#pragma once

#include "shadowkit/scene/material.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace shadowkit::scene {

class AlphaMask {
public:
    // An empty image: the factor's alpha alone decides (sampleLevel0 reads 1 there).
    AlphaMask(Texture texture, float baseAlpha, float cutoff);

    // Whether the surface covers `uv`: the same answer as the definition above, for every uv
    // (non-finite and far out of [0, 1] included), wrap mode and filter.
    bool covers(glm::vec2 uv) const;
    // Whether covers(uv) is answered by the table, without sampling (for tests and statistics).
    bool decidedByTable(glm::vec2 uv) const;

private:
    enum class Cell : uint8_t { Hole, Covered, Edge };

    bool sampled(glm::vec2 uv) const;
    const Cell* cellAt(glm::vec2 uv) const; // null: sample

    Texture m_texture;
    float m_baseAlpha = 1.0f, m_cutoff = 0.5f;
    // LINEAR textures: cell (i, j), i in [0, width], j in [0, height], is the bilinear footprint
    // whose lower texel index is (i − 1, j − 1) before wrapping — every footprint of a uv in
    // [0, 1]², the one-texel ring beyond the edges included (where the wrap mode decides which
    // texels it reads). Empty for NEAREST textures and untextured surfaces.
    std::vector<Cell> m_cells;
};

} // namespace shadowkit::scene
