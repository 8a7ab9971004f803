// Rasterized shadows measured against ray-traced truth, end to end (GL + eval).
// CTest label `gl`: runs headless on Mesa llvmpipe.
#include "headless_gl_test.h"

#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/ray_scene.h"
#include "shadowkit/eval/truth.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/views.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class EvalIntegrationTest : public gl::testing::HeadlessGlTest {
protected:
    // Renders and ray-traces one view and returns the figures.
    static eval::Figures measure(const scene::Scene& s, const core::PerspectiveCamera& cam, const core::DirectionalLight& sun,
                                 core::Technique technique, const gl::RenderSettings& settings) {
        auto setup = core::computeShadowSetup({.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = technique});
        EXPECT_TRUE(setup);
        auto renderer = gl::Renderer::create(s);
        EXPECT_TRUE(renderer);
        auto raster = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
        EXPECT_TRUE(raster) << raster.error();
        auto rays = eval::RayScene::build(s);
        EXPECT_TRUE(rays);
        const eval::TruthBuffers truth = eval::computeTruth(**rays, cam, sun, settings.width, settings.height);
        auto comparison = eval::compare(*raster, truth);
        EXPECT_TRUE(comparison);
        return comparison->figures;
    }
};

} // namespace

TEST_F(EvalIntegrationTest, SmallMapScoresWorseThanLargeMapOnTheSameView) {
    scene::ForestOptions o;
    o.trees = 300;
    o.terrainSize = 200;
    o.terrainResolution = 32;
    const scene::Scene forest = scene::makeForest(o);
    auto views = scene::loadViews(scene::dataDirectory() / "views.json");
    ASSERT_TRUE(views);
    scene::ResolvedView view = scene::resolveView(*scene::findView(*views, "aerial"), forest);
    view.camera.zFar = 400;
    view.camera.aspect = 4.0 / 3.0;
    gl::RenderSettings settings;
    settings.width = 200;
    settings.height = 150;
    settings.fogDensity = 0.0f;

    for (core::Technique t : {core::Technique::Standard, core::Technique::Focused}) {
        settings.shadowMapSize = 256;
        const eval::Figures small = measure(forest, view.camera, view.light, t, settings);
        settings.shadowMapSize = 2048;
        const eval::Figures large = measure(forest, view.camera, view.light, t, settings);
        EXPECT_GT(small.validPx, 5000);
        EXPECT_GT(small.wrongPct, large.wrongPct) << core::techniqueName(t);
        EXPECT_GT(small.undersampledPct, large.undersampledPct) << core::techniqueName(t);
        EXPECT_GT(small.pixelsPerTexelP50, 4.0 * large.pixelsPerTexelP50) << core::techniqueName(t); // 8x fewer texels per side
    }
}

TEST_F(EvalIntegrationTest, UnbiasedMapShowsAcneOnALitTiltedPlaneThatSlopeScaledBiasRemoves) {
    // A single plane tilted 30° about x, lit from 40° above it: everything is lit in truth,
    // so every shadowed pixel is self-shadowing acne.
    scene::Scene s;
    scene::Mesh plane;
    scene::addBox(plane, glm::mat4(1.0f), {10, 0.01f, 10}, glm::vec3(0.8f));
    plane.computeBounds();
    s.meshes = {plane};
    s.batches = {{0, {glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(1, 0, 0))}, false}};
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 12, 14};
    cam.wsDirection = -cam.wsEye;
    cam.aspect = 1.0;
    cam.zNear = 1.0;
    cam.zFar = 60;
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(40, 20).value();
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.shadowMapSize = 512;

    settings.bias.slope = 0.0;
    settings.bias.constant = 0.0;
    const eval::Figures unbiased = measure(s, cam, sun, core::Technique::Focused, settings);
    settings.bias.slope = 2.0;
    settings.bias.constant = 1.0;
    const eval::Figures biased = measure(s, cam, sun, core::Technique::Focused, settings);
    ASSERT_GT(unbiased.validPx, 5000);
    EXPECT_GT(unbiased.falseShadowPct, 5.0);
    EXPECT_LT(biased.falseShadowPct, 0.1);
    EXPECT_EQ(biased.falseLitPct, 0.0); // nothing is shadowed in truth
}

TEST_F(EvalIntegrationTest, ExcessiveConstantBiasDetachesShadowsIntoFalseLit) {
    // Peter-panning: a 20 cm slab 5 cm above a tilted plane. A bias of a few depth steps keeps its
    // contact shadow; a constant of 10^6 steps (6 % of the map's depth range) pushes the
    // stored depth behind the receivers near the contact, which then read as lit.
    scene::Scene s;
    scene::Mesh plane, box;
    scene::addBox(plane, glm::mat4(1.0f), {10, 0.01f, 10}, glm::vec3(0.8f));
    scene::addBox(box, glm::translate(glm::mat4(1.0f), {0, 0.16f, 0}), {1.5f, 0.1f, 1.5f}, glm::vec3(0.8f)); // a slab
    plane.computeBounds();
    box.computeBounds();
    const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(20.0f), glm::vec3(1, 0, 0));
    s.meshes = {plane, box};
    s.batches = {{0, {tilt}, false}, {1, {tilt}, false}};
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 9, 10};
    cam.wsDirection = -cam.wsEye;
    cam.aspect = 1.0;
    cam.zNear = 1.0;
    cam.zFar = 60;
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(35, 30).value(); // a long shadow in view
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.shadowMapSize = 1024;
    const eval::Figures normal = measure(s, cam, sun, core::Technique::Focused, settings);
    settings.bias.constant = 1e6;
    const eval::Figures excessive = measure(s, cam, sun, core::Technique::Focused, settings);
    ASSERT_GT(normal.validPx, 5000);
    EXPECT_LT(normal.falseLitPct, 0.5);
    EXPECT_GT(excessive.falseLitPct, 5.0 * normal.falseLitPct + 0.5);
}

TEST_F(EvalIntegrationTest, LispsmBeatsFocusedOnThePerpendicularView) {
    // Seed 001's ideal case: view perpendicular to the light. Same map size, same view.
    scene::ForestOptions o;
    o.trees = 1500;
    o.terrainSize = 300;
    o.terrainResolution = 64;
    const scene::Scene forest = scene::makeForest(o);
    auto views = scene::loadViews(scene::dataDirectory() / "views.json");
    ASSERT_TRUE(views);
    scene::ResolvedView view = scene::resolveView(*scene::findView(*views, "perpendicular"), forest);
    gl::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.shadowMapSize = 1024;
    const eval::Figures focused = measure(forest, view.camera, view.light, core::Technique::Focused, settings);
    const eval::Figures lispsm = measure(forest, view.camera, view.light, core::Technique::Lispsm, settings);
    EXPECT_LT(lispsm.undersampledPct, focused.undersampledPct);
    EXPECT_LT(lispsm.wrongPct, focused.wrongPct);
    EXPECT_LT(lispsm.pixelsPerTexelP50, 0.5 * focused.pixelsPerTexelP50);
}
