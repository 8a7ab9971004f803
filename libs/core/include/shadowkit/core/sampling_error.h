// The sampling error a shadow set-up will have where the camera sees receivers: pixels per
// texel, predicted at a sparse sample of visible points instead of measured at every pixel.
//
// Wimmer et al. 2004 §4.1 write the aliasing error at a receiver as dp/ds (perspective
// aliasing: how the parameterization spreads texels over view depth) times cos φ / cos ψ
// (projection aliasing: how the surface turns towards the eye and away from the light). Both
// are factors of one 2 × 2 Jacobian on the receiver's tangent plane,
//
//     d(pixel)/d(texel) = d(pixel)/d(surface) · (d(texel)/d(surface))⁻¹,
//
// and the figure `shadowkit eval` measures at every pixel (docs/references.md, evaluation §3)
// is its largest singular value. Here both factors are exact derivatives of the camera's and
// the map's projections at the sample's point and normal, so a prediction differs from eval's
// measurement only in which points it looks at: a few thousand from a low-resolution
// read-back of depth and normals (receiverSamples) rather than every pixel.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <glm/mat2x2.hpp>

#include <span>
#include <vector>

namespace shadowkit::core {

/// Pixels one texel covers along its worst direction: the largest singular value of
/// d(pixel)/d(texel), from its inverse d(texel)/d(pixel) (columns: image x and y). Infinite
/// where a pixel's footprint in the map collapses to a line (a surface edge-on to the light).
double pixelsPerTexel(const glm::dmat2& texelFromPixel);

/// The q-quantile of `values` as eval reports it (the element at index ⌊q·n⌋, clamped);
/// reorders `values`; 0 for none.
double percentileInPlace(std::span<double> values, double q);

/// A visible receiver: a surface point the camera sees, with its unit normal.
struct ReceiverSample {
    Vec3 wsPosition{0.0};         ///< the surface point
    Vec3 wsNormal{0.0, 1.0, 0.0}; ///< its unit normal
};

/// Up to `maxSamples` receivers from a read-back of what the camera sees (RasterBuffers'
/// viewDepth and wsNormal, at any resolution, the camera's aspect): the pixels with a surface
/// facing the light (core::facesLight: the only ones eval scores), spread evenly over them in
/// image order. Deterministic.
std::vector<ReceiverSample> receiverSamples(const RasterBuffers& raster, const PerspectiveCamera& camera,
                                            const DirectionalLight& light, size_t maxSamples);

/// Predicted pixels per texel over the receiver samples: p50, p95, the undersampled fraction.
struct SamplingFigures {
    size_t samples = 0;                ///< receivers the figures are over
    double p50 = 0.0;                  ///< median pixels per texel
    double p95 = 0.0;                  ///< 95th percentile
    double p99 = 0.0;                  ///< 99th percentile
    double undersampledFraction = 0.0; ///< share above 1 pixel per texel, [0, 1]
};

/// What the parameter search minimises (error_driven.h): p95 pixels per texel, plus the
/// undersampled fraction as a tie-breaker worth at most one pixel per texel. The p95 is the
/// worst error most of the screen sees — the median hides the near field, where aliasing
/// shows, and the maximum belongs to a few receivers edge-on to the light that no parameter
/// helps; between set-ups of nearly equal p95 the one with more pixel-accurate receivers wins.
double samplingObjective(const SamplingFigures& figures);

/// The camera as it renders width × height pixels and a sample of the receivers it sees. The
/// per-sample screen Jacobians are computed once here; each prediction then costs one
/// projection derivative and a 2 × 2 singular value per sample.
class SamplingErrorModel {
public:
    /// Fails for an invalid camera or image size. Samples seen edge-on (no screen footprint)
    /// or behind the eye are dropped.
    static Result<SamplingErrorModel> create(const PerspectiveCamera& camera, int width, int height,
                                             std::span<const ReceiverSample> samples);

    size_t size() const { return m_samples.size(); }             ///< samples kept
    const PerspectiveCamera& camera() const { return m_camera; } ///< the camera it models
    /// [nearest, farthest] view depth of the samples; nullopt without samples.
    std::optional<Vec2> viewDepthRange() const;

    /// Per sample, pixels per texel in the map of `setup` that serves it: a cascade by view
    /// depth as the shader picks it (skCascadeOf), else the only map. `out` has size().
    void predict(const ShadowSetup& setup, std::span<double> out) const;
    /// The figures over every sample. Uses an internal buffer: one thread per model.
    SamplingFigures figures(const ShadowSetup& setup) const;
    /// samplingObjective(figures(setup)), exactly, for a third of the cost: the search needs
    /// only the p95 and the undersampled share, not the other two quantiles.
    double objective(const ShadowSetup& setup) const;

    /// The same camera with at most `maxSamples` of these samples, spread evenly over them in
    /// their order (every k-th): a cheaper model for a search that runs every frame.
    SamplingErrorModel subsampled(size_t maxSamples) const;

private:
    struct Sample {
        Vec3 esPosition;             ///< relative to the camera's eye
        double viewDepth;            ///< along the unit view direction
        Vec3 tangentU, tangentV;     ///< orthonormal basis of the receiver's plane
        glm::dmat2 tangentFromPixel; ///< d(u, v)/d(pixel x, y)
    };
    /// Predicts every sample into m_scratch; returns the share above 1 pixel per texel.
    double predictUndersampled(const ShadowSetup& setup) const;

    PerspectiveCamera m_camera;
    std::vector<Sample> m_samples;
    mutable std::vector<double> m_scratch;
};

} // namespace shadowkit::core
