// Spot and point lights measured against ray-traced truth on the standard night views `lamp`
// and `torch` (docs/local-lights.md), at their sizes and the default local map and
// bias, on the full default forest. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class LocalLightsEvalTest : public gl::testing::HeadlessGlTest {};

// The view's local lights measured with maps of `mapSize` texels per side (figures of every
// light together; these views have one light each).
eval::Figures measureView(measure::Measurer& measurer, const scene::Scene& forest, const std::string& name,
                          int mapSize) {
    auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    EXPECT_TRUE(views) << views.error();
    const scene::ResolvedView view = scene::resolveView(*scene::findView(*views, name), forest);
    gl::RenderSettings settings; // defaults: the recommended local bias, hard test
    settings.width = view.width;
    settings.height = view.height;
    settings.sun = view.sun;
    const core::Aabb bounds = measurer.renderer().wsSceneBounds();
    auto lighting = core::computeLocalLighting({.camera = view.camera, .wsSceneBounds = bounds, .mapSize = mapSize},
                                               view.points, view.spots);
    EXPECT_TRUE(lighting) << lighting.error();
    EXPECT_TRUE(measurer.renderer().setLocalLights(*lighting));
    auto m = measurer.measure({.camera = view.camera, .light = view.light, .wsSceneBounds = bounds}, settings);
    EXPECT_TRUE(m) << m.error();
    EXPECT_EQ(m->lights.size(), view.points.size() + view.spots.size()) << "night: the sun is not measured";
    return m->figures();
}

} // namespace

TEST_F(LocalLightsEvalTest, LampAndTorchAreRightToHalfAPercentAndAQuarterOfTheMapSizeIsWorse) {
    const scene::Scene forest = scene::makeForest({});
    auto measurer = measure::Measurer::create(forest);
    ASSERT_TRUE(measurer) << measurer.error();
    for (const char* name : {"lamp", "torch"}) {
        const eval::Figures full = measureView(**measurer, forest, name, core::LocalShadowInputs{}.mapSize);
        const eval::Figures quarter = measureView(**measurer, forest, name, core::LocalShadowInputs{}.mapSize / 4);
        EXPECT_GT(full.validPx, 20000) << name << ": the light must reach a good part of the image";
        EXPECT_LE(full.wrongPct, 0.5) << name;
        EXPECT_GT(quarter.wrongPct, full.wrongPct) << name;
        EXPECT_GT(quarter.pixelsPerTexelP50, 3.0 * full.pixelsPerTexelP50) << name << ": 4x fewer texels per side";
    }
}
