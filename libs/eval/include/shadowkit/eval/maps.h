// Pictures of a comparison: the error map and the aliasing heat map.
#pragma once

#include "shadowkit/eval/metrics.h"
#include "shadowkit/scene/image.h"

namespace shadowkit::eval {

// Colours of the error map (README, "Error maps").
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

} // namespace shadowkit::eval
