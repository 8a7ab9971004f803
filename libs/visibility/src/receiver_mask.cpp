// Receiver mask for shadow caster culling.
//
// Based on: Bittner, Mattausch, Silvennoinen, Wimmer, "Shadow Caster Culling for Efficient
// Shadow Mapping", I3D 2011 (docs/references.md). The paper rasterises the visible
// receivers into a light-space mask and tests each caster's bounding volume against it;
// its "depth-aware" variant keeps per texel the receivers' farthest light depth, so a
// caster lying wholly behind every receiver under it is culled too. We build the mask from
// the camera's own depth buffer (every pixel is a receiver point, which is exactly what the
// lookup shades), so it holds no receiver the camera does not see.
//
// Why it is conservative. A receiver at map depth d_r is shadowed by a caster only where the
// caster stores a depth below d_r at a texel the receiver's lookup reads. The lookup reads
// within the filter footprint and normal offset of the receiver's own texel (`dilation`).
// A caster's fragments lie inside its box, whose projection — all corners in front of the
// centre — is inside the rectangle of the projected corners, and whose depth is at least
// the smallest corner depth (the depth metric is linear in world space, or z/w of a
// projective map, both extreme at corners). Polygon offset and bias push caster depths
// farther, never nearer. So if every texel of the rectangle holds d_r <= the box's nearest
// depth, nothing in the box can darken a visible pixel.
#include "shadowkit/visibility/receiver_mask.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::visibility {

ReceiverMask::ReceiverMask(int size, const Mat4& clipFromWorld, std::optional<Vec4> linearDepthFromWorld)
    : m_size(std::max(size, 1)), m_clipFromWorld(clipFromWorld), m_linearDepthFromWorld(linearDepthFromWorld) {
    m_levels.emplace_back(size_t(m_size) * size_t(m_size), -INFINITY);
}

int ReceiverMask::texelOf(double ndc) const {
    return std::clamp(static_cast<int>(std::floor((0.5 * ndc + 0.5) * m_size)), 0, m_size - 1);
}

std::optional<ReceiverMask::Sample> ReceiverMask::sample(const Vec3& ws) const {
    const Vec4 clip = m_clipFromWorld * Vec4(ws, 1.0);
    if (!(clip.w > 1e-12)) return std::nullopt;
    const double depth = m_linearDepthFromWorld ? glm::dot(*m_linearDepthFromWorld, Vec4(ws, 1.0)) : clip.z / clip.w;
    return Sample{texelOf(clip.y / clip.w) * m_size + texelOf(clip.x / clip.w), static_cast<float>(depth)};
}

void ReceiverMask::mark(const Vec3& ws) {
    const auto s = sample(ws);
    if (!s) {
        m_everything = true;
        return;
    }
    float& texel = m_levels[0][size_t(s->texel)];
    texel = std::max(texel, s->depth);
}

void ReceiverMask::finish(int dilation) {
    std::vector<float>& base = m_levels[0];
    for (const float d : base) // the GPU marks NaN for a receiver behind the centre
        if (std::isnan(d)) m_everything = true;
    // Separable max filter: rows, then columns.
    if (dilation > 0) {
        std::vector<float> tmp(base.size());
        for (int pass = 0; pass < 2; ++pass) {
            for (int y = 0; y < m_size; ++y)
                for (int x = 0; x < m_size; ++x) {
                    float best = -INFINITY;
                    for (int k = -dilation; k <= dilation; ++k) {
                        const int u = pass == 0 ? x + k : x, v = pass == 0 ? y : y + k;
                        if (u >= 0 && u < m_size && v >= 0 && v < m_size)
                            best = std::max(best, base[size_t(v * m_size + u)]);
                    }
                    tmp[size_t(y * m_size + x)] = best;
                }
            base.swap(tmp);
        }
    }
    m_levels.resize(1);
    for (int size = m_size; size > 1;) {
        const int half = (size + 1) / 2;
        const std::vector<float>& fine = m_levels.back();
        std::vector<float> coarse(size_t(half) * size_t(half), -INFINITY);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                float& c = coarse[size_t((y / 2) * half + x / 2)];
                c = std::max(c, fine[size_t(y * size + x)]);
            }
        m_levels.push_back(std::move(coarse));
        size = half;
    }
}

bool ReceiverMask::mayShadow(const Aabb& box) const {
    if (m_everything) return true;
    if (box.isEmpty()) return false;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, nearest = INFINITY;
    for (int c = 0; c < 8; ++c) {
        const Vec3 ws = box.corner(c);
        const Vec4 clip = m_clipFromWorld * Vec4(ws, 1.0);
        if (!(clip.w > 1e-12)) return true;
        x0 = std::min(x0, clip.x / clip.w), x1 = std::max(x1, clip.x / clip.w);
        y0 = std::min(y0, clip.y / clip.w), y1 = std::max(y1, clip.y / clip.w);
        nearest = std::min(nearest,
                           m_linearDepthFromWorld ? glm::dot(*m_linearDepthFromWorld, Vec4(ws, 1.0)) : clip.z / clip.w);
    }
    if (x1 < -1.0 || x0 > 1.0 || y1 < -1.0 || y0 > 1.0) return false; // draws nothing into the map
    int tx0 = texelOf(x0), tx1 = texelOf(x1), ty0 = texelOf(y0), ty1 = texelOf(y1);
    // The finest level at which the rectangle spans at most 4 texels a side; a conservative
    // "no" there is final, a "maybe" on a wide rectangle is kept (rare for a tree).
    size_t level = 0;
    while (level + 1 < m_levels.size() && std::max(tx1 - tx0, ty1 - ty0) >= 4) {
        tx0 /= 2, tx1 /= 2, ty0 /= 2, ty1 /= 2;
        ++level;
    }
    const int size = (m_size + (1 << level) - 1) >> level;
    const std::vector<float>& texels = m_levels[level];
    // Rounded down to float, as the marks are: a caster level with a receiver is kept.
    const float threshold = std::nextafter(static_cast<float>(nearest), -INFINITY);
    for (int y = ty0; y <= ty1; ++y)
        for (int x = tx0; x <= tx1; ++x)
            if (texels[size_t(y * size + x)] > threshold) return true;
    return false;
}

size_t ReceiverMask::markedTexels() const {
    return static_cast<size_t>(
        std::count_if(m_levels[0].begin(), m_levels[0].end(), [](float d) { return d > -INFINITY; }));
}

} // namespace shadowkit::visibility
