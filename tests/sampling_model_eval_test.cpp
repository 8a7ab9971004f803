// The sampling model (core/sampling_error.h) against eval's exact per-pixel figure (issue 16):
// samples from a read-back at a quarter of the resolution predict the p50 / p95 / p99 pixels
// per texel that `shadowkit eval` measures at every valid pixel, for every technique on every
// standard view of a small forest. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/core/sampling_error.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit;

namespace {

class SamplingModelEvalTest : public gl::testing::HeadlessGlTest {};

double relativeError(double predicted, double measured) { return std::abs(predicted - measured) / measured; }

} // namespace

TEST_F(SamplingModelEvalTest, PredictedPercentilesAgreeWithEvalWithinTenPercent) {
    const scene::Scene forest = gl::testing::smallForest(400, 300, 48);
    auto measurer = measure::Measurer::create(forest);
    ASSERT_TRUE(measurer) << measurer.error();
    gl::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    const core::Aabb bounds = (*measurer)->renderer().wsSceneBounds();
    double worst50 = 0.0, worst95 = 0.0, worst99 = 0.0;
    for (const std::string name : {"paper", "perpendicular", "into-sun", "sun-behind", "noon", "aerial"}) {
        const scene::ResolvedView view = gl::testing::standardView(forest, name);
        core::ShadowSetupInputs inputs{
            .camera = view.camera, .light = view.light, .wsSceneBounds = bounds, .mapSize = 1024};
        inputs.camera.aspect = 16.0 / 9.0;
        auto samples =
            frame::sampleReceivers((*measurer)->renderer(), inputs, settings, {.width = 160, .maxSamples = 4096});
        ASSERT_TRUE(samples) << samples.error();
        ASSERT_GT(samples->size(), 500u) << name;
        auto model = core::SamplingErrorModel::create(inputs.camera, settings.width, settings.height, *samples);
        ASSERT_TRUE(model) << model.error();
        for (const core::TechniqueInfo& technique : core::allTechniques()) {
            inputs.technique = technique.technique;
            auto measured = (*measurer)->measure(inputs, settings);
            ASSERT_TRUE(measured) << measured.error();
            const eval::Figures& f = measured->figures();
            ASSERT_GT(f.validPx, 5000) << name;
            const core::SamplingFigures predicted = model->figures(measured->setup);
            const std::string where = name + " " + std::string(technique.name);
            const double e50 = relativeError(predicted.p50, f.pixelsPerTexelP50),
                         e95 = relativeError(predicted.p95, f.pixelsPerTexelP95),
                         e99 = relativeError(predicted.p99, f.pixelsPerTexelP99);
            EXPECT_LT(e50, 0.10) << where << " p50: " << predicted.p50 << " predicted, " << f.pixelsPerTexelP50
                                 << " measured";
            EXPECT_LT(e95, 0.10) << where << " p95: " << predicted.p95 << " predicted, " << f.pixelsPerTexelP95
                                 << " measured";
            // The 1 % tail of 4,096 samples is 41 receivers, mostly edge-on to the light, where
            // the figure changes fastest: a looser bound (docs/error-driven.md). Its estimate
            // moves with which receivers the even spread picks: one pixel along the sun's rays
            // left out of some 8,000 (core::facesLight, as eval leaves it out) shifts every pick
            // after it and moved the worst p99 from 0.26 to 0.36 (`paper`, PSM).
            EXPECT_LT(e99, 0.40) << where << " p99: " << predicted.p99 << " predicted, " << f.pixelsPerTexelP99
                                 << " measured";
            worst50 = std::max(worst50, e50), worst95 = std::max(worst95, e95), worst99 = std::max(worst99, e99);
        }
    }
    std::printf("worst relative error of the predicted p50 %.3f, p95 %.3f, p99 %.3f\n", worst50, worst95, worst99);
}
