// Pictures of a comparison: the error map, the aliasing heat map, and the same pixels shaded
// by the sun under the ray-traced and the rendered visibility, to be set side by side.
#pragma once

#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/eval/truth.h"
#include "shadowkit/scene/image.h"

#include <span>

namespace shadowkit::eval {

// Colours of the error map (docs/evaluation.md, "Error and aliasing maps").
struct ErrorMapColors {
    static constexpr uint8_t notEvaluated[3] = {24, 24, 28};
    static constexpr uint8_t litCorrect[3] = {205, 205, 205};
    static constexpr uint8_t shadowCorrect[3] = {105, 105, 105};
    static constexpr uint8_t falseShadow[3] = {230, 50, 30}; // red
    static constexpr uint8_t falseLit[3] = {40, 120, 255};   // blue
    static constexpr uint8_t excluded[3] = {250, 205, 40};   // yellow
};

scene::Image errorMapImage(const Comparison& comparison, int width, int height);

// Pixels per texel on a log2 scale from 1/64 (left of the bar) to 64 (right), with a
// colour bar and labels under the image; 1 pixel per texel is the white tick. Pixels
// that are not valid are black.
scene::Image aliasingMapImage(const Comparison& comparison, int width, int height);

// The signed error against a soft truth (eval --sun-angle --error-map): rendered − true
// visibility per valid pixel, red where the rendered shadow is too dark (−1: shadow where the
// sun is wholly seen), light grey where it is right, blue where too light (+1), in the error
// map's false-shadow and false-lit colours; pixels not compared keep its not-evaluated colour.
scene::Image softErrorMapImage(std::span<const float> shadowTerm, const SoftTruth& soft, const Comparison& comparison);

// The truth's surfaces in grey, lit by the sun alone: ambient + (1 − ambient) · N·L · v, with
// v the visibility — `truth.lit` for the ray-traced picture, the rendered shadow term
// (`raster.shadowTerm`, filtered as drawn) for the rendered one. Both use the truth's
// surfaces and normals, so the two pictures differ exactly where the shadows do. The sky is
// flat blue; a pixel with no rendered surface in the rendered picture is magenta.
scene::Image truthShadowImage(const TruthBuffers& truth, const core::DirectionalLight& light);
scene::Image renderedShadowImage(const TruthBuffers& truth, const core::RasterBuffers& raster,
                                 const core::DirectionalLight& light);
// The same picture under the sun's disk: v the visible fraction of the disk (`soft`, computed on
// `truth`'s surfaces), so penumbrae and the partial light under leaves show as greys.
scene::Image softTruthShadowImage(const TruthBuffers& truth, const SoftTruth& soft,
                                  const core::DirectionalLight& light);

} // namespace shadowkit::eval
