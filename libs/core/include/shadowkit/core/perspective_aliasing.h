// Perspective aliasing dp/ds of a shadow-map parameterization along view depth, for the
// ideal case of a view direction perpendicular to the light (seed 001 §4.3, eq. 3).
#pragma once

#include <limits>
#include <vector>

namespace shadowkit::core {

// dp/ds = (z − z_n + n)² / z · (z_f − z_n) / (n (n + z_f − z_n)),  z in [z_n, z_f].
// n is the distance of LiSPSM's projection centre from the near plane of P:
//   n → ∞ gives uniform shadow maps, (z_f − z_n)/z; n = z_n gives PSM, z (z_f − z_n)/(z_n z_f).
// Pass n = infinity for the uniform limit (evaluated in closed form, no overflow).
double perspectiveAliasing(double z, double zNear, double zFar, double n);

// The n that makes dp/ds equal at z_n and z_f, minimising its maximum (seed 001 §4.3):
// n_opt = z_n + √(z_n z_f).
double lispsmOptimalN(double zNear, double zFar);

struct AliasingCurve {
    std::vector<double> z, dpds; // samples, z ascending
    double max = 0.0;            // max dp/ds over [z_n, z_f]
    double argmaxZ = 0.0;        // where it is reached (the lower z on a tie)
};

// `samples` points spaced logarithmically over [z_n, z_f] (both ends included); the
// maximum is taken from the closed form at the ends, where the convex curve peaks.
AliasingCurve sampleAliasing(double zNear, double zFar, double n, int samples = 200);

inline constexpr double kUniformN = std::numeric_limits<double>::infinity();

} // namespace shadowkit::core
