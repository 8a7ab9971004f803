// Split distances for cascaded shadow maps.
//
// Based on: Dimitrov, "Cascaded Shadow Maps", NVIDIA 2007, the practical split
// scheme of Zhang et al., "Parallel-Split Shadow Maps", 2006: a blend of the logarithmic
// scheme (ideal for perspective aliasing, Wimmer et al. 2004 §4.2) and the uniform one (which keeps
// the first split from being uselessly thin).
// The end points are set exactly (not from the formula) so the first split starts at the
// near plane and the last ends at the far plane to the bit; the formula's own rounding
// would leave a sliver uncovered (docs/references.md, pitfall 7).
#include "shadowkit/core/cascade_splits.h"

#include "shadowkit/core/conventions.h"

#include <cmath>

namespace shadowkit::core {

SplitDistances practicalSplits(double zNear, double zFar, int count, double lambda) {
    SK_ASSERT(zNear > 0.0 && zFar > zNear && count >= 1 && lambda >= 0.0 && lambda <= 1.0,
              "practicalSplits(): needs 0 < near < far, count >= 1, lambda in [0, 1]");
    SplitDistances z;
    for (int i = 0; i <= count; ++i) {
        const double s = double(i) / count;
        const double logarithmic = zNear * std::pow(zFar / zNear, s);
        const double uniform = zNear + s * (zFar - zNear);
        z.push_back(lambda * logarithmic + (1.0 - lambda) * uniform);
    }
    z.front() = zNear;
    z.back() = zFar;
    return z;
}

} // namespace shadowkit::core
