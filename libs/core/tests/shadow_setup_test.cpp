#include "setup_configs.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/shadow_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

using namespace shadowkit::core;
using namespace shadowkit::core::testing;

TEST(ShadowSetupTest, EveryPointOfBLiesInsideTheClipCubeForTenThousandConfigurations) {
    ConfigGenerator gen(20261122);
    int emptyBodies = 0, parallelFallbacks = 0, warped = 0;
    for (int i = 0; i < 10000; ++i) {
        ShadowSetupInputs in = gen.next();
        for (const TechniqueInfo& info : allTechniques()) {
            const Technique t = info.technique;
            if (!holdsFocusBody(t)) continue;
            in.technique = t;
            const Result<ShadowSetup> setup = computeShadowSetup(in);
            ASSERT_TRUE(setup) << "config " << i << ": " << setup.error();
            ASSERT_EQ(setup->views.size(), t == Technique::Csm ? size_t(in.cascades.count) : 1u);
            for (const ShadowView& view : setup->views) {
                ASSERT_TRUE(isFinite(view.clipFromWorld) && isFinite(view.lightFromWorld)) << "config " << i;

                for (const Vec3& p : pointsToHold(in, *setup, view)) {
                    // No point behind a projection centre (w > 0), none outside the clip cube.
                    ASSERT_GT((view.clipFromWorld * Vec4(p, 1.0)).w, 0.0) << info.name << ", config " << i;
                    ASSERT_LE(outsideClipCube(view.clipFromWorld, p), 1e-6) << info.name << ", config " << i;
                }
                warped += t == Technique::Lispsm && view.clipFromWorld[3][3] != 1.0; // perspective, not affine
            }

            if (t == Technique::Focused) {
                emptyBodies += setup->body.isEmpty();
                parallelFallbacks += !setup->fallbacks.empty() && !setup->body.isEmpty();
            }
        }
    }
    // The generator must actually exercise both degenerate paths.
    EXPECT_GT(emptyBodies, 0);
    EXPECT_GT(parallelFallbacks, 0);
    EXPECT_GT(warped, 4000); // LiSPSM set-ups really warp (the others: empty B, near-parallel views)
}

TEST(ShadowSetupTest, FocusBodyContainsTheVisibleSceneAndEverythingBetweenItAndTheLight) {
    ConfigGenerator gen(7);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        const ShadowSetupInputs in = gen.next();
        const ConvexBody body = computeFocusBody(in.camera, in.light, in.wsSceneBounds);
        const Aabb box = sceneBoxForFocus(in.wsSceneBounds);
        const double eps = 1e-7 * (box.diagonal() + glm::length(box.center()) + 1.0);

        for (const Vec3& v : body.vertices())
            ASSERT_TRUE(box.contains(v, eps)) << "B leaves the scene box, config " << i;
        for (int s = 0; s < 50; ++s) {
            const Vec3 receiver = pointInFrustum(in.camera, gen);
            if (!box.contains(receiver)) continue;
            ++checked;
            ASSERT_TRUE(body.contains(receiver, eps)) << "visible point outside B, config " << i;
            // A caster between the receiver and the sun, inside the scene, is in B too.
            const Vec3 caster = receiver + gen.uniform(0, box.diagonal()) * in.light.wsTowardsLight();
            if (box.contains(caster)) {
                ASSERT_TRUE(body.contains(caster, eps)) << "caster outside B, config " << i;
            }
        }
    }
    EXPECT_GT(checked, 5000);
}

TEST(ShadowSetupTest, FocusBodyIsItsDefinitionWithEveryPlaneOfTheSweepApplied) {
    // computeFocusBody sweeps V ∩ S as far as one face of the scene box and cuts it by the
    // other five (ConvexBody::sweptUntil); B built from the definition — the box cut by every
    // plane of the sweep — must have the same vertices.
    ConfigGenerator gen(2026);
    int compared = 0;
    for (int i = 0; i < 2000; ++i) {
        const ShadowSetupInputs in = gen.next();
        const Aabb box = sceneBoxForFocus(in.wsSceneBounds);
        ConvexBody visible = ConvexBody::fromAabb(box);
        visible.clip(in.camera.wsFrustumPlanes());
        ConvexBody byDefinition;
        if (!visible.isEmpty()) {
            byDefinition = ConvexBody::fromAabb(box);
            const ConvexBody::Planes sweep = visible.sweepHalfSpaces(in.light.wsTowardsLight());
            byDefinition.clip(std::span<const Plane>(sweep.data(), sweep.size()));
        }
        const ConvexBody body = computeFocusBody(in.camera, in.light, in.wsSceneBounds);
        ASSERT_EQ(body.isEmpty(), byDefinition.isEmpty()) << "config " << i;
        if (body.isEmpty()) continue;
        ++compared;
        const double eps = 1e-7 * (box.diagonal() + glm::length(box.center()) + 1.0);
        const ConvexBody::Points got = body.vertices(), expected = byDefinition.vertices();
        ASSERT_EQ(got.size(), expected.size()) << "config " << i;
        for (const Vec3& p : expected) {
            double nearest = INFINITY;
            for (const Vec3& q : got) nearest = std::min(nearest, glm::length(q - p));
            ASSERT_LE(nearest, eps) << "config " << i;
        }
    }
    EXPECT_GT(compared, 1000);
}

TEST(ShadowSetupTest, TheRememberedFocusBodyIsReturnedOnlyForExactlyTheSameInputs) {
    // computeFocusBody keeps its last result per thread: a change to any input it depends on
    // must compute B afresh, whatever was computed just before.
    const Aabb box = Aabb::fromMinMax(Vec3(-100, 0, -100), Vec3(100, 20, 100));
    const PerspectiveCamera base{.wsEye = Vec3(0, 5, 40), .wsDirection = Vec3(0.2, -0.3, -1), .zNear = 0.5, .zFar = 80};
    const DirectionalLight sun = *DirectionalLight::fromSunAngles(40, 30);
    using Change = std::function<void(PerspectiveCamera&, DirectionalLight&, Aabb&)>;
    const std::vector<std::pair<const char*, Change>> changes = {
        {"eye", [](auto& c, auto&, auto&) { c.wsEye.x += 3.0; }},
        {"direction", [](auto& c, auto&, auto&) { c.wsDirection.x += 0.3; }},
        {"up", [](auto& c, auto&, auto&) { c.wsUp = Vec3(0.5, 1, 0); }},
        {"fov", [](auto& c, auto&, auto&) { c.fovYDegrees = 40.0; }},
        {"aspect", [](auto& c, auto&, auto&) { c.aspect = 1.0; }},
        {"near", [](auto& c, auto&, auto&) { c.zNear = 5.0; }},
        {"far", [](auto& c, auto&, auto&) { c.zFar = 40.0; }},
        {"light", [](auto&, auto& l, auto&) { l = *DirectionalLight::fromSunAngles(70, 30); }},
        {"bounds", [](auto&, auto&, auto& b) { b.max.y = 10.0; }},
    };
    const double baseVolume = computeFocusBody(base, sun, box).volume();
    for (const auto& [name, change] : changes) {
        PerspectiveCamera camera = base;
        DirectionalLight light = sun;
        Aabb bounds = box;
        change(camera, light, bounds);
        computeFocusBody(camera, light, bounds);
        computeFocusBody(camera, light, Aabb::fromMinMax(Vec3(-1), Vec3(1))); // something else in between
        const double fresh = computeFocusBody(camera, light, bounds).volume();
        ASSERT_GT(std::abs(fresh - baseVolume), 1e-6 * baseVolume)
            << name << " does not change B: the test would not see a stale body";
        computeFocusBody(base, sun, box);
        EXPECT_EQ(computeFocusBody(camera, light, bounds).volume(), fresh) << name << " changed, B was not";
        EXPECT_EQ(computeFocusBody(base, sun, box).volume(), baseVolume) << name;
    }
}

TEST(ShadowSetupTest, FocusedIsTighterThanStandardForAViewInsideALargeScene) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-512, 0, -512), Vec3(512, 30, 512));
    in.camera.wsEye = Vec3(0, 2, 0);
    in.camera.zNear = 0.1;
    in.camera.zFar = 70;
    in.light = *DirectionalLight::fromSunAngles(45, 90);
    in.technique = Technique::Standard;
    const Mat4 standard = computeShadowSetup(in)->views[0].clipFromWorld;
    in.technique = Technique::Focused;
    const Mat4 focused = computeShadowSetup(in)->views[0].clipFromWorld;
    // Texels per metre along world X grows by the ratio of covered widths (≈ 1024 m vs ≈ 140 m).
    EXPECT_GT(std::abs(focused[0][0]) + std::abs(focused[0][1]),
              5.0 * (std::abs(standard[0][0]) + std::abs(standard[0][1])));
}

TEST(ShadowSetupTest, ViewAlongTheLightKeepsAWellDefinedFrame) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-100, 0, -100), Vec3(100, 20, 100));
    in.camera.wsEye = Vec3(0, 50, 0);
    in.camera.wsDirection = Vec3(0, -1, 0);
    in.camera.wsUp = Vec3(0, 0, -1);
    in.technique = Technique::Focused;
    for (const Vec3 l : {Vec3(0, -1, 0), Vec3(0, 1, 0)}) {
        in.light = DirectionalLight{l};
        const Result<ShadowSetup> setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        EXPECT_TRUE(isFinite(setup->views[0].clipFromWorld));
        ASSERT_EQ(setup->fallbacks.size(), 1u);
        EXPECT_NE(setup->fallbacks[0].find("parallel"), std::string::npos);
    }
}

TEST(ShadowSetupTest, ViewMissingTheSceneFallsBackToTheSceneBox) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-10, 0, -10), Vec3(10, 5, 10));
    in.camera.wsEye = Vec3(0, 100, 0);
    in.camera.wsDirection = Vec3(0, 1, 0); // looking at the sky
    in.camera.wsUp = Vec3(0, 0, -1);
    in.light = *DirectionalLight::fromSunAngles(60, 10);
    const Result<ShadowSetup> setup = computeShadowSetup(in);
    ASSERT_TRUE(setup);
    EXPECT_TRUE(setup->body.isEmpty());
    ASSERT_EQ(setup->fallbacks.size(), 1u);
    for (const Vec3& c : in.wsSceneBounds.corners()) EXPECT_LE(outsideClipCube(setup->views[0].clipFromWorld, c), 1e-9);
}

TEST(ShadowSetupTest, BadInputsAreErrorsNotNaN) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(0), Vec3(1));
    in.camera.zNear = 10;
    in.camera.zFar = 1;
    EXPECT_FALSE(computeShadowSetup(in));
    in.camera.zFar = 100;
    in.wsSceneBounds = Aabb{};
    const auto r = computeShadowSetup(in);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.errorInfo().field, "scene_bounds");
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(0), Vec3(1));
    in.light.wsDirection = Vec3(NAN, 0, 0);
    EXPECT_FALSE(computeShadowSetup(in));
}

TEST(ShadowSetupTest, TechniqueNamesRoundTrip) {
    for (const TechniqueInfo& info : allTechniques()) EXPECT_EQ(parseTechnique(info.name), info.technique);
    EXPECT_FALSE(parseTechnique("lispsm-typo"));
}
