// The view-depth range of what is actually visible, for LiSPSM's n (Scherzer 2005 §4.4: Δz
// "from the visibility algorithm"): a min/max reduction over a frame's view depths.
#pragma once

#include "shadowkit/core/conventions.h"

#include <optional>
#include <span>

namespace shadowkit::core {

/// [nearest, farthest] of the positive, finite depths (0 marks a pixel where nothing was
/// drawn); nullopt when there is none. Feed it to LispsmOptions::visibleDepth: it narrows
/// n only, never the focus body B.
std::optional<Vec2> visibleDepthRange(std::span<const float> viewDepth);

} // namespace shadowkit::core
