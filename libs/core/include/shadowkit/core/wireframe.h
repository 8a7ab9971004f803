// Edges to draw for insight (the viewer's wireframes): a projection's clip volume — a view
// frustum, a shadow map's volume, warped or not — and a convex body such as the focus body B.
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/convex_body.h"

#include <utility>
#include <vector>

namespace shadowkit::core {

using Edge = std::pair<Vec3, Vec3>;

/// The 12 edges of the clip volume of `clipFromWorld` (x, y in [−1, 1], depth in [0, 1]),
/// mapped back to the world through its inverse; empty when the matrix is singular or a
/// corner lies at infinity (w = 0: an infinite far plane).
std::vector<Edge> clipVolumeEdges(const Mat4& clipFromWorld);

/// Every face's boundary of the body, each shared edge once.
std::vector<Edge> bodyEdges(const ConvexBody& body);

} // namespace shadowkit::core
