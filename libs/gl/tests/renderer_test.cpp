// Headless rendering tests (CTest label `gl`): a box floating over a plane under an
// overhead sun must shadow the plane below it, for every technique.
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class RendererTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        auto context = gl::Context::createHeadless();
        ASSERT_TRUE(context) << context.error();
        s_context = std::move(context).value().release();
    }
    static void TearDownTestSuite() { delete s_context; }
    static gl::Context* s_context;
};
gl::Context* RendererTest::s_context = nullptr;

scene::Scene boxOverPlane() {
    scene::Scene s;
    scene::Mesh ground, box;
    ground.name = "ground";
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {20, 0.05f, 20}, glm::vec3(0.8f));
    box.name = "box";
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1}, glm::vec3(0.8f));
    ground.computeBounds();
    box.computeBounds();
    s.meshes = {ground, box};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 2.5f, 0})}, false}};
    return s;
}

core::PerspectiveCamera obliqueCamera() {
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 10, 20};
    cam.wsDirection = -cam.wsEye; // at the origin
    cam.fovYDegrees = 40;
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 60;
    return cam;
}

// Luminance of the pixel that shows world point `ws`.
double luminanceAt(const scene::Image& image, const core::PerspectiveCamera& cam, const core::Vec3& ws) {
    const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(ws, 1.0);
    const int x = static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * image.width);
    const int y = static_cast<int>((0.5 - cs.y / cs.w * 0.5) * image.height); // top row first
    const uint8_t* p = image.pixel(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

} // namespace

TEST_F(RendererTest, ContextIsOpenGL45Core) {
    EXPECT_NE(s_context->description().find("4.5"), std::string::npos) << s_context->description();
}

TEST_F(RendererTest, BoxOverPlaneShadowsThePlaneBelowItForEveryTechnique) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.shadowMapSize = 256;
    settings.fogDensity = 0.0f;

    for (const core::TechniqueInfo& technique : core::allTechniques()) {
        const auto setup = core::computeShadowSetup({.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = technique.technique});
        ASSERT_TRUE(setup) << setup.error();
        const auto stats = (*renderer)->render(cam, sun, *setup, settings);
        ASSERT_TRUE(stats) << stats.error();
        EXPECT_EQ(stats->shadow.drawCalls, 2u * setup->views.size()); // two batches per map
        const scene::Image image = (*renderer)->readColor();
        const double under = luminanceAt(image, cam, {0.3, 0, 0.3});
        const double away = luminanceAt(image, cam, {6, 0, 2});
        // Shadowed: ambient only; lit: ambient + sun. The ratio is ~0.45 with our radiances.
        EXPECT_LT(under, 0.7 * away) << technique.name << ": under " << under << ", away " << away;
        EXPECT_GT(away, 100.0) << technique.name << ": the lit plane must not be dark (acne or a wrong matrix)";
    }
}

TEST_F(RendererTest, ShadowMapImageShowsTheCaster) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    const auto setup = core::computeShadowSetup({.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = core::Technique::Standard});
    gl::RenderSettings settings;
    settings.width = settings.height = 32;
    settings.shadowMapSize = 64;
    ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
    const scene::Image map = (*renderer)->readShadowMap();
    ASSERT_EQ(map.width, 64);
    // The box (nearer the light) is brighter than the plane around it at the map's centre.
    EXPECT_GT(map.pixel(32, 32)[0], map.pixel(2, 2)[0]);
}

TEST_F(RendererTest, OutOfRangeSettingsAreErrorsNotGlErrors) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    const auto setup = core::computeShadowSetup({.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = core::Technique::Focused});
    gl::RenderSettings settings;
    settings.shadowMapSize = 1 << 20;
    const auto r = (*renderer)->render(cam, sun, *setup, settings);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("map size"), std::string::npos);
}

TEST_F(RendererTest, CasterAboveTheFrustumStillShadowsItsCascade) {
    // The caster floats 40 m up, far above the view frustum (which reaches 19 m at that
    // depth), but between the ground it shadows and the overhead sun: every cascade
    // configuration must keep it in the split that serves that ground.
    scene::Scene s;
    scene::Mesh ground, box;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, -50}), {60, 0.5f, 60}, glm::vec3(0.8f));
    scene::addBox(box, glm::mat4(1.0f), {3, 0.5f, 3}, glm::vec3(0.8f));
    ground.computeBounds();
    box.computeBounds();
    s.meshes = {ground, box};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 40, -30})}, false}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 2, 0};
    cam.wsDirection = {0, -0.05, -1};
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 100;
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.shadowMapSize = 512;
    settings.fogDensity = 0.0f;
    for (int variant = 0; variant < 3; ++variant) {
        core::ShadowSetupInputs in{.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = core::Technique::Csm};
        in.cascades.count = 2;
        in.cascades.splits = {0.5, 20, 100};
        in.cascades.warp = variant == 1 ? core::CascadeWarp::Lispsm : core::CascadeWarp::None;
        in.cascades.stabilize = variant == 2;
        in.cascades.mapSize = settings.shadowMapSize;
        const auto setup = core::computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
        const scene::Image image = (*renderer)->readColor();
        const double under = luminanceAt(image, cam, {0, 0, -30}), away = luminanceAt(image, cam, {9, 0, -30});
        EXPECT_LT(under, 0.7 * away) << "variant " << variant << ": under " << under << ", away " << away;
    }
}
