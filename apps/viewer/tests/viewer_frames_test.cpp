// The viewer's frame loop without its window: camera moves keep held lattices (--stabilize)
// and auto's tracking; an option change starts afresh. CTest label `gl` (headless Mesa).
#include "headless_gl_test.h"
#include "test_scenes.h"
#include "timeline.h"
#include "viewer_frames.h"

#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/mesh_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

using namespace shadowkit;

namespace {

class ViewerFramesTest : public gl::testing::HeadlessGlTest {
protected:
    void SetUp() override {
        HeadlessGlTest::SetUp();
        if (IsSkipped()) return;
        forest = gl::testing::smallForest(300, 200, 32);
        auto r = gl::Renderer::create(forest);
        ASSERT_TRUE(r) << r.error();
        renderer = std::move(r).value();
        start = gl::testing::standardView(forest, "perpendicular").camera;
    }

    // Frame i of a slow walk sideways (3 cm a frame), drawn at 192 × 108.
    core::Result<frame::DrawnFrame> walk(viewer::ViewerFrames& frames, int i) {
        const core::Vec3 side = glm::normalize(glm::cross(start.wsDirection, start.wsUp));
        return frames.draw(*renderer, forest, start.wsEye + 0.03 * i * side, start.wsDirection, 192, 108, 0.0);
    }

    scene::Scene forest;
    std::unique_ptr<gl::Renderer> renderer;
    core::PerspectiveCamera start;
};

TEST_F(ViewerFramesTest, CameraMovesKeepHeldLatticesAndAnOptionChangeRefits) {
    viewer::ViewerFrames frames;
    app::StateOptions state{{"technique", {"lispsm"}}, {"map-size", {"512"}}, {"stabilize", {"true"}}};
    ASSERT_TRUE(frames.setOptions(state, forest));
    int laterRefits = 0;
    for (int i = 0; i < 10; ++i) {
        auto f = walk(frames, i);
        ASSERT_TRUE(f) << f.error();
        ASSERT_TRUE(f->frame.refits);
        if (i == 0)
            EXPECT_EQ(f->frame.refits->views, 1);
        else
            laterRefits += f->frame.refits->views;
    }
    EXPECT_LE(laterRefits, 1) << "held lattices were dropped on camera moves";
    // The panel changed an option: a cut.
    state["lispsm-weight"] = {"1.5"};
    ASSERT_TRUE(frames.setOptions(state, forest));
    auto f = walk(frames, 10);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->frame.refits->views, 1);
}

TEST_F(ViewerFramesTest, OffersAutoAndKeepsTheLastGoodOptionsOnABadOne) {
    viewer::ViewerFrames frames;
    ASSERT_TRUE(frames.setOptions({{"technique", {"auto"}}, {"texel-budget", {"1M"}}}, forest));
    auto first = walk(frames, 0);
    ASSERT_TRUE(first) << first.error();
    ASSERT_TRUE(first->frame.autoChoice);
    const core::Status bad = frames.setOptions({{"technique", {"auto"}}, {"texel-budget", {"lots"}}}, forest);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().find("--texel-budget"), std::string::npos) << bad.error();
    auto still = walk(frames, 1); // drawn with the last good options
    ASSERT_TRUE(still);
    EXPECT_TRUE(still->frame.autoChoice);
}

// Along a camera path that frames a loaded model, the viewer frames the box `render` frames
// (Timeline::prepareViews): one for the whole path, so that `render --state` draws the viewer's
// frame, and the camera does not follow a mover out and back.
TEST_F(ViewerFramesTest, APathFramingAModelWithAMoverFramesWhatRenderFrames) {
    scene::Scene model; // a 10 × 2 × 10 m block and a 1 m box circling 30 m round it: no terrain
    scene::Mesh block;
    scene::addBox(block, glm::mat4(1.0f), {5.0f, 1.0f, 5.0f}, {0.6f, 0.6f, 0.6f});
    block.computeBounds();
    scene::Mesh mover;
    scene::addBox(mover, glm::mat4(1.0f), {0.5f, 0.5f, 0.5f}, {0.8f, 0.3f, 0.2f});
    mover.computeBounds();
    model.meshes = {block, mover};
    model.batches.push_back({.mesh = 0, .worldFromObject = {glm::mat4(1.0f)}});
    model.batches.push_back({.mesh = 1, .worldFromObject = {glm::mat4(1.0f)}, .dynamic = true});
    model.tracks.push_back({.batch = 1, .instance = 0, .radius = 30.0, .speed = 2.0 * std::numbers::pi * 30.0 / 8.0});
    scene::animate(model, 0.0);
    auto modelRenderer = gl::Renderer::create(model);
    ASSERT_TRUE(modelRenderer) << modelRenderer.error();

    const app::StateOptions state{{"path", {"orbit"}}, {"map-size", {"512"}}};
    viewer::ViewerFrames frames;
    ASSERT_TRUE(frames.setOptions(state, model, 0.0));
    app::TimelineOptions timelineOptions;
    timelineOptions.path = "orbit";
    auto timeline = timelineOptions.resolve();
    ASSERT_TRUE(timeline) << timeline.error();
    scene::ViewSpec spec;
    scene::ResolvedView still = scene::resolveView(spec, model);
    ASSERT_TRUE(timeline->prepareViews(still, model, /*stillSize=*/true, /*sayFraming=*/false));
    ASSERT_FALSE(still.pathFramedBox.isEmpty());
    for (double t : {0.0, 2.0, 5.5}) {
        std::vector<uint32_t> moved;
        scene::animate(model, t, &moved);
        ASSERT_TRUE((*modelRenderer)->moveInstances(model, moved));
        auto drawn = frames.draw(**modelRenderer, model, start.wsEye, start.wsDirection, 192, 108, t);
        ASSERT_TRUE(drawn) << drawn.error();
        still.width = 192, still.height = 108;
        auto rendered = timeline->viewAt(still, model, t, /*stillSize=*/true);
        ASSERT_TRUE(rendered) << rendered.error();
        EXPECT_TRUE(drawn->frame.view.framed) << t;
        const core::Vec3 viewerEye = drawn->frame.view.camera.wsEye, renderEye = rendered->camera.wsEye;
        EXPECT_LT(glm::distance(viewerEye, renderEye), 1e-9 * glm::length(renderEye)) << t;
    }
}

} // namespace

namespace {

// The panel's lists and defaults come from the options' registration (app::choicesOf,
// app::defaultOf): the same table `render` parses.
TEST(OptionTableTest, EnumeratedOptionsListEveryChoiceAndTheLibrariesDefaults) {
    viewer::FrameOptions options;
    CLI::App app{"table"};
    options.addTo(app);
    const std::vector<std::string> techniques = app::choicesOf(app, "--technique");
    for (const core::TechniqueInfo& t : core::allTechniques())
        EXPECT_NE(std::find(techniques.begin(), techniques.end(), std::string(t.name)), techniques.end()) << t.name;
    EXPECT_EQ(techniques.back(), "auto");
    EXPECT_EQ(app::defaultOf(app, "--technique"), core::techniqueName(core::defaultTechnique()));
    EXPECT_EQ(app::choicesOf(app, "--visibility"), (std::vector<std::string>{"off", "frustum", "chc", "gpu", "auto"}));
    EXPECT_EQ(app::choicesOf(app, "--local-pass"),
              (std::vector<std::string>{"layered", "vertex-layer", "geometry", "per-face"}));
    EXPECT_EQ(app::defaultOf(app, "--map-size"), std::to_string(core::ShadowSetupInputs{}.mapSize));
    EXPECT_EQ(std::stod(app::defaultOf(app, "--tsm-focus")), core::TsmOptions{}.focusFraction);
    EXPECT_EQ(std::stod(app::defaultOf(app, "--lambda")), core::CascadeOptions{}.lambda);
    // Every choice listed parses; a number option lists none; an unknown flag is nothing.
    for (const std::string& c : app::choicesOf(app, "--cull")) {
        viewer::FrameOptions parsed;
        CLI::App one{"one"};
        parsed.addTo(one);
        EXPECT_NO_THROW(one.parse(std::vector<std::string>{"--cull=" + c})) << c;
    }
    EXPECT_TRUE(app::choicesOf(app, "--lambda").empty());
    EXPECT_TRUE(app::choicesOf(app, "--no-such-flag").empty());
}

} // namespace
