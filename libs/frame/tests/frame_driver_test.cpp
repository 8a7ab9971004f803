// The frame driver: its phases in order and what it keeps between frames. CTest label `gl`
// (headless Mesa); the configuration checks need no GL.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/core/visible_depth.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/read_backs.h"

#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class FrameDriverTest : public gl::testing::HeadlessGlTest {
protected:
    void SetUp() override {
        HeadlessGlTest::SetUp();
        if (IsSkipped()) return;
        forest = gl::testing::smallForest(300, 200, 32);
        view = gl::testing::standardView(forest, "perpendicular");
        view.width = 192, view.height = 108;
        view.camera.aspect = 16.0 / 9.0;
        view.camera.zFar = 150.0;
        auto r = gl::Renderer::create(forest);
        ASSERT_TRUE(r) << r.error();
        renderer = std::move(r).value();
    }

    static frame::FrameConfig config(core::Technique technique) {
        frame::FrameConfig c;
        c.technique.technique = technique;
        c.technique.mapSize = 512;
        return c;
    }

    // `view` slid `metres` sideways and turned by `degrees` about the vertical.
    scene::ResolvedView moved(double metres, double degrees) const {
        scene::ResolvedView v = view;
        const core::Vec3 side = glm::normalize(glm::cross(v.camera.wsDirection, v.camera.wsUp));
        v.camera.wsEye += metres * side;
        const double a = glm::radians(degrees);
        const core::Vec3 d = v.camera.wsDirection;
        v.camera.wsDirection = glm::normalize(
            core::Vec3(d.x * std::cos(a) - d.z * std::sin(a), d.y, d.x * std::sin(a) + d.z * std::cos(a)));
        return v;
    }

    scene::Scene forest;
    scene::ResolvedView view;
    std::unique_ptr<gl::Renderer> renderer;
};

TEST_F(FrameDriverTest, HeldLatticesAreKeptAcrossCameraMovesAndRefittedAfterACut) {
    frame::FrameConfig c = config(core::Technique::Lispsm);
    c.heldLattices = core::HysteresisOptions{};
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver) << driver.error();
    int laterRefits = 0;
    for (int i = 0; i < 12; ++i) { // a slow walk: 3 cm and 0.05° a frame
        auto f = driver->prepare(*renderer, moved(0.03 * i, 0.05 * i));
        ASSERT_TRUE(f) << f.error();
        ASSERT_TRUE(f->refits);
        if (i == 0)
            EXPECT_EQ(f->refits->views, 1) << "the first frame is the fresh fit";
        else
            laterRefits += f->refits->views;
    }
    // A driver dropped on every camera move (the viewer before the frame driver) refits 11 times.
    EXPECT_LE(laterRefits, 1);
    driver->reset();
    auto afterCut = driver->prepare(*renderer, moved(0.36, 0.6));
    ASSERT_TRUE(afterCut);
    EXPECT_EQ(afterCut->refits->views, 1);
    // A set-up computed afresh each frame has no refits to report.
    auto fresh = frame::FrameDriver::create(config(core::Technique::Lispsm));
    ASSERT_TRUE(fresh);
    EXPECT_FALSE(fresh->prepare(*renderer, view)->refits);
}

TEST_F(FrameDriverTest, TheVisibleDepthIsMeasuredFromThisFrameBeforeTheSetUp) {
    frame::FrameConfig c = config(core::Technique::Lispsm);
    auto plain = frame::FrameDriver::create(c);
    ASSERT_TRUE(plain);
    int64_t readBacks = gl::readBacksMade();
    auto without = plain->prepare(*renderer, view);
    ASSERT_TRUE(without);
    EXPECT_FALSE(without->inputs.visibleDepth);
    EXPECT_EQ(without->prePasses.submissions, 0);
    EXPECT_EQ(gl::readBacksMade() - readBacks, 0) << "what GL was asked to read back";

    c.visibleDepthFromFrame = true;
    auto measuring = frame::FrameDriver::create(c);
    ASSERT_TRUE(measuring);
    readBacks = gl::readBacksMade();
    auto with = measuring->prepare(*renderer, view);
    ASSERT_TRUE(with) << with.error();
    ASSERT_TRUE(with->inputs.visibleDepth);
    EXPECT_EQ(with->prePasses.submissions, 1);
    EXPECT_EQ(with->prePasses.readBacks, 1);
    EXPECT_EQ(gl::readBacksMade() - readBacks, 1) << "what GL was asked to read back";
    // The range of what the camera sees, within its planes and narrower than them (the view
    // looks over the forest, whose far edge is nearer than the far plane here or not).
    const auto range = renderer->visibleDepth(view.camera, view.light, without->setup, without->settings);
    ASSERT_TRUE(range && *range);
    EXPECT_EQ(*with->inputs.visibleDepth, **range);
    EXPECT_GE(with->inputs.visibleDepth->x, view.camera.zNear);
    EXPECT_LE(with->inputs.visibleDepth->y, view.camera.zFar);
    // And the set-up took it: LiSPSM's n follows the measured range, so the matrices differ.
    EXPECT_NE(with->setup.views[0].clipFromWorld, without->setup.views[0].clipFromWorld);
}

TEST_F(FrameDriverTest, AFrameThatMeasuresItsVisibleDepthDrawsOneCameraPrePass) {
    // The range's pre-pass is the frame's own: with CHC++ or a receiver mask the frame needs a
    // pre-pass anyway, and one is drawn, not two; the frame equals one drawn without the reuse.
    for (const gl::Culling culling : {gl::Culling::Occlusion, gl::Culling::Frustum}) {
        frame::FrameConfig c = config(core::Technique::Lispsm);
        c.render.culling = culling;
        c.render.receiverMask = true;
        c.visibleDepthFromFrame = true;
        auto driver = frame::FrameDriver::create(c);
        ASSERT_TRUE(driver) << driver.error();
        const int before = renderer->cameraPrePassesDrawn();
        auto drawn = driver->draw(*renderer, view);
        ASSERT_TRUE(drawn) << drawn.error();
        EXPECT_EQ(renderer->cameraPrePassesDrawn() - before, 1) << gl::cullingName(culling);
        const scene::Image reused = renderer->readColor();
        // The same frame, its pre-pass drawn afresh (the set-up given, nothing measured first).
        ASSERT_TRUE(renderer->render(view.camera, view.light, drawn->frame.setup, drawn->frame.settings));
        EXPECT_EQ(renderer->cameraPrePassesDrawn() - before, 2);
        EXPECT_EQ(renderer->readColor().rgba, reused.rgba) << gl::cullingName(culling);
    }
}

TEST_F(FrameDriverTest, AutosReceiverReadBackDrawsNoShadowPass) {
    frame::FrameConfig c = config(core::Technique::Tsm);
    const auto inputs = frame::FrameDriver::create(c)->prepare(*renderer, view);
    ASSERT_TRUE(inputs);
    ASSERT_TRUE(renderer->render(view.camera, view.light, inputs->setup, inputs->settings));
    ASSERT_GT(renderer->lastShadowPass().triangles, 0u);
    auto receivers = frame::readReceivers(*renderer, inputs->inputs, inputs->settings);
    ASSERT_TRUE(receivers) << receivers.error();
    EXPECT_EQ(renderer->lastShadowPass().triangles, 0u);
    EXPECT_EQ(renderer->lastShadowPass().drawCalls, 0);
    // The surfaces are there all the same: depth and normals where the forest is.
    const auto range = core::visibleDepthRange(receivers->viewDepth);
    ASSERT_TRUE(range);
    EXPECT_GT(range->y, range->x);
    for (const float term : receivers->shadowTerm) EXPECT_EQ(term, 1.0f);
}

TEST_F(FrameDriverTest, WithAutoTheVisibleDepthComesFromTheReceiversReadBack) {
    frame::FrameConfig c = config(core::Technique::Tsm);
    c.automatic = core::AutoOptions{};
    c.automatic->texelBudget = 512 * 512;
    c.visibleDepthFromFrame = true;
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver);
    const int64_t readBacks = gl::readBacksMade();
    auto f = driver->prepare(*renderer, view);
    ASSERT_TRUE(f) << f.error();
    // One read-back serves both: not a pre-pass for the range and another for the receivers —
    // by the driver's count and by what GL was asked.
    EXPECT_EQ(f->prePasses.submissions, 1);
    EXPECT_EQ(f->prePasses.readBacks, 1);
    EXPECT_EQ(gl::readBacksMade() - readBacks, 1);
    ASSERT_TRUE(f->inputs.visibleDepth);
    // The low-resolution range against the frame's own (a full-resolution camera pre-pass):
    // it lies within it (up to where a coarser pixel's centre falls), short of it by little.
    frame::FrameConfig plain = config(core::Technique::Tsm);
    plain.visibleDepthFromFrame = true;
    auto full = frame::FrameDriver::create(plain)->prepare(*renderer, view);
    ASSERT_TRUE(full && full->inputs.visibleDepth);
    const core::Vec2 lo = *f->inputs.visibleDepth, hi = *full->inputs.visibleDepth;
    EXPECT_GE(lo.x, 0.99 * hi.x);
    EXPECT_LE(lo.y, 1.01 * hi.y);
    EXPECT_LT(lo.x - hi.x, 0.05 * hi.x + 0.1);
    EXPECT_GT(lo.y, 0.95 * hi.y);
}

TEST_F(FrameDriverTest, BiasOverridesAreResolvedForTheTechniqueAutoChose) {
    frame::FrameConfig c = config(core::Technique::Tsm);
    c.automatic = core::AutoOptions{};
    c.automatic->texelBudget = 512 * 512;
    c.bias.slope = 0.75;
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver) << driver.error();
    auto f = driver->prepare(*renderer, view);
    ASSERT_TRUE(f) << f.error();
    ASSERT_TRUE(f->autoChoice);
    EXPECT_EQ(f->prePasses.submissions, 1); // the receivers' read-back
    EXPECT_EQ(f->setup.technique, f->autoChoice->inputs.technique);
    ASSERT_TRUE(f->settings.bias);
    core::BiasSettings expected =
        core::recommendedBias(f->inputs.technique, core::depthLayoutFor(f->inputs), f->settings.filter);
    expected.slope = 0.75;
    EXPECT_EQ(f->settings.bias->slope, expected.slope);
    EXPECT_EQ(f->settings.bias->constant, expected.constant);
    EXPECT_EQ(f->settings.bias->normalOffset, expected.normalOffset);
    EXPECT_EQ(f->settings.bias->cull, expected.cull);
    // Nothing overridden: the renderer's own recommendation (gl::biasFor), not a baked copy.
    c.bias = {};
    auto plain = frame::FrameDriver::create(c);
    ASSERT_TRUE(plain);
    EXPECT_FALSE(plain->prepare(*renderer, view)->settings.bias);
}

TEST_F(FrameDriverTest, ADrawnFrameIsItsPreparedFrameRendered) {
    frame::FrameConfig c = config(core::Technique::Csm);
    c.technique.cascades.count = 3;
    c.render.culling = gl::Culling::Occlusion;
    c.render.receiverMask = true;
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver);
    auto drawn = driver->draw(*renderer, view);
    ASSERT_TRUE(drawn) << drawn.error();
    EXPECT_EQ(drawn->frame.settings.width, view.width);
    EXPECT_EQ(drawn->frame.setup.views.size(), 3u);
    EXPECT_GT(drawn->stats.shadow.triangles, 0u);
    const scene::Image byDriver = renderer->readColor();
    const frame::PreparedFrame& f = drawn->frame;
    ASSERT_TRUE(renderer->render(f.view.camera, f.view.light, f.setup, f.settings));
    EXPECT_EQ(renderer->readColor().rgba, byDriver.rgba);
}

TEST_F(FrameDriverTest, TheViewsLampsAndTheConfiguredOnesAreSetUp) {
    frame::FrameConfig c = config(core::Technique::Tsm);
    c.lights.push_back(core::PointLight{.wsPosition = view.camera.wsEye + core::Vec3(0, 3, 0), .range = 20.0});
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver);
    ASSERT_TRUE(driver->prepare(*renderer, view));
    EXPECT_EQ(renderer->localLights().points.size(), view.points.size() + 1);
    // Too many lights: one error naming the field, and nothing drawn.
    for (int i = 0; i < gl::kMaxLocalLightsPerKind; ++i) c.lights.push_back(c.lights.front());
    auto crowded = frame::FrameDriver::create(c);
    ASSERT_TRUE(crowded);
    auto f = crowded->prepare(*renderer, view);
    ASSERT_FALSE(f);
    EXPECT_EQ(f.errorInfo().field, "lights");
}

TEST_F(FrameDriverTest, AViewsSunSizeTakesThePlaceOfTheConfiguredOneAndSoftensTheShadows) {
    frame::FrameConfig c = config(core::Technique::Tsm);
    c.render.filter = {core::ShadowFilter::Pcss, 16, 8.0f};
    c.render.sunAngleDegrees = 0.0; // a point-like sun: PCSS is the hard test
    auto driver = frame::FrameDriver::create(c);
    ASSERT_TRUE(driver);
    // Penumbra pixels of a prepared frame's shadow term.
    auto softPixels = [&](const frame::PreparedFrame& f) {
        auto raster = renderer->renderEvalBuffers(f.inputs.camera, f.inputs.light, f.setup, f.settings);
        EXPECT_TRUE(raster) << raster.error();
        size_t n = 0;
        for (const float t : raster->shadowTerm) n += t > 0.05f && t < 0.95f;
        return n;
    };
    auto point = driver->prepare(*renderer, view);
    ASSERT_TRUE(point) << point.error();
    EXPECT_EQ(point->settings.sunAngleDegrees, 0.0);
    scene::ResolvedView sized = view; // a path's sun key or a view's "sun_angle" of 3°
    sized.sunAngleDegrees = 3.0;
    auto soft = driver->prepare(*renderer, sized);
    ASSERT_TRUE(soft) << soft.error();
    EXPECT_EQ(soft->settings.sunAngleDegrees, 3.0);
    EXPECT_GT(softPixels(*soft), 2 * softPixels(*point) + 50);
    // The driver keeps no size between frames: the next view without one is the configuration's.
    EXPECT_EQ(driver->prepare(*renderer, view)->settings.sunAngleDegrees, 0.0);
}

TEST(FrameConfigTest, BadOptionsAreRefusedNamingTheirField) {
    auto fieldOf = [](const frame::FrameConfig& c) {
        const core::Status s = c.check();
        return s ? std::string() : s.errorInfo().field;
    };
    frame::FrameConfig c;
    EXPECT_EQ(fieldOf(c), "");
    c.technique.lispsm.weight = -1.0;
    EXPECT_EQ(fieldOf(c), "lispsm.weight");
    c = {};
    c.fogDensity = -0.1;
    EXPECT_EQ(fieldOf(c), "fog");
    c = {};
    c.localMapSize = 3;
    EXPECT_EQ(fieldOf(c), "local_map_size");
    EXPECT_EQ(c.check().error().rfind("local_map_size: must be in [", 0), 0u) << c.check().error();
    c = {};
    c.bias.normalOffset = std::nan("");
    EXPECT_EQ(fieldOf(c), "bias.normal_offset");
    c = {};
    c.render.blur.radiusPixels = 0.0f;
    EXPECT_EQ(fieldOf(c), "blur.radius");
    c = {};
    c.automatic = core::AutoOptions{};
    c.automatic->texelBudget = 0;
    EXPECT_EQ(fieldOf(c), "auto.texel_budget");
    EXPECT_FALSE(frame::FrameDriver::create(c));
}

} // namespace
