// A local light's reach from its fixed-function attenuation (light_reach.h).
#include "shadowkit/core/light_reach.h"

#include <cmath>
#include <limits>
#include <string>

namespace shadowkit::core {

namespace {
Status checkCoefficient(double value, const char* name) {
    if (std::isfinite(value) && value >= 0.0) return Ok{};
    return fieldError("attenuation." + std::string(name),
                      "must be finite and at least 0 (OpenGL refuses negative ones)");
}
} // namespace

Status validateReachCutoff(double cutoff) {
    if (std::isfinite(cutoff) && cutoff > 0.0 && cutoff < 1.0) return Ok{};
    return fieldError("reach.cutoff",
                      "must be in (0, 1): the fraction of full white below which a light no longer reaches");
}

Result<double> attenuationReach(const Attenuation& attenuation, double intensity, double cutoff) {
    if (auto ok = checkCoefficient(attenuation.constant, "constant"); !ok) return ok.errorInfo();
    if (auto ok = checkCoefficient(attenuation.linear, "linear"); !ok) return ok.errorInfo();
    if (auto ok = checkCoefficient(attenuation.quadratic, "quadratic"); !ok) return ok.errorInfo();
    if (!(std::isfinite(intensity) && intensity >= 0.0))
        return fieldError("light.intensity", "must be finite and at least 0 (the colour's brightest channel)");
    if (auto ok = validateReachCutoff(cutoff); !ok) return ok.errorInfo();
    const double kc = attenuation.constant, kl = attenuation.linear, kq = attenuation.quadratic;
    if (kc == 0.0 && kl == 0.0 && kq == 0.0)
        return fieldError("attenuation.constant",
                          "all three terms 0 divide the light by zero; the constant is usually 1");
    // kq·d² + kl·d − m = 0 with m = I / cutoff − kc: the light shows while the left side is ≤ 0.
    const double m = intensity / cutoff - kc;
    if (!(m > 0.0)) return 0.0; // dimmer than the cutoff already at the light
    if (kl == 0.0 && kq == 0.0) return std::numeric_limits<double>::infinity();
    if (!std::isfinite(m)) return std::numeric_limits<double>::infinity(); // brighter than a double says
    if (kq == 0.0) return m / kl;                                          // linear alone (∞ past a double's range)
    // The positive root as 2m / (kl + √(kl² + 4·kq·m)): no cancellation when kq·m ≪ kl². Where
    // kl² or kq·m overflows (terms near 1e154) that reads 0 (m / ∞): then the same root in
    // square-root scale, √(m / kq) · 2 / (t + √(t² + 4)) with t = kl / √(kq·m), whose factors stay finite.
    const double root = 2.0 * m / (kl + std::sqrt(kl * kl + 4.0 * kq * m));
    if (root > 0.0) return root;
    const double t = kl / (std::sqrt(kq) * std::sqrt(m));
    return std::sqrt(m) / std::sqrt(kq) * 2.0 / (t + std::sqrt(t * t + 4.0));
}

Attenuation quadraticAttenuationReaching(double range, double intensity, double cutoff) {
    // 1 + kq·range² = I / cutoff.
    return {.constant = 1.0, .linear = 0.0, .quadratic = (intensity / cutoff - 1.0) / (range * range)};
}

} // namespace shadowkit::core
