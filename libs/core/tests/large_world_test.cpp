// Large worlds: set-ups far from the world's origin (issue 15). computeShadowSetup works
// relative to the eye; these tests hold it to the matrix contract at 10^5–10^7 m, to
// translation invariance, and check what a GPU's floats make of the eye-relative matrices
// against the world ones.
#include "setup_configs.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/output_conventions.h"
#include "shadowkit/core/setup_hysteresis.h"
#include "shadowkit/core/shadow_setup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace shadowkit::core;
using namespace shadowkit::core::testing;

namespace {

// The configuration that a million random checks found outside the contract (issue 15): a
// 1.6 cm-deep frustum 90 km from the origin of a ±100 km world.
ShadowSetupInputs ninetyKilometresOut(Technique technique) {
    ShadowSetupInputs in;
    in.camera.wsEye = {71016.82, 149.14, -54140.24};
    in.camera.wsDirection = glm::normalize(Vec3(-0.8625, -0.2632, 0.4322));
    in.camera.wsUp = {0, 1, 0};
    in.camera.fovYDegrees = 12.8;
    in.camera.aspect = 1.175;
    in.camera.zNear = 0.00229;
    in.camera.zFar = 0.0158;
    in.light = DirectionalLight{glm::normalize(Vec3(-0.2575, -0.4954, -0.8296))};
    in.wsSceneBounds = Aabb::fromMinMax({-100000, -100, -100000}, {100000, 3000, 100000});
    in.technique = technique;
    return in;
}

// The inputs moved by `offset`, the stabilised lattice with them.
ShadowSetupInputs moved(ShadowSetupInputs in, const Vec3& offset) {
    in.camera.wsEye += offset;
    in.wsSceneBounds = Aabb::fromMinMax(in.wsSceneBounds.min + offset, in.wsSceneBounds.max + offset);
    in.wsGridOrigin += offset;
    return in;
}

Vec3 ndcOf(const Mat4& clipFrom, const Vec3& p) {
    const Vec4 c = clipFrom * Vec4(p, 1.0);
    return Vec3(c) / c.w;
}

// Largest clip-unit difference of a float pipeline's NDC from double's for these points:
// what a GPU given the float matrix and float positions computes.
double floatError(const Mat4& clipFrom, const std::vector<Vec3>& points) {
    const glm::mat4 f(clipFrom);
    double worst = 0.0;
    for (const Vec3& p : points) {
        const glm::vec4 c = f * glm::vec4(glm::vec3(p), 1.0f);
        const Vec3 exact = ndcOf(clipFrom, p);
        const Vec3 gpu = Vec3(glm::vec3(c) / c.w);
        worst = std::max({worst, std::abs(gpu.x - exact.x), std::abs(gpu.y - exact.y)});
    }
    return worst;
}

std::vector<Vec3> minus(std::vector<Vec3> points, const Vec3& origin) {
    for (Vec3& p : points) p -= origin;
    return points;
}

// pointsToHold relative to the eye: the reference bodies computed where double holds a
// millimetre frustum (a split's B clipped from a ±100 km box in world coordinates 90 km out
// is itself off by 0.2 % of the split).
std::vector<Vec3> eyeRelativePointsToHold(const ShadowSetupInputs& in, const ShadowSetup& setup, size_t view) {
    const ShadowSetup centred = rebased(setup, in.camera.wsEye);
    return pointsToHold(moved(in, -in.camera.wsEye), centred, centred.views[view]);
}

} // namespace

TEST(LargeWorldTest, TheIssuesConfigurationNinetyKilometresOutIsContainedByEveryTechnique) {
    for (const TechniqueInfo& info : allTechniques()) {
        if (!holdsFocusBody(info.technique)) continue; // its levels: virtual_clipmap_test.cpp, at 1e6 m too
        const ShadowSetupInputs in = ninetyKilometresOut(info.technique);
        auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << info.name << ": " << setup.error();
        EXPECT_EQ(setup->wsEye, in.camera.wsEye);
        for (size_t v = 0; v < setup->views.size(); ++v) {
            const ShadowView& view = setup->views[v];
            std::vector<Vec3> points = eyeRelativePointsToHold(in, *setup, v);
            ConfigGenerator gen(1);
            if (info.technique != Technique::Csm) // a split holds its own depth range only (in its B)
                for (int i = 0; i < 200; ++i) points.push_back(pointInFrustum(in.camera, gen) - in.camera.wsEye);
            ASSERT_FALSE(points.empty()) << info.name;
            for (const Vec3& p : points) {
                // The contract (1e-6 clip units, 1/160 of a texel of the largest map) in
                // eye-relative coordinates, and in world ones as an engine that does not render
                // camera-relative would use it.
                ASSERT_GT((view.clipFromEyeRelative * Vec4(p, 1.0)).w, 0.0) << info.name;
                EXPECT_LE(outsideClipCube(view.clipFromEyeRelative, p), 1e-6) << info.name;
                EXPECT_LE(outsideClipCube(view.clipFromWorld, p + in.camera.wsEye), 1e-6) << info.name;
            }
        }
    }
}

TEST(LargeWorldTest, SetUpsAreContainedAndTranslationInvariantAtTenToTheFiveSixAndSevenMetres) {
    ConfigGenerator gen(15);
    int checked = 0;
    for (const double distance : {1e5, 1e6, 1e7}) {
        for (int i = 0; i < 150; ++i) {
            ShadowSetupInputs atOrigin = gen.next();
            const Vec3 offset = distance * Vec3(gen.unitVector().x, 0.01 * gen.uniform(-1, 1), gen.unitVector().z);
            for (const TechniqueInfo& info : allTechniques()) {
                atOrigin.technique = info.technique;
                const ShadowSetupInputs far = moved(atOrigin, offset);
                auto near = computeShadowSetup(atOrigin);
                auto there = computeShadowSetup(far);
                ASSERT_TRUE(near && there) << info.name;
                ASSERT_EQ(near->views.size(), there->views.size());
                for (size_t v = 0; v < there->views.size(); ++v) {
                    const ShadowView& view = there->views[v];
                    for (const Vec3& eyeRelative : eyeRelativePointsToHold(far, *there, v)) {
                        ASSERT_GT((view.clipFromEyeRelative * Vec4(eyeRelative, 1.0)).w, 0.0) << info.name;
                        if (holdsFocusBody(info.technique)) { // a clipmap level holds what its rule gives it
                            ASSERT_LE(outsideClipCube(view.clipFromEyeRelative, eyeRelative), 1e-6)
                                << info.name << " at " << distance;
                        }
                        // The same map as at the origin: the points land where they land there.
                        const Vec3 d = ndcOf(view.clipFromEyeRelative, eyeRelative) -
                                       ndcOf(near->views[v].clipFromEyeRelative, eyeRelative);
                        ASSERT_LE(std::max(std::abs(d.x), std::abs(d.y)), 1e-6) << info.name << " at " << distance;
                        ++checked;
                    }
                }
            }
        }
    }
    EXPECT_GT(checked, 30000);
}

TEST(LargeWorldTest, OnAGpusFloatsEyeRelativeMatricesKeepTheReceiversWhereTheWorldMatricesLoseThem) {
    // The forest's ground camera 1,000 km out: receivers within 50 m of the eye.
    ShadowSetupInputs in;
    const Vec3 far(1e6, 0.0, -1e6);
    in.camera.wsEye = far + Vec3(0, 1.8, 0);
    in.camera.wsDirection = glm::normalize(Vec3(0, -0.1, -1));
    in.camera.zNear = 0.1;
    in.camera.zFar = 50.0;
    in.light = DirectionalLight{glm::normalize(Vec3(0.3, -1.0, 0.4))};
    in.wsSceneBounds = Aabb::fromMinMax(far - Vec3(500, 1, 500), far + Vec3(500, 30, 500));
    for (const TechniqueInfo& info : allTechniques()) {
        in.technique = info.technique;
        auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        ConfigGenerator gen(3);
        std::vector<Vec3> receivers;
        for (int i = 0; i < 500; ++i) receivers.push_back(pointInFrustum(in.camera, gen));
        for (const ShadowView& view : setup->views) {
            const double texel = 2.0 / setup->mapSize;
            // Camera-relative: positions minus the eye in double, then float.
            const double eyeRelative = floatError(view.clipFromEyeRelative, minus(receivers, in.camera.wsEye));
            EXPECT_LE(eyeRelative, 0.05 * texel) << info.name;
            // The world matrix in float is off by float's step at 10^6 (6 cm): texels of the
            // focused maps, a fraction of one of the standard map's 0.5 m.
            const double world = floatError(view.clipFromWorld, receivers);
            EXPECT_GE(world, 10.0 * eyeRelative) << info.name;
            // (A clipmap's finest level only: its coarser texels are as large as the standard map's.)
            if (info.technique != Technique::Standard && (!setup->clipmap || &view == &setup->views[0])) {
                EXPECT_GE(world, texel) << info.name;
            }
        }
    }
}

TEST(LargeWorldTest, ARebasedSetUpIsTheSameMapInItsOwnCoordinates) {
    ConfigGenerator gen(21);
    for (int i = 0; i < 300; ++i) {
        ShadowSetupInputs in = moved(gen.next(), Vec3(3e6, 0, -2e6));
        in.technique = allTechniques()[static_cast<size_t>(i) % allTechniques().size()].technique;
        auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        const Vec3 origin = in.wsSceneBounds.center(); // a scene's own origin, near its eye
        const ShadowSetup local = rebased(*setup, origin);
        EXPECT_EQ(local.wsEye, setup->wsEye - origin);
        for (size_t v = 0; v < local.views.size(); ++v)
            for (const Vec3& p : pointsToHold(in, *setup, setup->views[v])) {
                const Vec3 d = ndcOf(local.views[v].clipFromWorld, p - origin) -
                               ndcOf(setup->views[v].clipFromEyeRelative, p - in.camera.wsEye);
                ASSERT_LE(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), 1e-6);
                const double linear = glm::dot(local.views[v].linearDepthFromWorld, Vec4(p - origin, 1.0));
                ASSERT_NEAR(linear,
                            glm::dot(setup->views[v].linearDepthFromEyeRelative, Vec4(p - in.camera.wsEye, 1.0)), 1e-6);
            }
        ASSERT_EQ(local.body.vertices().size(), setup->body.vertices().size());
    }
}

TEST(LargeWorldTest, HeldViewsAndLocalLightsKeepTheirEyeRelativeMatricesConsistent) {
    // A held lattice carries its refit's eye; every frame's set-up must still describe one map
    // in both coordinate systems.
    const Vec3 far(2e6, 0, 5e5);
    SetupHysteresis hysteresis;
    ShadowSetupInputs in;
    in.technique = Technique::Lispsm;
    in.camera.wsEye = far + Vec3(0, 2, 0);
    in.camera.wsDirection = glm::normalize(Vec3(0.2, -0.1, -1));
    in.camera.zFar = 200.0;
    in.light = DirectionalLight{glm::normalize(Vec3(0.4, -1.0, 0.3))};
    in.wsSceneBounds = Aabb::fromMinMax(far - Vec3(1000, 1, 1000), far + Vec3(1000, 30, 1000));
    int held = 0;
    for (int frame = 0; frame < 30; ++frame) {
        in.camera.wsEye += Vec3(0.05, 0, -0.3);
        auto setup = hysteresis.next(in);
        ASSERT_TRUE(setup);
        held += hysteresis.lastRefits().views == 0;
        EXPECT_EQ(setup->wsEye, in.camera.wsEye);
        for (const ShadowView& view : setup->views)
            for (const Vec3& p : setup->body.vertices()) {
                const Vec3 d = ndcOf(view.clipFromWorld, p) - ndcOf(view.clipFromEyeRelative, p - setup->wsEye);
                ASSERT_LE(std::max(std::abs(d.x), std::abs(d.y)), 1e-6) << "frame " << frame;
                ASSERT_LE(outsideClipCube(view.clipFromEyeRelative, p - setup->wsEye), 1e-6) << "frame " << frame;
            }
    }
    EXPECT_GT(held, 10); // the held path was exercised

    LocalShadowInputs local{.camera = in.camera, .wsSceneBounds = in.wsSceneBounds};
    const PointLight lamp{.wsPosition = in.camera.wsEye + Vec3(0, 3, -5), .range = 20};
    auto lighting = computeLocalLighting(local, std::span(&lamp, 1), {});
    ASSERT_TRUE(lighting);
    const LocalLighting moved = rebased(*lighting, far);
    EXPECT_EQ(moved.points[0].wsPosition, lamp.wsPosition - far);
    for (size_t v = 0; v < lighting->pointSetups[0].views.size(); ++v) {
        const Vec3 p = lamp.wsPosition + Vec3(1, -2.5, -3); // under the lamp
        const Vec4 world = lighting->pointSetups[0].views[v].clipFromWorld * Vec4(p, 1.0);
        const Vec4 there = moved.pointSetups[0].views[v].clipFromWorld * Vec4(p - far, 1.0);
        EXPECT_NEAR(world.x / world.w, there.x / there.w, 1e-6);
        EXPECT_NEAR(world.y / world.w, there.y / there.w, 1e-6);
    }
}

TEST(LargeWorldTest, EngineViewsGiveTheSameLookupEyeRelativeInEveryConvention) {
    ConfigGenerator gen(99);
    const OutputConventions conventions[] = {OutputConventions::openGL(), OutputConventions::vulkan(),
                                             OutputConventions::direct3D()};
    for (int i = 0; i < 200; ++i) {
        ShadowSetupInputs in = moved(gen.next(), Vec3(-4e5, 10, 9e5));
        in.technique = allTechniques()[static_cast<size_t>(i) % allTechniques().size()].technique;
        auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        for (OutputConventions c : conventions) {
            c.reversedZ = i % 2 == 0;
            for (size_t v = 0; v < setup->views.size(); ++v) {
                const EngineShadowView view = toEngineView(setup->views[v], *setup, c);
                ASSERT_EQ(view.wsEye, in.camera.wsEye);
                for (const Vec3& eyeRelative : eyeRelativePointsToHold(in, *setup, v)) {
                    const Vec3 p = eyeRelative + in.camera.wsEye;
                    const Vec3 d = ndcOf(view.textureFromEyeRelative, eyeRelative) - ndcOf(view.textureFromWorld, p);
                    ASSERT_LE(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), 1e-6);
                    ASSERT_NEAR(glm::dot(view.linearDepthFromEyeRelative, Vec4(eyeRelative, 1.0)),
                                glm::dot(view.linearDepthFromWorld, Vec4(p, 1.0)), 1e-6);
                }
            }
        }
    }
}
