// shadowkit score against eval: shadowkit's own rasterised term, scored as another renderer's
// mask (eval/score.h), must class every pixel eval validated as eval did — the same pixels, the
// same numbers — and differ only by the pixels eval excluded (silhouettes where the rasteriser
// and the rays see different surfaces), which a mask cannot tell apart. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/eval/score.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/measure/measurer.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit;

namespace {
class ScoreIntegrationTest : public gl::testing::HeadlessGlTest {};
} // namespace

TEST_F(ScoreIntegrationTest, ShadowkitsOwnTermScoresAsEvalMeasuredIt) {
    const scene::Scene forest = gl::testing::smallForest(300, 200, 32);
    auto measurer = measure::Measurer::create(forest);
    ASSERT_TRUE(measurer) << measurer.error();
    gl::RenderSettings settings;
    settings.width = 192;
    settings.height = 108;
    settings.sunAngleDegrees = 0.53;
    settings.filter = {core::ShadowFilter::Pcss, 16};
    for (const char* name : {"perpendicular", "aerial"})
        for (core::Technique technique : {core::Technique::Tsm, core::Technique::Standard}) {
            const scene::ResolvedView view = gl::testing::standardView(forest, name);
            core::PerspectiveCamera camera = view.camera;
            camera.aspect = 192.0 / 108.0;
            auto m = (*measurer)->measure({.camera = camera,
                                           .light = view.light,
                                           .wsSceneBounds = forest.wsBounds(),
                                           .technique = technique,
                                           .mapSize = 512},
                                          settings);
            ASSERT_TRUE(m) << m.error();
            const eval::ShadowMask mask{m->raster.width, m->raster.height, m->raster.shadowTerm, {}};
            auto scored = eval::scoreMask(mask, *m->truth);
            ASSERT_TRUE(scored) << scored.error();
            const eval::Figures &e = m->figures(), &s = scored->figures;
            const std::string what = std::string(name) + ", " + std::string(core::techniqueName(technique));
            ASSERT_GT(e.validPx, 5000) << what;
            // Every pixel eval validated, classed the same; those it excluded, now counted.
            int64_t excludedNowWrong = 0;
            for (size_t i = 0; i < m->comparison.classes.size(); ++i) {
                const eval::PixelClass before = m->comparison.classes[i], now = scored->classes[i];
                if (before == eval::PixelClass::Excluded)
                    excludedNowWrong += now == eval::PixelClass::FalseLit || now == eval::PixelClass::FalseShadow;
                else
                    ASSERT_EQ(now, before) << what << ", pixel " << i;
            }
            EXPECT_EQ(s.validPx, e.validPx + e.excludedPx) << what;
            EXPECT_EQ(s.excludedPx, 0) << what;
            const double wrongBefore = std::round(e.wrongPct * double(e.validPx) / 100.0);
            EXPECT_NEAR(s.wrongPct * double(s.validPx) / 100.0, wrongBefore + double(excludedNowWrong), 1e-6) << what;
            // The soft figures over the same pixels: eval's where it validated them.
            ASSERT_TRUE(m->softTruth && m->soft) << what;
            const eval::SoftFigures soft =
                eval::compareSoft(mask.visibility, *m->softTruth, m->comparison.classes, 0.53);
            EXPECT_DOUBLE_EQ(soft.softMae, m->soft->softMae) << what;
            EXPECT_EQ(soft.penumbraPx, m->soft->penumbraPx) << what;
        }
}
