// A local light's reach from its attenuation (light_reach.h): checked against the lighting
// equation itself, found by bisection, and on the degenerate fall-offs.
#include "shadowkit/core/light_reach.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace shadowkit::core;

namespace {
// What the fixed-function pipeline lights a white surface facing the light with at distance d.
double lit(const Attenuation& a, double intensity, double d) {
    return intensity / (a.constant + a.linear * d + a.quadratic * d * d);
}
// The distance where lit() falls to `cutoff`, by bisection on the lighting equation (no root formula).
double bisectedReach(const Attenuation& a, double intensity, double cutoff) {
    double lo = 0.0, hi = 1.0;
    while (lit(a, intensity, hi) >= cutoff) hi *= 2.0;
    for (int i = 0; i < 200; ++i) (lit(a, intensity, 0.5 * (lo + hi)) >= cutoff ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}
} // namespace

TEST(LightReach, TheLightFallsToTheCutoffExactlyAtItsReach) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 500; ++trial) {
        // Coefficients over many orders of magnitude, a term or two sometimes 0.
        const auto term = [&](double scale) {
            return unit(rng) < 0.2 ? 0.0 : scale * std::pow(10.0, 6.0 * unit(rng) - 3.0);
        };
        Attenuation a{
            .constant = unit(rng) < 0.1 ? 0.0 : 0.2 + 2.0 * unit(rng), .linear = term(0.1), .quadratic = term(0.01)};
        if (a.linear == 0.0 && a.quadratic == 0.0) a.quadratic = 0.01;
        const double intensity = 0.1 + 3.0 * unit(rng), cutoff = std::pow(10.0, -4.0 * unit(rng) - 0.5);
        const double reach = attenuationReach(a, intensity, cutoff).value();
        if (intensity / cutoff <= a.constant) {
            EXPECT_EQ(reach, 0.0);
            continue;
        }
        const double expected = bisectedReach(a, intensity, cutoff);
        ASSERT_NEAR(reach, expected, 1e-9 * expected) << a.constant << " " << a.linear << " " << a.quadratic;
        EXPECT_GE(lit(a, intensity, reach * (1.0 - 1e-9)), cutoff);
        EXPECT_LT(lit(a, intensity, reach * (1.0 + 1e-9)), cutoff);
        // A dimmer cutoff reaches farther.
        EXPECT_GT(attenuationReach(a, intensity, 0.5 * cutoff).value(), reach);
    }
}

TEST(LightReach, DegenerateFallOffs) {
    // No fall-off: the light reaches everything.
    EXPECT_EQ(attenuationReach({}, 1.0).value(), std::numeric_limits<double>::infinity());
    EXPECT_EQ(attenuationReach({.constant = 0.5}, 1.0).value(), std::numeric_limits<double>::infinity());
    // A light that never shows: no colour, or a constant term dimming it below the cutoff.
    EXPECT_EQ(attenuationReach({.quadratic = 1.0}, 0.0).value(), 0.0);
    EXPECT_EQ(attenuationReach({.constant = 300.0, .quadratic = 1.0}, 1.0).value(), 0.0);
    // Linear alone: I / (kc + kl·d) = cutoff at d = (I / cutoff − kc) / kl.
    EXPECT_DOUBLE_EQ(attenuationReach({.constant = 1.0, .linear = 0.5}, 1.0, 0.01).value(), 99.0 / 0.5);
    // Quadratic alone: d = √((I / cutoff − kc) / kq) — and a tiny quadratic beside a large linear
    // term keeps its digits (the textbook root would cancel).
    EXPECT_DOUBLE_EQ(attenuationReach({.constant = 0.0, .quadratic = 4.0}, 1.0, 0.01).value(), 5.0);
    const Attenuation nearlyLinear{.constant = 1.0, .linear = 1.0, .quadratic = 1e-14};
    EXPECT_NEAR(attenuationReach(nearlyLinear, 1.0, 0.01).value(), bisectedReach(nearlyLinear, 1.0, 0.01), 1e-9);
    // Terms whose products overflow a double keep the root (d² + d − 2 = 0 scaled by 1e200: d = 1;
    // without the linear term d = √2), not 0 from m / ∞ or NaN from ∞ / ∞; a light brighter than a
    // double can say reaches everything.
    EXPECT_DOUBLE_EQ(attenuationReach({.linear = 1e200, .quadratic = 1e200}, 1e200, 0.5).value(), 1.0);
    EXPECT_DOUBLE_EQ(attenuationReach({.quadratic = 1e200}, 1e200, 0.5).value(), std::sqrt(2.0));
    EXPECT_NEAR(attenuationReach({.linear = 1e200, .quadratic = 1e200}, 1e200, 0.5).value(),
                bisectedReach({.linear = 1e200, .quadratic = 1e200}, 1e200, 0.5), 1e-12);
    EXPECT_EQ(attenuationReach({.quadratic = 1.0}, 1e300, 1e-10).value(), std::numeric_limits<double>::infinity());
    EXPECT_EQ(attenuationReach({.linear = 1e-200}, 1e300, 0.5).value(), std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(attenuationReach({.linear = 1e200}, 1e200, 0.5).value(), 2.0);
}

TEST(LightReach, ARangeBecomesAnAttenuationThatReachesIt) {
    for (const double range : {0.5, 30.0, 2000.0})
        for (const double intensity : {0.8, 1.0, 5.0}) {
            const Attenuation a = quadraticAttenuationReaching(range, intensity);
            EXPECT_EQ(a.constant, 1.0);
            EXPECT_EQ(a.linear, 0.0);
            EXPECT_NEAR(bisectedReach(a, intensity, kDefaultReachCutoff), range, 1e-9 * range);
            EXPECT_NEAR(attenuationReach(a, intensity).value(), range, 1e-9 * range);
        }
}

TEST(LightReach, BadInputNamesItsField) {
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    const auto field = [](const Result<double>& r) { return r ? std::string("(none)") : r.errorInfo().field; };
    for (const double bad : {-1e-9, nan, inf}) {
        EXPECT_EQ(field(attenuationReach({.constant = bad}, 1.0)), "attenuation.constant") << bad;
        EXPECT_EQ(field(attenuationReach({.linear = bad}, 1.0)), "attenuation.linear") << bad;
        EXPECT_EQ(field(attenuationReach({.quadratic = bad}, 1.0)), "attenuation.quadratic") << bad;
        EXPECT_EQ(field(attenuationReach({}, bad)), "light.intensity") << bad;
    }
    EXPECT_EQ(field(attenuationReach({.constant = 0.0}, 1.0)), "attenuation.constant");
    for (const double bad : {0.0, 1.0, -0.1, nan, inf}) {
        EXPECT_EQ(field(attenuationReach({}, 1.0, bad)), "reach.cutoff") << bad;
        EXPECT_FALSE(validateReachCutoff(bad));
    }
    EXPECT_TRUE(validateReachCutoff(kDefaultReachCutoff));
}
