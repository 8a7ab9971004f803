// A user's glTF measured as its author set it up (`--view file`, scene::fileView): through its
// own camera, under its own sun and lamp, against the ray-traced truth of the same lights.
// tests/data/lit_pillar.gltf: a 12 m plate with a 4 m pillar 2 km from the origin, a camera
// 14 m up and 14 m back looking 45° down towards −z, a sun travelling along (1, −1, 0) — so
// the pillar's shadow falls towards +x, to the right in the picture — and a point lamp in front
// on the left. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace shadowkit;

namespace {

class FileViewEvalTest : public gl::testing::HeadlessGlTest {};

// Pixels rendered and truly in shadow, in the picture's left and right halves.
struct ShadowHalves {
    int64_t left = 0, right = 0;
};

ShadowHalves shadowHalvesOf(const std::vector<eval::PixelClass>& classes, int width) {
    ShadowHalves out;
    for (size_t i = 0; i < classes.size(); ++i)
        if (classes[i] == eval::PixelClass::ShadowCorrect)
            ++(int(i % size_t(width)) < width / 2 ? out.left : out.right);
    return out;
}

} // namespace

TEST_F(FileViewEvalTest, TheFilesOwnSunAndLampCastItsShadowsWhereTheyMust) {
    const auto file = std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "lit_pillar.gltf";
    const auto model = scene::loadScene(file);
    ASSERT_TRUE(model) << model.error();
    const auto view = scene::fileView(*model, "", gl::kMaxLocalLightsPerKind);
    ASSERT_TRUE(view) << view.error();
    ASSERT_TRUE(view->sun);
    ASSERT_EQ(view->points.size(), 1u);
    auto measurer = measure::Measurer::create(*model);
    ASSERT_TRUE(measurer) << measurer.error();
    gl::RenderSettings settings;
    settings.width = 240;
    settings.height = 160; // the camera's aspect, 1.5
    const core::Aabb bounds = (*measurer)->renderer().wsSceneBounds();
    const core::ShadowSetupInputs input{
        .camera = view->camera, .light = view->light, .wsSceneBounds = bounds, .technique = core::Technique::Tsm};

    // The sun: the shadow lies right of the pillar. The standard views' sun for an unlit file
    // (90° right of the camera) would throw it to the left; ignoring the file's direction shows.
    auto sun = (*measurer)->measure(input, settings);
    ASSERT_TRUE(sun) << sun.error();
    const ShadowHalves sunShadow = shadowHalvesOf(sun->comparison.classes, settings.width);
    EXPECT_GT(sunShadow.right, 150); // 343 at 240 × 160
    EXPECT_LT(sunShadow.left, sunShadow.right / 20);
    EXPECT_LT(sun->figures().wrongPct, 1.0);

    // The lamp alone (the sun off): its shadow is cast and scored against its own truth.
    auto lighting = core::computeLocalLighting({.camera = view->camera, .wsSceneBounds = bounds, .mapSize = 512},
                                               view->points, view->spots);
    ASSERT_TRUE(lighting) << lighting.error();
    ASSERT_TRUE((*measurer)->renderer().setLocalLights(*lighting));
    settings.sun = false;
    auto lamp = (*measurer)->measure(input, settings);
    ASSERT_TRUE(lamp) << lamp.error();
    const ShadowHalves lampShadow = shadowHalvesOf(lamp->comparison.classes, settings.width);
    EXPECT_GT(lampShadow.left + lampShadow.right, 100);
    EXPECT_LT(lamp->figures().wrongPct, 1.0);
}
