// The hemi-octahedral map (octahedral.h): a bijection between the upper hemisphere and the
// unit square, its landmarks where the construction puts them, and the directions it is handed
// that lie outside its domain.
#include "shadowkit/core/octahedral.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace shadowkit::core;

namespace {
void expectNear(glm::vec2 a, glm::vec2 b, float tolerance, const char* what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
}
} // namespace

TEST(HemiOctahedral, EveryDirectionAboveTheHorizonComesBackFromItsPointAndEveryPointFromItsDirection) {
    std::mt19937 rng(11);
    std::normal_distribution<float> gauss;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        glm::vec3 d(gauss(rng), std::abs(gauss(rng)), gauss(rng));
        d = glm::normalize(d);
        const glm::vec2 uv = hemiOctahedralFromDirection(d * (0.1f + 10.0f * unit(rng))); // any length
        ASSERT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f);
        const glm::vec3 back = directionFromHemiOctahedral(uv);
        EXPECT_GT(glm::dot(back, d), 1.0f - 1e-6f) << d.x << "," << d.y << "," << d.z;

        const glm::vec2 p(unit(rng), unit(rng));
        const glm::vec3 e = directionFromHemiOctahedral(p);
        EXPECT_NEAR(glm::length(e), 1.0f, 1e-6f);
        EXPECT_GE(e.y, 0.0f);
        expectNear(hemiOctahedralFromDirection(e), p, 2e-6f, "square → direction → square");
    }
}

// The construction's landmarks: the zenith in the middle, the four horizon axes at the corners
// (the square is the octahedron's upper half turned by 45°), and every horizontal direction on
// the square's edge.
TEST(HemiOctahedral, TheZenithLiesInTheMiddleAndTheHorizonOnTheEdge) {
    expectNear(hemiOctahedralFromDirection({0, 1, 0}), {0.5f, 0.5f}, 1e-7f, "zenith");
    expectNear(hemiOctahedralFromDirection({1, 0, 0}), {1.0f, 1.0f}, 1e-7f, "+x");
    expectNear(hemiOctahedralFromDirection({-1, 0, 0}), {0.0f, 0.0f}, 1e-7f, "-x");
    expectNear(hemiOctahedralFromDirection({0, 0, 1}), {1.0f, 0.0f}, 1e-7f, "+z");
    expectNear(hemiOctahedralFromDirection({0, 0, -1}), {0.0f, 1.0f}, 1e-7f, "-z");
    for (int k = 0; k < 64; ++k) {
        const float azimuth = 6.2831853f * float(k) / 64.0f;
        const glm::vec2 uv = hemiOctahedralFromDirection({std::cos(azimuth), 0.0f, std::sin(azimuth)});
        const float edge = std::max(std::abs(2.0f * uv.x - 1.0f), std::abs(2.0f * uv.y - 1.0f));
        EXPECT_NEAR(edge, 1.0f, 1e-6f) << "azimuth " << azimuth;
    }
    // and the square's edge reads back as the horizon
    for (const glm::vec2 uv : {glm::vec2(0.0f, 0.3f), glm::vec2(1.0f, 0.8f), glm::vec2(0.25f, 1.0f)})
        EXPECT_NEAR(directionFromHemiOctahedral(uv).y, 0.0f, 1e-7f);
}

// Neighbouring directions land on neighbouring points: a sign slip in one quadrant would tear
// the square along an axis, and a step of θ would move the point by up to a unit. The map
// stretches an arc by at most about 1.14 (measured over 200,000 random directions and steps), so
// a step of θ moves the point by less than 1.5 θ.
TEST(HemiOctahedral, NeighbouringDirectionsLandOnNeighbouringPoints) {
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (int trial = 0; trial < 2000; ++trial) {
        const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), std::abs(gauss(rng)) + 0.01f, gauss(rng)));
        glm::vec3 step = glm::normalize(glm::cross(d, glm::vec3(gauss(rng), gauss(rng), gauss(rng))));
        const float theta = 1e-3f;
        glm::vec3 e = glm::normalize(d + theta * step);
        if (e.y < 0.0f) e = glm::normalize(d - theta * step);
        const float moved = glm::length(hemiOctahedralFromDirection(e) - hemiOctahedralFromDirection(d));
        EXPECT_LT(moved, 1.5f * theta) << d.x << "," << d.y << "," << d.z;
    }
}

// Outside the domain: below the horizon a direction is seen from the horizon in its azimuth;
// straight down, a zero vector and a NaN give a defined point, never a NaN.
TEST(HemiOctahedral, DirectionsBelowTheHorizonZeroOrNotFiniteGiveADefinedPoint) {
    expectNear(hemiOctahedralFromDirection({0.6f, -0.8f, 0.0f}), hemiOctahedralFromDirection({1, 0, 0}), 1e-7f,
               "below the horizon");
    expectNear(hemiOctahedralFromDirection({0.3f, -0.5f, -0.4f}), hemiOctahedralFromDirection({0.3f, 0.0f, -0.4f}),
               1e-6f, "below the horizon, another azimuth");
    expectNear(hemiOctahedralFromDirection({0, -1, 0}), {1.0f, 1.0f}, 0.0f, "straight down");
    expectNear(hemiOctahedralFromDirection({0, 0, 0}), {0.5f, 0.5f}, 0.0f, "zero");
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    expectNear(hemiOctahedralFromDirection({nan, 1, 0}), {0.5f, 0.5f}, 0.0f, "NaN");
    expectNear(hemiOctahedralFromDirection({inf, 1, 0}), {0.5f, 0.5f}, 0.0f, "infinite");
    const glm::vec3 fromNan = directionFromHemiOctahedral({nan, 0.5f});
    EXPECT_NEAR(glm::length(fromNan), 1.0f, 1e-6f);
    const glm::vec3 outside = directionFromHemiOctahedral({-3.0f, 2.0f}); // clamped to (0, 1): -z
    EXPECT_NEAR(outside.z, -1.0f, 1e-6f);
}
