// Split distances of cascaded / parallel-split shadow maps.
#pragma once

#include "shadowkit/core/small_vector.h"

namespace shadowkit::core {

using SplitDistances = SmallVector<double, 9>; ///< up to 8 splits without allocating

/// The practical split scheme (Dimitrov 2007, after Zhang et al. 2006):
///   z_i = λ n (f/n)^(i/N) + (1 − λ)(n + (i/N)(f − n)),  i = 0..N,
/// λ = 0: uniform spacing, λ = 1: logarithmic. Returns N + 1 distances, z_0 = n, z_N = f.
/// Preconditions: 0 < n < f, N >= 1, λ in [0, 1].
SplitDistances practicalSplits(double zNear, double zFar, int count, double lambda);

} // namespace shadowkit::core
