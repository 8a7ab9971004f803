// Perspective aliasing dp/ds of a shadow-map parameterization along view depth, for the
// ideal case of a view direction perpendicular to the light (Wimmer et al. 2004 §4.3, eq. 3).
#pragma once

#include <limits>
#include <vector>

namespace shadowkit::core {

/// dp/ds = (z − z_n + n)² / z · (z_f − z_n) / (n (n + z_f − z_n)),  z in [z_n, z_f].
/// n is the distance of LiSPSM's projection centre from the near plane of P:
///   n → ∞ gives uniform shadow maps, (z_f − z_n)/z; n = z_n gives PSM, z (z_f − z_n)/(z_n z_f).
/// Pass n = infinity for the uniform limit (evaluated in closed form, no overflow).
double perspectiveAliasing(double z, double zNear, double zFar, double n);

/// The n that makes dp/ds equal at z_n and z_f, minimising its maximum (Wimmer et al. 2004 §4.3):
/// n_opt = z_n + √(z_n z_f).
double lispsmOptimalN(double zNear, double zFar);

/// A curve of Wimmer et al. 2004's Figure 6: perspective aliasing dp/ds over view depth z.
struct AliasingCurve {
    std::vector<double> z;    ///< sample depths, ascending
    std::vector<double> dpds; ///< dp/ds at each
    double max = 0.0;         ///< max dp/ds over [z_n, z_f]
    double argmaxZ = 0.0;     ///< where it is reached (the lower z on a tie)
};

/// `samples` points spaced logarithmically over [z_n, z_f] (both ends included); the
/// maximum is taken from the closed form at the ends, where the convex curve peaks.
AliasingCurve sampleAliasing(double zNear, double zFar, double n, int samples = 200);

/// The same along the view axis for a view at angle γ to the light (Wimmer et al. 2004 §4.4, Figure 7):
/// a point at view depth z sits u = (z − z_n) sin γ along the warp axis, so
///   dp/ds = (u + n)² d / (z n (n + d) sin γ),   d = extent of B along the warp axis,
/// which is equation (3) at γ = 90° with d = z_f − z_n. The curve is convex in z (a z + b +
/// c / z), so its maximum over [z_n, z_f] is at an end; this returns that maximum.
double predictedMaxAliasing(double zNear, double zFar, double d, double sinGamma, double n);

inline constexpr double kUniformN = std::numeric_limits<double>::infinity();

} // namespace shadowkit::core
