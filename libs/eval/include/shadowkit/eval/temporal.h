// Temporal stability of shadows along a sequence (docs/references.md, the evaluation
// protocol): flicker is a pixel whose rendered lit/shadowed state changes from one frame to
// the next at the same world point while the truth there does not.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/truth.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace shadowkit::eval {

// What a frame leaves for the next one's comparison.
struct ShadowStates {
    core::PerspectiveCamera camera;
    int width = 0, height = 0;
    // Per pixel, top row first: 0 not evaluated (sky, facing away from the light, excluded),
    // else bit 0 rendered lit and bit 1 truth lit, plus 4 to mark the pixel as evaluated.
    std::vector<uint8_t> state;
    std::vector<uint32_t> surfaceId;    // the truth's surface
    std::vector<float> viewDepth;       // the truth's view depth
    std::vector<core::Vec3> wsPosition; // the truth's hit point
};

// A frame's states from its camera, truth and comparison (sizes must agree).
ShadowStates shadowStates(const core::PerspectiveCamera& camera, const TruthBuffers& truth,
                          const Comparison& comparison);

// What the switches between levels of detail changed on screen from the previous frame to this
// one (levelPops, below).
struct LevelPops {
    int64_t drawnPx = 0;     // pixels either drawing covers
    double popPct = 0.0;     // of drawnPx: coverage, surface or shadow changed
    double surfacePct = 0.0; // of drawnPx: coverage or surface changed (the look of what is drawn)
    double shadowPct = 0.0;  // of drawnPx: the same surface, its shadow term across the threshold
};

struct TemporalFigures {
    int64_t comparedPx = 0;
    double flickerPct = 0.0;            // of comparedPx: rendered state changed, truth did not
    double truthChangePct = 0.0;        // of comparedPx: the truth changed (moving sun, movers)
    std::optional<LevelPops> levelPops; // when measured (measure::MeasureOptions::levelPops)
};

// This frame's surface points under the previous frame's shadows: the previous frame's
// set-up, light and casters, drawn and looked up from this frame's camera
// (gl::Renderer::renderEvalBuffers), and the truth there under the previous light and
// casters (litAt). So both frames' states are known at exactly the same world points.
struct PreviousShadowsHere {
    core::RasterBuffers raster;    // this frame's camera, the previous frame's maps
    std::vector<uint8_t> truthLit; // per pixel, at this frame's truth hit points
};

struct TemporalOptions {
    // Relative view-depth agreement: of a point reprojected into the previous camera with the
    // surface seen there, and of the two renderings of this frame's camera.
    double depthTolerance = 0.02;
    double shadowThreshold = 0.5; // as CompareOptions::shadowThreshold
};

// A pixel of `current` is compared when it is evaluated, its truth hit point was in view in
// `previous` (reprojected, one of the four pixels around it shows the same surface at a
// consistent depth), the rendering with the previous casters shows the same surface (no
// mover passed in front), and its surface is not among `reshaped` (global instance indices
// whose mesh changed shape between the frames, Scene::deformations: a point of this frame's
// surface lies off the previous one, inside or outside it, so "the same world point" names
// no point of that surface then — under its previous shape the truth there shades it by its
// own skin). Its rendered state "changed" when the previous maps' term there is on the other
// side of the threshold; the truth likewise. Flicker: rendered changed, truth did not.
// Identical frames give zero; so does a camera moving over still shadows.
TemporalFigures compareFrames(const ShadowStates& previous, const ShadowStates& current,
                              const PreviousShadowsHere& before, const TemporalOptions& options = {},
                              std::span<const uint32_t> reshaped = {});

// Pops between levels of detail: one camera drawn twice, with the levels it chooses itself
// (`ownLevels`) and with those the previous frame's camera chose (`previousLevels`,
// gl::RenderSettings::lodCamera), so that motion, the sun and the casters cancel and only the
// levels' switches between the frames remain. A pixel pops when one drawing covers it and the
// other does not, or they show another instance, or the same one at view depths apart by more than
// options.depthTolerance of the depth (another leaf, a cloud's plane), or — the same surface — its
// shadow term lies on the other side of options.shadowThreshold. A flickering canopy is the first
// kind; a shadow that jumps as its caster changes level, the second.
LevelPops levelPops(const core::RasterBuffers& ownLevels, const core::RasterBuffers& previousLevels,
                    const TemporalOptions& options = {});

} // namespace shadowkit::eval
