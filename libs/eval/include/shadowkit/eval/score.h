// Scoring any renderer's shadows against the ray-traced truth (`shadowkit score`): a shadow
// mask another engine drew — per pixel the sun's visibility, 1 lit … 0 shadowed — from a camera
// whose truth shadowkit computes for a scene it can load. The mask takes the place of the
// rasterised shadow term in the same comparison `eval` makes (metrics.h), on the truth's own
// surfaces, so the figures are eval's: wrong_pct, false shadow and false lit, and against a
// soft truth soft_mae and the rest (soft_truth.h); pixels-per-texel figures need the engine's
// shadow map and are not given.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/truth.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace shadowkit::eval {

struct ShadowMask {
    int width = 0, height = 0;
    std::vector<float> visibility; // row-major, top row first: 1 lit … 0 shadowed
    // Where the engine drew a surface (the PNG's alpha above one half), or empty when the mask
    // does not say: then every pixel counts as drawn.
    std::vector<uint8_t> drawn;
};

// A mask from a PNG (8 or 16 bits; grey or the red channel; alpha, if any, marks what was
// drawn) or a .npy array (float32 or float64 visibility, uint8 or uint16 scaled to [0, 1]).
// Errors of one line name the file; a value outside [0, 1] or NaN is refused.
core::Result<ShadowMask> loadShadowMask(const std::filesystem::path& file);

struct ScoreOptions {
    CompareOptions compare;
    // At most this fraction of the pixels may disagree with the truth on whether a surface is
    // there (a mask with alpha): more means another camera or scene, and the mask is refused.
    double maxDrawnMismatch = 0.02;
};

// The mask against the truth of its camera, as eval::compare would class a rasterised term:
// a pixel is valid where the truth's surface faces the light (and the mask drew one), excluded
// where the mask drew nothing on a surface or something on the sky. Fails in one line for a
// mask of another size than the truth or whose drawn pixels disagree with the truth's
// surfaces on more than options.maxDrawnMismatch of the image.
core::Result<Comparison> scoreMask(const ShadowMask& mask, const TruthBuffers& truth, const ScoreOptions& options = {});

} // namespace shadowkit::eval
