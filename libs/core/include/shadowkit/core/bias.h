// Depth-bias settings against self-shadowing (acne) and their recommended values.
#pragma once

#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/core/shadow_setup.h"

namespace shadowkit::core {

/// Which caster faces are left out of the shadow map.
enum class CasterCull {
    None,  ///< both sides: the receiver's own front face is in the map (needs bias)
    Back,  ///< front faces only (the usual choice for closed meshes)
    Front, ///< back faces only: "back-side rendering" (Scherzer 2005 §4.2): the stored depth is the
           // far side of each caster, so lit front faces are never compared with themselves
    /// Back faces of closed casters only (scene/closed_surface.h: mesh levels that bound solids,
    /// single-sided materials, no mirrored instance); open ones draw both sides. Without bias the
    /// map is None's — a ray from the light enters a solid through a face turned towards it —
    /// for fewer samples written; with slope-scaled offset it is not: a steep near side is
    /// pushed back past what its far side would have stored (docs/performance.md).
    BackOfClosed,
};

/// Caster-side and receiver-side bias of a shadow map: slope, constant, normal offset, receiver plane, culled faces.
struct BiasSettings {
    /// The slope term is glPolygonOffset's factor for hyperbolic depth, applied per fragment for
    /// linear depth. A constant unit is 2^-24 of the depth range for both: added to clip z
    /// (z += constant·2^-24·w) rather than as glPolygonOffset's units, which for a float depth
    /// buffer scale with the largest depth in the primitive and are unbounded for one that
    /// crosses a warped map's w = 0 under depth clamping (docs/bias-and-filtering.md).
    double slope = 2.0;    ///< × max depth slope; [0, 100]
    double constant = 4.0; ///< minimum resolvable depth steps; [0, 1e6]
    /// Receiver moved along its normal by this many texels' world size before the lookup
    /// (normal offset), whatever its slope; [0, 10].
    double normalOffset = 0.0;
    /// Receiver moved, besides, along its drawn triangle's normal f by this × its texel's
    /// footprint on f: k (|a_u·f| + |a_v·f|), a_u and a_v one texel's world steps in u and v
    /// across the light — 0 for a face turned to the light, the texel's extent along a face the
    /// light grazes; ½ clears the triangle's own depth anywhere in its texel (skNormalOffset in
    /// glsl/shadowkit_shadows.glsl derives it); [0, 10].
    double normalOffsetFootprint = 0.0;
    /// With either normal offset: a receiver whose own texel, before the offset, holds a caster
    /// nearer the light than its own surface reaches (8 texels of its depth slope) stays
    /// shadowed where the light grazes its triangle (|f·ℓ| < 0.15) and the offset carried its
    /// lookup a quarter texel or more across the map — an offset against the receiver's own
    /// surface must not move a distant caster's shadow edge (skOffsetGuard in
    /// glsl/shadowkit_shadows.glsl; docs/bias-and-filtering.md). The hard test and the 2 × 2 PCF.
    bool offsetGuard = false;
    /// Receiver-plane depth bias: the reference depth follows the receiver's plane to each
    /// texel (tap) centre, using the screen derivatives of the shadow coordinates.
    bool receiverPlane = false;
    /// Caster faces culled when drawing the map (front: back sides only). Faces are turned
    /// towards or away from the light in the world (caster_facing.h), whatever the warp.
    CasterCull cull = CasterCull::None;
};

/// Checks the ranges above; error fields "bias.slope", "bias.constant", "bias.normal_offset",
/// "bias.normal_offset_footprint".
Status validate(const BiasSettings& bias);

/// The bias every caller gets unless it sets its own (the renderer, `shadowkit render`,
/// `eval`, `compare`): chosen per technique and depth layout from measurements (docs/bias-and-filtering.md,
/// "Bias and filtering"), with receiver-plane depth bias switched on for wide filter
/// kernels, which self-shadow sloped receivers without it.
BiasSettings recommendedBias(Technique technique, DepthLayout layout, const FilterSettings& filter = {});

} // namespace shadowkit::core
