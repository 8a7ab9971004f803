// The live aliasing heat map (RenderSettings::aliasingOverlay, the viewer's "pixels per
// texel") is the evaluation's: on every pixel the evaluation counts, the overlay's colour is
// eval::aliasingMapImage's for the same frame. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/eval/maps.h"
#include "shadowkit/measure/measurer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

using namespace shadowkit;

namespace {
class AliasingOverlayTest : public gl::testing::HeadlessGlTest {};
} // namespace

TEST_F(AliasingOverlayTest, TheShaderHeatMapMatchesTheEvaluationsOnEveryValidPixel) {
    const scene::Scene forest = gl::testing::smallForest(300, 200, 32);
    for (const char* viewName : {"perpendicular", "aerial"}) {
        const scene::ResolvedView view = gl::testing::standardView(forest, viewName);
        auto measurer = measure::Measurer::create(forest);
        ASSERT_TRUE(measurer) << measurer.error();
        gl::RenderSettings settings;
        settings.width = 256;
        settings.height = 144;
        const core::ShadowSetupInputs inputs{.camera = view.camera,
                                             .light = view.light,
                                             .wsSceneBounds = forest.wsBounds(),
                                             .technique = core::Technique::Lispsm,
                                             .mapSize = 1024};
        auto m = (*measurer)->measure(inputs, settings);
        ASSERT_TRUE(m) << m.error();
        const scene::Image expected = eval::aliasingMapImage(m->comparison, settings.width, settings.height);

        settings.aliasingOverlay = true;
        ASSERT_TRUE((*measurer)->renderer().render(view.camera, view.light, m->setup, settings));
        const scene::Image overlay = (*measurer)->renderer().readColor();
        int compared = 0, differ = 0;
        for (int y = 0; y < settings.height; ++y)
            for (int x = 0; x < settings.width; ++x) {
                if (std::isnan(m->comparison.pixelsPerTexel[static_cast<size_t>(y * settings.width + x)])) continue;
                ++compared;
                const uint8_t *a = overlay.pixel(x, y), *b = expected.pixel(x, y);
                // float in the shader, double in eval: a level or two on the ramp.
                if (std::abs(a[0] - b[0]) > 3 || std::abs(a[1] - b[1]) > 3 || std::abs(a[2] - b[2]) > 3) ++differ;
            }
        EXPECT_GT(compared, 5000) << viewName;
        EXPECT_LT(differ, compared / 200) << viewName << ": " << differ << " of " << compared << " pixels differ";
    }
}
