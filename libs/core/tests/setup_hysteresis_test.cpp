// Set-up hysteresis: the enclosing camera holds every camera within reach; a kept set-up is
// bit for bit the same and still covers the real camera's focus; a refit when the eye or
// the view leaves its reach, or the light moves.
#include "shadowkit/core/setup_hysteresis.h"

#include <gtest/gtest.h>

#include <random>

using namespace shadowkit::core;

namespace {

PerspectiveCamera groundCamera() {
    PerspectiveCamera c;
    c.wsEye = {0.0, 1.8, 0.0};
    c.wsDirection = {0.3, -0.05, -1.0};
    c.fovYDegrees = 60.0;
    c.aspect = 16.0 / 9.0;
    c.zNear = 0.5;
    c.zFar = 300.0;
    return c;
}

Vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return glm::normalize(Vec3(g(rng), g(rng), g(rng)));
}

// A camera within reach: eye moved by up to r, direction turned by up to α.
PerspectiveCamera nearby(const PerspectiveCamera& c, const HysteresisOptions& o, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    PerspectiveCamera out = c;
    out.wsEye += randomUnit(rng) * (o.radiusMetres * u(rng));
    const Vec3 d = glm::normalize(c.wsDirection);
    const Vec3 axis = glm::normalize(glm::cross(d, randomUnit(rng)));
    const double angle = glm::radians(o.turnDegrees) * u(rng);
    out.wsDirection = d * std::cos(angle) + glm::cross(axis, d) * std::sin(angle); // Rodrigues, axis ⟂ d
    return out;
}

ShadowSetupInputs inputs(const PerspectiveCamera& c, Technique t) {
    return {.camera = c,
            .light = DirectionalLight::fromSunAngles(35.0, 110.0).value(),
            .wsSceneBounds = Aabb::fromMinMax(Vec3(-500, -10, -500), Vec3(500, 40, 500)),
            .technique = t,
            .mapSize = 1024};
}

} // namespace

TEST(SetupHysteresis, TheEnclosingCameraHoldsEveryCameraWithinReach) {
    std::mt19937 rng(7);
    const HysteresisOptions o{.radiusMetres = 3.0, .turnDegrees = 6.0};
    const PerspectiveCamera c = groundCamera();
    const PerspectiveCamera big = enclosingCamera(c, o);
    ASSERT_TRUE(big.validate());
    const auto planes = big.wsFrustumPlanes();
    for (int k = 0; k < 500; ++k) {
        const PerspectiveCamera other = nearby(c, o, rng);
        for (const Vec3& corner : other.wsFrustumCorners())
            for (const Plane& p : planes) ASSERT_LE(p.signedDistance(corner), 1e-6 * c.zFar) << "camera " << k;
    }
}

TEST(SetupHysteresis, AKeptSetupIsTheSameAndStillCoversTheFocusOfTheRealCamera) {
    std::mt19937 rng(11);
    const HysteresisOptions o{.radiusMetres = 4.0, .turnDegrees = 5.0};
    for (const Technique t : {Technique::Lispsm, Technique::Tsm, Technique::Focused}) {
        SetupHysteresis hysteresis(o);
        const PerspectiveCamera c = groundCamera();
        auto first = hysteresis.next(inputs(c, t));
        ASSERT_TRUE(first);
        EXPECT_TRUE(hysteresis.refitted());
        for (int k = 0; k < 50; ++k) {
            const PerspectiveCamera other = nearby(c, o, rng);
            auto kept = hysteresis.next(inputs(other, t));
            ASSERT_TRUE(kept);
            ASSERT_FALSE(hysteresis.refitted()) << techniqueName(t) << " camera " << k;
            ASSERT_EQ(kept->views[0].clipFromWorld, first->views[0].clipFromWorld);
            // Every point the real camera sees inside the scene lands in the map.
            const auto corners = other.wsFrustumCorners();
            std::uniform_real_distribution<double> u(0.0, 1.0);
            for (int s = 0; s < 200; ++s) {
                const double a = u(rng), b = u(rng), depth = u(rng);
                auto on = [&](int base) {
                    return glm::mix(glm::mix(corners[base], corners[base + 1], a), glm::mix(corners[base + 3], corners[base + 2], a), b);
                };
                const Vec3 p = glm::mix(on(0), on(4), depth);
                if (!inputs(other, t).wsSceneBounds.contains(p)) continue;
                const Vec4 cs = kept->views[0].clipFromWorld * Vec4(p, 1.0);
                ASSERT_GT(cs.w, 0.0);
                EXPECT_LE(std::abs(cs.x / cs.w), 1.0 + 1e-9) << techniqueName(t);
                EXPECT_LE(std::abs(cs.y / cs.w), 1.0 + 1e-9) << techniqueName(t);
            }
        }
    }
}

TEST(SetupHysteresis, RefitsWhenTheEyeOrTheViewLeavesItsReachOrTheLightMoves) {
    const HysteresisOptions o{.radiusMetres = 2.0, .turnDegrees = 5.0};
    SetupHysteresis hysteresis(o);
    PerspectiveCamera c = groundCamera();
    ASSERT_TRUE(hysteresis.next(inputs(c, Technique::Lispsm)));
    c.wsEye.x += 2.5;
    ASSERT_TRUE(hysteresis.next(inputs(c, Technique::Lispsm)));
    EXPECT_TRUE(hysteresis.refitted());
    ASSERT_TRUE(hysteresis.next(inputs(c, Technique::Lispsm)));
    EXPECT_FALSE(hysteresis.refitted());
    c.wsDirection = Vec3(0.5, -0.05, -1.0); // about 10° round
    ASSERT_TRUE(hysteresis.next(inputs(c, Technique::Lispsm)));
    EXPECT_TRUE(hysteresis.refitted());
    ShadowSetupInputs in = inputs(c, Technique::Lispsm);
    in.light = DirectionalLight::fromSunAngles(35.5, 110.0).value();
    ASSERT_TRUE(hysteresis.next(in));
    EXPECT_TRUE(hysteresis.refitted());
    EXPECT_FALSE(validate(HysteresisOptions{.radiusMetres = 0.0}));
    EXPECT_FALSE(validate(HysteresisOptions{.turnDegrees = 60.0}));
}
