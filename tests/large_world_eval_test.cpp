// Large worlds end to end (issue 15): a forest standing 10^6 and 10^7 m from the world's
// origin is rendered and ray-traced as precisely as at it — set-ups relative to the eye,
// the GPU and Embree in the scene's own coordinates (scene::Scene::wsOrigin). CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

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

namespace {

// A user's model as a survey export writes it: a 20 m ground, a 3 m box and a 6 m pole, in
// world metres `at` (an OBJ), loaded as `eval --scene FILE` loads it.
scene::Scene loadSurveyModelAt(const glm::dvec3& at) {
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_survey_model.obj";
    {
        std::ofstream out(file);
        out.precision(17);
        int vertices = 0;
        const auto box = [&](glm::dvec3 lo, glm::dvec3 hi) { // outward faces, counter-clockwise
            const glm::dvec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
                                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
            for (const glm::dvec3& p : c) out << "v " << at.x + p.x << ' ' << at.y + p.y << ' ' << at.z + p.z << '\n';
            const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 4, 6, 2}, {1, 3, 7, 5}, {2, 6, 7, 3}, {0, 1, 5, 4}};
            for (const auto& q : f)
                out << "f " << vertices + q[0] + 1 << ' ' << vertices + q[1] + 1 << ' ' << vertices + q[2] + 1 << ' '
                    << vertices + q[3] + 1 << '\n';
            vertices += 8;
        };
        box({-10, -0.5, -10}, {10, 0, 10});
        box({-2, 0, -2}, {2, 3, 2});
        box({4, 0, 3}, {4.2, 6, 3.2});
        out.close();
        // A file the test could not write is the test's failure, not the loader's.
        if (!out) ADD_FAILURE() << file << ": the test could not write it";
    }
    auto loaded = scene::loadScene(file);
    std::filesystem::remove(file);
    EXPECT_TRUE(loaded) << loaded.error();
    return loaded ? std::move(*loaded) : scene::Scene{};
}

eval::Figures measureLoadedView(const scene::Scene& model, const std::string& name, int64_t& shadowedPx) {
    const scene::ResolvedView view = gl::testing::standardView(model, name);
    auto measurer = measure::Measurer::create(model);
    EXPECT_TRUE(measurer) << measurer.error();
    if (!measurer) return {};
    gl::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    core::PerspectiveCamera camera = view.camera;
    camera.aspect = 16.0 / 9.0;
    auto measured = (*measurer)->measure({.camera = camera,
                                          .light = view.light,
                                          .wsSceneBounds = (*measurer)->renderer().wsSceneBounds(),
                                          .technique = core::Technique::Tsm,
                                          .mapSize = 1024},
                                         settings);
    EXPECT_TRUE(measured) << measured.error();
    if (!measured) return {};
    shadowedPx = std::count(measured->comparison.classes.begin(), measured->comparison.classes.end(),
                            eval::PixelClass::ShadowCorrect);
    return measured->figures();
}

} // namespace

// Issue 49, robust on a user's model: loaded from a file in survey metres (a UTM easting and
// northing), a model scores as the same file at the origin does. Before the loader stood such a
// scene at its own origin (scene/src/near_origin.cpp), its floats held the file's big numbers: a
// model like this 1e6 m out was 48 % wrong on `paper`, with raster and ray disagreeing on 2,700
// of 4,600 pixels, and 1e7 m out 15–40 % on every view.
TEST_F(LargeWorldEvalTest, AModelInSurveyMetresLoadedFromItsFileScoresAsAtTheOrigin) {
    const scene::Scene atOrigin = loadSurveyModelAt(glm::dvec3(0.0));
    const scene::Scene surveyed = loadSurveyModelAt(glm::dvec3(512345.678, 231.5, 5412345.321));
    for (const std::string view : {"paper", "perpendicular", "aerial"}) {
        int64_t originShadowed = 0, surveyShadowed = 0;
        const eval::Figures origin = measureLoadedView(atOrigin, view, originShadowed);
        const eval::Figures survey = measureLoadedView(surveyed, view, surveyShadowed);
        ASSERT_GT(origin.validPx, 2000) << view;
        ASSERT_GT(originShadowed, 100) << view; // there are shadows to get wrong
        EXPECT_NEAR(survey.wrongPct, origin.wrongPct, 0.05) << view;
        EXPECT_NEAR(double(survey.validPx), double(origin.validPx), 0.002 * double(origin.validPx)) << view;
        EXPECT_NEAR(double(surveyShadowed), double(originShadowed), 0.01 * double(originShadowed)) << view;
    }
}
