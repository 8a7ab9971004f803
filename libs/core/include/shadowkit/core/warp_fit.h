// Fitting a (possibly projective) light-space transform to the clip cube.
#pragma once

#include "shadowkit/core/conventions.h"

#include <span>

namespace shadowkit::core {

/// Returns Fit · preClipFromLight, where Fit scales and offsets clip coordinates so that the
/// points' NDC bounds become x, y in [-1, 1] and depth in [0, 1]. Fit acts on homogeneous
/// clip coordinates (x' = s·x + o·w), so it is exact under the perspective divide.
/// Precondition: every point has w > 0 (lies in front of the projection centre).
Mat4 fitToClipCube(const Mat4& preClipFromLight, std::span<const Vec3> lsPoints);

} // namespace shadowkit::core
