#include "shadowkit/scene/alpha_mask.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace shadowkit::scene {

namespace {

float alphaAt(const Texture& t, int x, int y) {
    return float(t.image.pixel(wrapTexelIndex(x, t.image.width, t.wrapS),
                               wrapTexelIndex(y, t.image.height, t.wrapT))[3]) /
           255.0f;
}

} // namespace

AlphaMask::AlphaMask(Texture texture, float baseAlpha, float cutoff)
    : m_texture(std::move(texture)), m_baseAlpha(baseAlpha), m_cutoff(cutoff) {
    const int w = m_texture.image.width, h = m_texture.image.height;
    if (w <= 0 || h <= 0 || m_texture.nearest) return;
    // A bilinear sample of texels in [lo, hi] lies in [lo, hi] up to the rounding of its three
    // mixes (a few ulps of 1); `margin` is far wider, so a cell is called only where every uv in
    // it gives the sampled answer. NaN factors make every cell an edge, which samples.
    const float margin = 1e-5f * (1.0f + std::abs(m_baseAlpha));
    m_cells.resize(size_t(w + 1) * size_t(h + 1));
    for (int j = 0; j <= h; ++j) {
        for (int i = 0; i <= w; ++i) {
            const float a[4] = {alphaAt(m_texture, i - 1, j - 1), alphaAt(m_texture, i, j - 1),
                                alphaAt(m_texture, i - 1, j), alphaAt(m_texture, i, j)};
            const auto [aMin, aMax] = std::minmax({a[0], a[1], a[2], a[3]});
            const float lo = std::min(m_baseAlpha * aMin, m_baseAlpha * aMax);
            const float hi = std::max(m_baseAlpha * aMin, m_baseAlpha * aMax);
            m_cells[size_t(j) * size_t(w + 1) + size_t(i)] =
                lo >= m_cutoff + margin ? Cell::Covered : (hi < m_cutoff - margin ? Cell::Hole : Cell::Edge);
        }
    }
}

bool AlphaMask::sampled(glm::vec2 uv) const {
    const float alpha = m_baseAlpha * (m_texture.image.width > 0 ? sampleLevel0(m_texture, uv).a : 1.0f);
    return alpha >= m_cutoff;
}

const AlphaMask::Cell* AlphaMask::cellAt(glm::vec2 uv) const {
    if (m_cells.empty() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return nullptr;
    // The footprint's lower texel as sampleLevel0 finds it (the same float operations).
    const int w = m_texture.image.width, h = m_texture.image.height;
    const glm::vec2 st =
        glm::clamp(uv * glm::vec2(float(w), float(h)), glm::vec2(-16777216.0f), glm::vec2(16777216.0f));
    const glm::vec2 base = glm::floor(st - 0.5f);
    const int i = int(base.x) + 1, j = int(base.y) + 1;
    if (i < 0 || i > w || j < 0 || j > h) return nullptr; // beyond the ring: texels wrapped further
    return &m_cells[size_t(j) * size_t(w + 1) + size_t(i)];
}

bool AlphaMask::covers(glm::vec2 uv) const {
    const Cell* cell = cellAt(uv);
    if (!cell || *cell == Cell::Edge) return sampled(uv);
    return *cell == Cell::Covered;
}

bool AlphaMask::decidedByTable(glm::vec2 uv) const {
    const Cell* cell = cellAt(uv);
    return cell && *cell != Cell::Edge;
}

} // namespace shadowkit::scene
