// Perspective aliasing of uniform, perspective and light space perspective shadow maps.
//
// Based on: Wimmer, Scherzer, Purgathofer, "Light Space Perspective Shadow Maps",
// EGSR 2004, §4.3, equation (3), and Figure 6 (z_n = 1, z_f = 100).
#include "shadowkit/core/perspective_aliasing.h"

#include "shadowkit/core/conventions.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {

double perspectiveAliasing(double z, double zNear, double zFar, double n) {
    const double depth = zFar - zNear;
    if (std::isinf(n)) return depth / z; // lim n→∞ of (z − z_n + n)² / (n (n + depth)) = 1
    const double zp = z - zNear + n;     // z' in the paper: distance from the projection centre
    return zp * zp / z * depth / (n * (n + depth));
}

double predictedMaxAliasing(double zNear, double zFar, double d, double sinGamma, double n) {
    auto at = [&](double z) {
        if (std::isinf(n)) return d / (z * sinGamma);
        const double zp = (z - zNear) * sinGamma + n;
        return zp * zp * d / (z * n * (n + d) * sinGamma);
    };
    return std::max(at(zNear), at(zFar));
}

double lispsmOptimalN(double zNear, double zFar) { return zNear + std::sqrt(zNear * zFar); }

AliasingCurve sampleAliasing(double zNear, double zFar, double n, int samples) {
    SK_ASSERT(zNear > 0.0 && zFar > zNear && samples >= 2, "sampleAliasing(): needs 0 < zNear < zFar and 2+ samples");
    AliasingCurve c;
    for (int i = 0; i < samples; ++i) {
        const double z = i == samples - 1 ? zFar : zNear * std::pow(zFar / zNear, double(i) / (samples - 1));
        c.z.push_back(z);
        c.dpds.push_back(perspectiveAliasing(z, zNear, zFar, n));
    }
    // The curve (z − z_n + n)²/z is convex in z: its maximum is at an end point.
    const double atNear = perspectiveAliasing(zNear, zNear, zFar, n), atFar = perspectiveAliasing(zFar, zNear, zFar, n);
    // Equal within rounding (n = n_opt) counts as a tie: report the near end.
    const bool nearWins = atNear >= atFar * (1.0 - 1e-12);
    c.max = nearWins ? atNear : atFar;
    c.argmaxZ = nearWins ? zNear : zFar;
    return c;
}

} // namespace shadowkit::core
