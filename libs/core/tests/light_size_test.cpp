// The sun's size (light_size.h): its validation, tan of the angular radius, and PCSS's light
// size in a map's own texels — exact on an orthographic map, and following a warped map's
// footprint, which is what an engine's PCSS with one constant per map gets wrong.
#include "shadowkit/core/light_size.h"

#include "shadowkit/core/output_conventions.h"
#include "shadowkit/core/shadow_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace shadowkit::core;

TEST(LightSize, TheSunsAngleIsCheckedAndItsRadiusIsHalfItsDiameter) {
    EXPECT_TRUE(validateSunAngle(0.0));
    EXPECT_TRUE(validateSunAngle(kRealSunAngleDegrees));
    EXPECT_TRUE(validateSunAngle(kMaxSunAngleDegrees));
    for (const double bad : {-1e-9, 20.000001, std::nan(""), double(INFINITY)}) {
        const Status s = validateSunAngle(bad);
        ASSERT_FALSE(s) << bad;
        EXPECT_EQ(s.errorInfo().field, "sun_angle");
    }
    EXPECT_EQ(tanAngularRadius(0.0), 0.0);
    // The real sun: 0.53° across, a radius of 4.625 mrad (the engine-integration page's figure).
    EXPECT_NEAR(tanAngularRadius(0.53), 0.004625, 1e-6);
    EXPECT_NEAR(tanAngularRadius(20.0), std::tan(10.0 * std::numbers::pi / 180.0), 1e-15);
}

TEST(LightSize, OnAnOrthographicMapThePenumbraIsTheDisksWidthInTexels) {
    // A standard map over a 200 m square under an overhead sun: 2048 texels over 200 m.
    ShadowSetupInputs in;
    in.light = DirectionalLight::fromDirection({0, -1, 0}).value();
    in.wsSceneBounds = Aabb::fromMinMax({-100, 0, -100}, {100, 20, 100});
    in.technique = Technique::Standard;
    in.mapSize = 2048;
    in.camera.wsEye = {0, 10, 0};
    const ShadowSetup setup = computeShadowSetup(in).value();
    const EngineShadowView view = toEngineView(setup.views.front(), setup, {});
    // The texel's size from the map itself: texels per metre along x on the ground, which an
    // overhead sun's plane holds (an orthographic map: the same everywhere).
    const auto texel = [&](const Vec3& q) {
        const Vec4 t = view.textureFromWorld * Vec4(q, 1.0);
        return Vec2(t) / t.w * double(in.mapSize);
    };
    const double metresPerTexel = 1.0 / glm::length(texel({4, 0, -7}) - texel({3, 0, -7}));
    ASSERT_GT(metresPerTexel, 0.05);
    ASSERT_LT(metresPerTexel, 0.2);
    for (const Vec3 p : {Vec3(3, 0, -7), Vec3(-80, 5, 60)}) {
        const double texels = penumbraTexelsPerMetre(view.clipFromWorld, in.mapSize, in.light.wsDirection, 2.0, p);
        // A blocker 10 m up: a penumbra of half-width 10·tan 1°, so many texels, the same anywhere.
        EXPECT_NEAR(10.0 * texels, 10.0 * std::tan(std::numbers::pi / 180.0) / metresPerTexel, 1e-6);
    }
    EXPECT_EQ(penumbraTexelsPerMetre(view.clipFromWorld, in.mapSize, in.light.wsDirection, 0.0, {0, 0, 0}), 0.0);
}

TEST(LightSize, OnAWarpedMapItFollowsTheLocalFootprint) {
    // LiSPSM looking along the ground with the sun from the side: texels are many times denser
    // near the eye than far away, and so, in texels, is the same penumbra.
    ShadowSetupInputs in;
    in.light = DirectionalLight::fromSunAngles(30.0, 90.0).value();
    in.wsSceneBounds = Aabb::fromMinMax({-300, 0, -300}, {300, 20, 300});
    in.technique = Technique::Lispsm;
    in.mapSize = 2048;
    in.camera.wsEye = {0, 1.8, 0};
    in.camera.wsDirection = {0, 0, -1};
    in.camera.zFar = 250;
    const ShadowSetup setup = computeShadowSetup(in).value();
    const EngineShadowView view = toEngineView(setup.views.front(), setup, {});
    const auto texels = [&](const Vec3& p) {
        return penumbraTexelsPerMetre(view.clipFromWorld, in.mapSize, in.light.wsDirection, kRealSunAngleDegrees, p);
    };
    const double nearEye = texels({0, 0, -3}), farAway = texels({0, 0, -200});
    EXPECT_GT(nearEye, 4.0 * farAway) << "a constant per map would be wrong by this ratio";
    // Against the map itself: the disk of radius tan α a metre towards the sun, perpendicular to
    // it, spans an ellipse whose area in texels is π times the result squared (finite differences
    // of textureFromWorld).
    const Vec3 l = in.light.wsTowardsLight();
    const Vec3 e1 = glm::normalize(glm::cross(l, Vec3(0, 1, 0))), e2 = glm::cross(l, e1);
    const double r = tanAngularRadius(kRealSunAngleDegrees);
    for (const Vec3 p : {Vec3(0, 0, -3), Vec3(20, 0, -60), Vec3(0, 0, -200)}) {
        const auto texel = [&](const Vec3& q) {
            const Vec4 t = view.textureFromWorld * Vec4(q, 1.0);
            return Vec2(t) / t.w * double(in.mapSize);
        };
        const Vec2 d1 = texel(p + r * e1) - texel(p), d2 = texel(p + r * e2) - texel(p);
        const double areaRadius = std::sqrt(std::abs(d1.x * d2.y - d1.y * d2.x));
        EXPECT_NEAR(texels(p), areaRadius, 1e-3 * areaRadius) << p.z;
    }
}
