// Flicker measured end to end (GL + Embree through measure::PathMeasurer): none for a still
// camera and scene, some when the map's grid slides within a texel (none when by whole
// texels), and stabilised cascades
// flickering less than unstabilised ones as the camera slides sideways. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/eval/temporal.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/measure/path_measurer.h"

#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class TemporalIntegrationTest : public gl::testing::HeadlessGlTest {
protected:
    void SetUp() override {
        HeadlessGlTest::SetUp();
        forest = gl::testing::smallForest(300, 200, 32);
        view = gl::testing::standardView(forest, "perpendicular");
        view.camera.zFar = 150.0;
        view.camera.aspect = 16.0 / 9.0;
        settings.width = 192;
        settings.height = 108;
        settings.fogDensity = 0.0f;
        auto m = measure::Measurer::create(forest);
        ASSERT_TRUE(m) << m.error();
        measurer = std::move(m).value();
    }

    core::ShadowSetupInputs inputs(const core::PerspectiveCamera& camera, core::Technique technique) const {
        core::ShadowSetupInputs in{.camera = camera,
                                   .light = view.light,
                                   .wsSceneBounds = forest.wsBounds(),
                                   .technique = technique,
                                   .mapSize = 512};
        in.cascades.count = 3;
        return in;
    }

    // Flicker of frame `b` against frame `a` (nothing moves but the camera), measured by the
    // temporal protocol every front end uses (measure::PathMeasurer).
    eval::TemporalFigures flicker(const core::ShadowSetupInputs& a, const core::ShadowSetupInputs& b) {
        EXPECT_EQ(a.technique, b.technique);
        frame::FrameConfig config;
        config.technique = a;
        config.render = settings;
        config.fogDensity = settings.fogDensity;
        auto driver = frame::FrameDriver::create(config);
        EXPECT_TRUE(driver) << driver.error();
        measure::PathMeasurer path(*measurer, forest, *driver);
        auto frameAt = [&](const core::ShadowSetupInputs& in) {
            scene::ResolvedView v = view;
            v.camera = in.camera;
            v.width = settings.width, v.height = settings.height;
            return v;
        };
        auto first = path.next(0.0, frameAt(a));
        EXPECT_TRUE(first) << first.error();
        EXPECT_FALSE(first->temporal);
        auto second = path.next(0.0, frameAt(b));
        EXPECT_TRUE(second && second->temporal);
        return *second->temporal;
    }

    scene::Scene forest;
    scene::ResolvedView view;
    gl::RenderSettings settings;
    std::unique_ptr<measure::Measurer> measurer;
};

core::PerspectiveCamera slid(core::PerspectiveCamera camera, double metres) {
    camera.wsEye += metres * glm::normalize(glm::cross(camera.wsDirection, camera.wsUp));
    return camera;
}

} // namespace

TEST_F(TemporalIntegrationTest, AStillCameraAndSceneHaveNoFlicker) {
    for (const core::Technique t : {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Csm}) {
        const eval::TemporalFigures f = flicker(inputs(view.camera, t), inputs(view.camera, t));
        EXPECT_GT(f.comparedPx, 5000) << core::techniqueName(t);
        EXPECT_EQ(f.flickerPct, 0.0) << core::techniqueName(t);
        EXPECT_EQ(f.truthChangePct, 0.0) << core::techniqueName(t);
    }
}

TEST_F(TemporalIntegrationTest, AMapWhoseGridSlidesWithinATexelFlickersAndByWholeTexelsDoesNot) {
    const core::ShadowSetupInputs in = inputs(view.camera, core::Technique::Focused);
    auto frame = measurer->measure(in, settings);
    ASSERT_TRUE(frame);
    const eval::ShadowStates states = eval::shadowStates(in.camera, *frame->truth, frame->comparison);
    // The previous frame drew the same map shifted by `texels` to the side: x' = x + (2 texels / size) w.
    auto flickerAfterShift = [&](double texels) {
        core::ShadowSetup shifted = frame->setup;
        core::Mat4 shift(1.0);
        shift[3][0] = 2.0 * texels / shifted.mapSize;
        for (core::ShadowView& v : shifted.views) v.clipFromWorld = shift * v.clipFromWorld;
        auto before = measurer->shadowsAt(*frame, in.camera, shifted, in.light, settings, true);
        EXPECT_TRUE(before);
        const eval::TemporalFigures f = eval::compareFrames(states, states, *before);
        EXPECT_EQ(f.truthChangePct, 0.0);
        return f.flickerPct;
    };
    EXPECT_EQ(flickerAfterShift(0.0), 0.0);
    // Sampling the world at the same points: what texel snapping (--stabilize) relies on.
    EXPECT_EQ(flickerAfterShift(1.0), 0.0);
    EXPECT_EQ(flickerAfterShift(-3.0), 0.0);
    // Half a texel: every edge runs over other texels.
    EXPECT_GT(flickerAfterShift(0.5), 0.05);
}

TEST_F(TemporalIntegrationTest, StabilisedCascadesFlickerLessThanUnstabilisedOnASidewaysMove) {
    double sum[2] = {0.0, 0.0};
    for (const bool stabilize : {false, true})
        for (int step = 0; step < 3; ++step) {
            core::ShadowSetupInputs a = inputs(slid(view.camera, 0.13 * step), core::Technique::Csm);
            core::ShadowSetupInputs b = inputs(slid(view.camera, 0.13 * (step + 1)), core::Technique::Csm);
            a.cascades.stabilize = b.cascades.stabilize = stabilize;
            const eval::TemporalFigures f = flicker(a, b);
            EXPECT_GT(f.comparedPx, 5000);
            EXPECT_EQ(f.truthChangePct, 0.0);
            sum[stabilize] += f.flickerPct;
        }
    EXPECT_GT(sum[0], 0.0);          // a grid that follows the camera slides under the shadows
    EXPECT_LT(sum[1], 0.5 * sum[0]); // a snapped one far less
}
