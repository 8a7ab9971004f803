// Large worlds end to end (issue 15): a forest standing 10^6 and 10^7 m from the world's
// origin is rendered and ray-traced as precisely as at it — set-ups relative to the eye,
// the GPU and Embree in the scene's own coordinates (scene::Scene::wsOrigin). CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace shadowkit;

namespace {

class LargeWorldEvalTest : public gl::testing::HeadlessGlTest {};

struct Figures {
    eval::Figures sun, lamp;
    int64_t sunShadowedPx = 0; // rendered and truly in the sun's shadow
};

// The view's figures under the sun, and under a point lamp beside the path with the sun off.
Figures measureAt(const core::Vec3& wsOrigin, core::Technique technique, gl::Culling culling) {
    scene::Scene forest = gl::testing::smallForest(400, 300, 48);
    forest.wsOrigin = wsOrigin;
    const scene::ResolvedView view = gl::testing::standardView(forest, "perpendicular");
    auto measurer = measure::Measurer::create(forest);
    EXPECT_TRUE(measurer) << measurer.error();
    gl::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.culling = culling;
    settings.receiverMask = culling == gl::Culling::Occlusion;
    core::PerspectiveCamera camera = view.camera;
    camera.aspect = 16.0 / 9.0;
    const core::Aabb bounds = (*measurer)->renderer().wsSceneBounds();
    Figures out;
    auto sun = (*measurer)->measure(
        {.camera = camera, .light = view.light, .wsSceneBounds = bounds, .technique = technique, .mapSize = 1024},
        settings);
    EXPECT_TRUE(sun) << sun.error();
    out.sun = sun->figures();
    out.sunShadowedPx =
        std::count(sun->comparison.classes.begin(), sun->comparison.classes.end(), eval::PixelClass::ShadowCorrect);

    const core::PointLight lamp{.wsPosition = camera.wsEye + core::Vec3(2, 2, -8), .range = 25};
    auto lighting = core::computeLocalLighting({.camera = camera, .wsSceneBounds = bounds, .mapSize = 512},
                                               std::span(&lamp, 1), {});
    EXPECT_TRUE(lighting) << lighting.error();
    EXPECT_TRUE((*measurer)->renderer().setLocalLights(*lighting));
    settings.sun = false;
    auto night = (*measurer)->measure(
        {.camera = camera, .light = view.light, .wsSceneBounds = bounds, .technique = technique, .mapSize = 1024},
        settings);
    EXPECT_TRUE(night) << night.error();
    out.lamp = night->figures();
    return out;
}

} // namespace

TEST_F(LargeWorldEvalTest, AForestAMillionAndTenMillionMetresOutScoresAsAtTheOrigin) {
    const struct {
        core::Technique technique;
        gl::Culling culling;
    } cases[] = {{core::Technique::Tsm, gl::Culling::Frustum},
                 {core::Technique::Lispsm, gl::Culling::Occlusion},
                 {core::Technique::Csm, gl::Culling::Frustum}};
    for (const auto& c : cases) {
        const Figures origin = measureAt(core::Vec3(0.0), c.technique, c.culling);
        ASSERT_GT(origin.sun.validPx, 20000);
        ASSERT_GT(origin.lamp.validPx, 1000);
        ASSERT_GT(origin.sunShadowedPx, 1000); // there are shadows to get wrong
        for (const core::Vec3 offset : {core::Vec3(1e6, 0, 1e6), core::Vec3(-7e6, 300, 7e6)}) {
            const Figures far = measureAt(offset, c.technique, c.culling);
            const std::string where = std::string(core::techniqueName(c.technique)) + " at " + std::to_string(offset.x);
            // The bound: wrong_pct within 0.05 of the origin's.
            EXPECT_NEAR(far.sun.wrongPct, origin.sun.wrongPct, 0.05) << where;
            EXPECT_NEAR(far.lamp.wrongPct, origin.lamp.wrongPct, 0.05) << where;
            // The same surfaces seen: primary rays and rasterised pixels agree as at the origin.
            EXPECT_NEAR(double(far.sun.validPx), double(origin.sun.validPx), 0.002 * double(origin.sun.validPx))
                << where;
            EXPECT_NEAR(far.sun.pixelsPerTexelP50, origin.sun.pixelsPerTexelP50, 0.01 * origin.sun.pixelsPerTexelP50)
                << where;
        }
    }
}
