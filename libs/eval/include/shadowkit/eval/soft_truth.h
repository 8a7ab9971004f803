// Soft ray-traced truth: the fraction of the sun's disk a surface point sees (issue 34's truth
// for soft shadows). The sun is not a point: it subtends about 0.53°, so under a 20 m tree its
// penumbra on the ground is some 19 cm wide. Per point, shadow rays go towards stratified
// directions spread uniformly over the disk's solid angle; a few probe rays first (on the rim
// and inside), and the full count only where they disagree (the penumbrae), with the standard
// error it leaves.
#pragma once

#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/ray_scene.h"
#include "shadowkit/eval/truth.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::eval {

/// The sun as a disk: where it is and how large it looks.
struct SunDisk {
    core::Vec3 wsTowardsSun{0.0, 1.0, 0.0}; ///< unit vector from the scene towards the disk's centre
    double angularDiameterDegrees = 0.53;   ///< the real sun's; 0 is the point-like sun of the hard truth
};

/// A spot or point light of some size: a sphere of uniform radiance (a lamp's bulb or globe).
struct SphereLight {
    core::Vec3 wsCentre{0.0};
    double radius = 0.05; ///< metres; 0 a point
};

struct SoftTruthOptions {
    /// Shadow rays per point in a penumbra, rounded up to a square (stratified k × k).
    int samples = 256;
    /// Rays per point first: 8 on the disk's rim (turned at random per point) and this many
    /// inside (rounded up to a square, stratified); all visible or all blocked ends the point
    /// there. A straight edge cutting off more than 1.3 % of the disk always meets the rim's
    /// probes, so a point they call umbra or full sun is within 1.3 % of it (an occluder thinner
    /// than the probes' spacing, a twig across the disk, can still pass between them).
    int probes = 9;
    /// Which jittered sample set: two seeds give independent estimates of the same truth.
    uint64_t seed = 1;
    /// Shadow-ray start offset along the geometric normal, a fraction of the scene diagonal (as
    /// TruthOptions).
    double normalOffsetFraction = 1e-5;
};

struct SoftTruth {
    int width = 0, height = 0;
    /// Row-major, top row first: the visible fraction of the disk, 0..1, at each point of `hits`
    /// facing the sun; NaN where there is no surface or it faces away.
    std::vector<float> visibility;
    /// The estimate's standard error per point: sqrt(v (1 - v) / n) for n stratified samples (an
    /// upper bound: stratification only lowers it); 0 where the probes agreed.
    std::vector<float> standardError;
    double seconds = 0.0;
    uint64_t rays = 0;
    uint64_t penumbraPoints = 0; ///< points that took the full sample count
};

/// The sun disk's visible fraction at the surface points of `hits` (computeTruth's). Every core
/// (TBB). An angular diameter of 0 traces one ray per point, exactly the hard truth's.
SoftTruth computeSoftTruth(const RayScene& rays, const TruthBuffers& hits, const SunDisk& sun,
                           const SoftTruthOptions& options = {});
/// The visible fraction of a sphere light at the points of `underLight` (eval::underLight's: its
/// facesLight marks the points the light reaches; NaN elsewhere). The sphere seen from a point at
/// distance d is a disk of angular radius asin(R / d), uniform in solid angle as the sun's; each
/// shadow ray must be free up to the sphere's near surface along it. A radius of 0 traces the
/// hard truth's one ray towards the centre.
SoftTruth computeSphereSoftTruth(const RayScene& rays, const TruthBuffers& underLight, const SphereLight& light,
                                 const SoftTruthOptions& options = {});

/// Rendered shadows against the soft truth.
struct SoftFigures {
    double sunAngleDegrees = 0.0; ///< the disk's angular diameter
    int64_t comparedPx = 0;       ///< the hard comparison's valid pixels (surface agreed, facing the sun)
    int64_t penumbraPx = 0;       ///< of those, where the true visibility is in (0.02, 0.98)
    double softMae = 0.0;         ///< mean |rendered − true visibility| over the compared pixels
    double penumbraMae = 0.0;     ///< the same over the penumbra pixels (0 when there are none)
    double softWrongPct = 0.0;    ///< % of the compared pixels off by more than 0.25
    /// Penumbra width, rendered against true: the compared pixels whose rendered term is in
    /// (0.1, 0.9) over those whose true visibility is. Both are the shadows of the same edges, so
    /// their bands' areas are edge length × 10–90 % width, and the ratio is the rendered
    /// penumbrae's mean width over the true ones' (weighted by edge length): 1 as wide, 0 hard
    /// edges, above 1 too soft. One ratio for the view: an edge drawn too wide and one too narrow
    /// cancel (penumbra_mae sees both). NaN where the truth has no such pixel.
    double penumbraWidthRatio = 0.0;
    double truthSeconds = 0.0; ///< computing the soft truth (SoftTruth::seconds)
    uint64_t truthRays = 0;    ///< its shadow rays
};

/// The rendered shadow term (1 lit … 0 shadowed, core::RasterBuffers::shadowTerm) against the
/// soft truth, over the pixels `classes` (the hard comparison's) calls valid.
SoftFigures compareSoft(std::span<const float> shadowTerm, const SoftTruth& soft, std::span<const PixelClass> classes,
                        double sunAngleDegrees);

/// Direction `k` of a k × k stratified set over a cone of half-angle `halfAngle` round `axis`
/// (unit), uniform in solid angle: (u, v) in [0, 1)² mapped to the unit disk by Shirley and
/// Chiu's concentric map, its radius squared the fraction of the cap's solid angle. In double:
/// 1 - cos of the sun's 4.6 mrad is 1.1e-5, about 180 float steps.
core::Vec3 coneDirection(const core::Vec3& axis, double halfAngle, double u, double v);

} // namespace shadowkit::eval
