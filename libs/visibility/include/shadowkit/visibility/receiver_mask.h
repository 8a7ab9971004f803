// Shadow caster culling by visible receivers: a low-resolution mask over one shadow map
// recording, per texel, the farthest (from the light) depth of any receiver the camera
// sees there; a caster is needed only if somewhere under its footprint a marked receiver
// lies farther from the light than the caster's nearest point.
#pragma once

#include "shadowkit/visibility/core_types.h"

#include <optional>
#include <span>
#include <vector>

namespace shadowkit::visibility {

class ReceiverMask {
public:
    // `clipFromWorld` is the shadow map's; depths are compared in the metric the map stores:
    // dot(linearDepthFromWorld, (ws, 1)) when given (linear layout), else clip z / w.
    ReceiverMask(int size, const Mat4& clipFromWorld, std::optional<Vec4> linearDepthFromWorld);

    int size() const { return m_size; }
    // The map depth of a world point in the stored metric, its texel (row-major, y up,
    // clamped to the mask: a receiver beyond the edge reads the edge texels), or nullopt
    // when it lies behind the map's projection centre.
    struct Sample {
        int texel = 0;
        float depth = 0.0f;
    };
    std::optional<Sample> sample(const Vec3& ws) const;

    // Marks one visible receiver point (the shader does the same for every camera pixel).
    void mark(const Vec3& ws);
    // Direct access for a GPU-built mask: size² farthest depths, -inf where nothing is marked.
    std::span<float> texels() { return m_levels[0]; }
    // After marking: widens every mark by `dilation` texels (the lookup's filter footprint
    // and normal offset, in mask texels) and builds the max pyramid mayShadow descends.
    void finish(int dilation);

    // Whether a caster inside `wsBox` may shadow a marked receiver: false only when for every
    // texel under the box's footprint the marked depth is no farther than the box's nearest
    // depth. Conservative: true when any corner lies behind the projection centre.
    bool mayShadow(const Aabb& wsBox) const;

    size_t markedTexels() const;
    bool everything() const { return m_everything; }

private:
    int texelOf(double ndc) const; // of one NDC coordinate, clamped to the mask

    int m_size;
    Mat4 m_clipFromWorld;
    std::optional<Vec4> m_linearDepthFromWorld;
    bool m_everything = false;                // a receiver behind the centre: keep every caster
    std::vector<std::vector<float>> m_levels; // [0] full size, then halves (max of 2x2)
};

} // namespace shadowkit::visibility
