// Temporal hysteresis for shadow set-ups: stable texels for every technique, warped or not.
//
// A uniform map is stabilised by snapping: shifted by whole texels it samples the same world
// points again (cascades.h). A warped map cannot be snapped — its texels differ in size over
// the map, and a perspective warp that follows the camera changes every texel every frame —
// but it can be *held*: its warp kept fixed in the world while the camera moves, and only
// shifted by whole texels of its own post-warp space, which is the same world lattice again,
// exactly, since x_ndc + t is still a whole-texel shift after the perspective divide.
//
// SetupHysteresis does that per shadow view: each frame it computes the set-up a fresh fit
// would give, and keeps the last refit's matrix (its texel lattice), shifted by whole texels
// so that it covers this frame's focus body of the view. It refits the view — one pop — only
// when the held lattice cannot cover that body any more, or when it has gone stale: when
// its texels along the camera's central ray are more than `maxTexelGrowth` times what a
// refit would give there now (a warp concentrates texels at the viewer's position of its
// refit; the camera leaving that position is what makes a held warp worse than a new one).
// A refit covers the body with `margin` to spare and, for a moving camera, also the
// bodies it will have on its way `lookaheadFrames` on (its last frame's motion repeated), as
// far as that room costs at most 3× a fresh fit's texel size, unless the light has just moved
// (a moving light refits every frame, and room for the motion would only coarsen each refit).
// Depth is refitted on its own when the body leaves the held depth range: it does not move
// texels.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <optional>

namespace shadowkit::core {

/// When held texel lattices are refitted: the margin round the focus body, the texel growth allowed, the motion covered
/// ahead.
struct HysteresisOptions {
    /// Spare room round the focus body at a refit, as a fraction of the map's extent: the body
    /// may move or grow this much before it forces a refit, and every texel is this much
    /// larger than a fresh fit's while it is held (a still view included). [0, 1].
    double margin = 0.05;
    /// Refit when a held texel on the camera's central ray is this many times the size of
    /// what a refit would give there now (linear size, on a plane facing the light). > 1.
    double maxTexelGrowth = 1.25;
    /// At a refit, also cover the focus bodies of the camera on its way this many frames on,
    /// extrapolated from its last motion (0: this frame's body only). A still camera pays
    /// nothing for it; a moving one trades texels for fewer refits. [0, 1000].
    double lookaheadFrames = 60.0;
};

/// Fails naming the field ("hysteresis.margin", "hysteresis.growth", "hysteresis.lookahead").
Status validate(const HysteresisOptions& options);

/// The size, on a plane facing the light, of the texel of `view` at `wsPoint`: wsTexelSize
/// (output_conventions.h) of its clip matrix. +inf where the map's projection degenerates there
/// (w <= 0 or a zero determinant).
double texelFootprint(const ShadowView& view, int mapSize, const Vec3& wsLightDirection, const Vec3& wsPoint);

/// Held texel lattices: a set-up kept fixed in the world across frames and refitted only when it must be.
class SetupHysteresis {
public:
    /// Holds nothing yet: the first next() fits afresh.
    explicit SetupHysteresis(HysteresisOptions options = {}) : m_options(options) {}

    /// This frame's set-up: every view held (whole-texel shifted) while it covers its focus
    /// body and has not gone stale, else refitted with the margin. Everything is refitted when
    /// the light, technique, map size, depth layout or view count changed. (A grown scene or
    /// a new projection needs no rule of its own: the body to cover is this frame's.)
    Result<ShadowSetup> next(const ShadowSetupInputs& inputs);
    /// Views refitted by the last next() (all of them on the first call), and why.
    struct Refits {
        int views = 0;   ///< all refitted views
        int toCover = 0; ///< the held lattice could not cover the view's focus body any more
        int stale = 0;   ///< its texels had grown past maxTexelGrowth
    };
    const Refits& lastRefits() const { return m_refits; }      ///< what the last next() refitted
    int refittedViews() const { return m_refits.views; }       ///< lastRefits().views
    bool refitted() const { return m_refits.views > 0; }       ///< any view refitted by the last next()
    void reset() { m_held.reset(), m_previousCamera.reset(); } ///< a camera cut: the next frame fits afresh

private:
    HysteresisOptions m_options;
    struct Held {
        ShadowSetupInputs inputs; ///< of the last frame
        ShadowSetup setup;        ///< this frame's views: held lattices, shifted
    };
    std::optional<Held> m_held;
    std::optional<PerspectiveCamera> m_previousCamera;
    Refits m_refits;
};

} // namespace shadowkit::core
