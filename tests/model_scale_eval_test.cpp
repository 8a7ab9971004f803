// A model scores the same whatever its units (issue 49, robust on a user's model): shadows do
// not know metres from micrometres, and neither may the set-ups, the framing or the truth. A
// file in the wrong units — a CAD part in metres that should have been millimetres, a scan
// scaled down twice — was 1–8 % wrong a micrometre across where it was 0.00 at a metre: the
// truth's shadow rays started 10 µm off their surface (a floor of 1 m × 1e-5), the focus body's
// scene box was at least 1 mm thick and the framing at least 1 mm away. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>

using namespace shadowkit;

namespace {

class ModelScaleEvalTest : public gl::testing::HeadlessGlTest {};

// tests/data/pillar_on_plate.gltf (a 12 m plate, a 4 m pillar) scaled by `scale` about the
// scene's own origin, standing at the world's (a micrometre 2 km out is another test: large
// worlds).
scene::Scene pillarScaledBy(double scale) {
    const auto file =
        std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "pillar_on_plate.gltf";
    auto loaded = scene::loadScene(file);
    EXPECT_TRUE(loaded) << loaded.error();
    if (!loaded) return {};
    loaded->wsOrigin = core::Vec3(0.0);
    const glm::mat4 scaled = glm::scale(glm::mat4(1.0f), glm::vec3(float(scale)));
    for (scene::MeshBatch& batch : loaded->batches)
        for (glm::mat4& worldFromObject : batch.worldFromObject) worldFromObject = scaled * worldFromObject;
    return std::move(*loaded);
}

eval::Figures scaledViewFigures(const scene::Scene& model, const std::string& name, core::Technique technique) {
    const scene::ResolvedView view = gl::testing::standardView(model, name);
    auto measurer = measure::Measurer::create(model);
    EXPECT_TRUE(measurer) << measurer.error();
    if (!measurer) return {};
    gl::RenderSettings settings;
    settings.width = 240;
    settings.height = 135;
    core::PerspectiveCamera camera = view.camera;
    camera.aspect = 16.0 / 9.0;
    auto measured = (*measurer)->measure({.camera = camera,
                                          .light = view.light,
                                          .wsSceneBounds = (*measurer)->renderer().wsSceneBounds(),
                                          .technique = technique,
                                          .mapSize = 1024},
                                         settings);
    EXPECT_TRUE(measured) << measured.error();
    return measured ? measured->figures() : eval::Figures{};
}

} // namespace

TEST_F(ModelScaleEvalTest, AModelAMicrometreAcrossScoresAsAtTwelveMetres) {
    const scene::Scene metres = pillarScaledBy(1.0);
    for (const double scale : {1e-3, 1e-6}) {
        const scene::Scene small = pillarScaledBy(scale);
        for (const std::string view : {"paper", "aerial"})
            for (const core::Technique technique : {core::Technique::Tsm, core::Technique::Lispsm}) {
                const eval::Figures at = scaledViewFigures(metres, view, technique);
                const eval::Figures scaled = scaledViewFigures(small, view, technique);
                const std::string where =
                    view + " " + std::string(core::techniqueName(technique)) + " at " + std::to_string(scale);
                ASSERT_GT(at.validPx, 2000) << where;
                EXPECT_NEAR(scaled.wrongPct, at.wrongPct, 0.02) << where;
                EXPECT_NEAR(double(scaled.validPx), double(at.validPx), 0.002 * double(at.validPx)) << where;
                // The same map density: the set-up's box is the model's, not a millimetre's.
                EXPECT_NEAR(scaled.pixelsPerTexelP50, at.pixelsPerTexelP50, 0.02 * at.pixelsPerTexelP50) << where;
            }
    }
    // The virtual clipmap's texels are powers of two of a metre: scaled by one, its levels and
    // pages fall as at 12 m, and so do its figures (before, its depth range was at least a metre
    // and its coarsest level held at least a millimetre).
    const scene::Scene pow2 = pillarScaledBy(std::ldexp(1.0, -20));
    for (const std::string view : {"paper", "aerial"}) {
        const eval::Figures at = scaledViewFigures(metres, view, core::Technique::Virtual);
        const eval::Figures scaled = scaledViewFigures(pow2, view, core::Technique::Virtual);
        ASSERT_GT(at.validPx, 2000) << view;
        EXPECT_NEAR(scaled.wrongPct, at.wrongPct, 0.02) << view;
        EXPECT_NEAR(scaled.pixelsPerTexelP50, at.pixelsPerTexelP50, 0.02 * at.pixelsPerTexelP50) << view;
    }
}
