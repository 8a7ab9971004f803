// A user's animated glTF measured as it plays: tests/data/turning_crane.gltf, a mast on a 24 m
// plate with a jib 5 m up that turns about the mast once every 8 s (glTF animation 'Turn',
// LINEAR rotation keys every 90°), its own camera 16 m up and back looking 45° down towards −z,
// and its own sun travelling along (1, −1, 0). At t = 0 the arm points +x, at t = 2 s −z: its
// shadow, thrown 5 m towards +x, lies on the plate in another place. The renderer and the ray
// tracer must both see the arm where the animation puts it: a renderer left at the rest pose
// would draw the old shadow against the new truth. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <vector>

using namespace shadowkit;

namespace {

class AnimatedFileEvalTest : public gl::testing::HeadlessGlTest {};

// The pixels the truth has in shadow (rendered right or wrong).
std::vector<bool> trulyShadowed(const std::vector<eval::PixelClass>& classes) {
    std::vector<bool> out(classes.size());
    for (size_t i = 0; i < classes.size(); ++i)
        out[i] = classes[i] == eval::PixelClass::ShadowCorrect || classes[i] == eval::PixelClass::FalseLit;
    return out;
}

// The file's own camera under its own sun, a focused map, at 240 × 160 (the camera's aspect, 1.5).
core::Result<measure::Measurement> measureThroughItsCamera(const scene::Scene& file, measure::Measurer& measurer,
                                                           gl::Culling culling = gl::RenderSettings{}.culling) {
    const auto view = scene::fileView(file, "", gl::kMaxLocalLightsPerKind);
    if (!view) return view.errorInfo();
    gl::RenderSettings settings;
    settings.width = 240;
    settings.height = 160;
    settings.culling = culling;
    return measurer.measure({.camera = view->camera,
                             .light = view->light,
                             .wsSceneBounds = measurer.renderer().wsSceneBounds(),
                             .technique = core::Technique::Focused},
                            settings);
}

} // namespace

TEST_F(AnimatedFileEvalTest, TheTurningArmsShadowMovesAndTheMapFollowsIt) {
    const auto file = std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "turning_crane.gltf";
    auto crane = scene::loadScene(file);
    ASSERT_TRUE(crane) << crane.error();
    ASSERT_EQ(crane->tracks.size(), 1u) << "the arm, below the turning jib";
    auto measurer = measure::Measurer::create(*crane);
    ASSERT_TRUE(measurer) << measurer.error();

    std::vector<std::vector<bool>> shadowAt;
    for (double t : {0.0, 2.0}) {
        std::vector<uint32_t> moved;
        scene::animate(*crane, t, &moved);
        ASSERT_EQ(moved.size(), 1u);
        ASSERT_TRUE((*measurer)->moveInstances(*crane, moved));
        auto measured = measureThroughItsCamera(*crane, **measurer);
        ASSERT_TRUE(measured) << measured.error();
        EXPECT_LT(measured->figures().wrongPct, 1.0) << "t = " << t;
        shadowAt.push_back(trulyShadowed(measured->comparison.classes));
    }
    // The arm's shadow moved: pixels in shadow at one time and lit at the other, both ways.
    int64_t left = 0, arrived = 0;
    for (size_t i = 0; i < shadowAt[0].size(); ++i) {
        left += shadowAt[0][i] && !shadowAt[1][i];
        arrived += !shadowAt[0][i] && shadowAt[1][i];
    }
    EXPECT_GT(left, 50);
    EXPECT_GT(arrived, 50);
}

// A skinned file posed at the time asked (scene::LoadOptions::poseSeconds):
// tests/data/bending_arm.gltf, a 6 m arm 5 m over the plate whose forearm (skinned to the elbow
// joint, 3 m out) turns from +x at t = 0 to −z at t = 1 s, under the crane's camera and sun. Both
// the renderer and the ray tracer are built from the posed mesh, so each pose's shadows are right,
// and the forearm's shadow lies elsewhere in the two poses.
TEST_F(AnimatedFileEvalTest, ASkinnedArmPosedAtTwoTimesCastsEachPosesShadow) {
    const auto file = std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "bending_arm.gltf";
    std::vector<std::vector<bool>> shadowAt;
    for (double t : {0.0, 1.0}) {
        auto arm = scene::loadScene(file, {.poseSeconds = t});
        ASSERT_TRUE(arm) << arm.error();
        auto measurer = measure::Measurer::create(*arm);
        ASSERT_TRUE(measurer) << measurer.error();
        auto measured = measureThroughItsCamera(*arm, **measurer);
        ASSERT_TRUE(measured) << measured.error();
        EXPECT_LT(measured->figures().wrongPct, 1.0) << "t = " << t;
        shadowAt.push_back(trulyShadowed(measured->comparison.classes));
    }
    ASSERT_EQ(shadowAt[0].size(), shadowAt[1].size());
    int64_t left = 0, arrived = 0;
    for (size_t i = 0; i < shadowAt[0].size(); ++i) {
        left += shadowAt[0][i] && !shadowAt[1][i];
        arrived += !shadowAt[0][i] && shadowAt[1][i];
    }
    EXPECT_GT(left, 20) << "the forearm's shadow at t = 0 is lit at t = 1";
    EXPECT_GT(arrived, 20) << "and its shadow at t = 1 was lit at t = 0";
    std::printf("bending arm: %lld pixels left the shadow, %lld reached it\n", static_cast<long long>(left),
                static_cast<long long>(arrived));
}

// The same arm played: loaded in its first pose, then posed at t = 1 s by scene::animate, the
// renderer and the ray tracer reshaping the forearm as the scene tells them. Each frame must be
// the frame a fresh load at that time gives — pixel for pixel, rendered and true (a renderer or
// ray tracer left with the first pose would keep the forearm's old shadow: 149 and 108 pixels
// apart, above) — with every culling path, whose boxes and lists the new shape moves.
TEST_F(AnimatedFileEvalTest, ASkinnedArmPlayedToATimeCastsWhatAFreshLoadAtThatTimeCasts) {
    const auto file = std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "bending_arm.gltf";
    auto played = scene::loadScene(file, {.poseSeconds = 0.0});
    ASSERT_TRUE(played) << played.error();
    ASSERT_EQ(played->deformations.size(), 1u) << "the skinned forearm";
    auto measurer = measure::Measurer::create(*played);
    ASSERT_TRUE(measurer) << measurer.error();
    for (const auto& [t, culling] : {std::pair{0.0, gl::Culling::Occlusion}, std::pair{1.0, gl::Culling::Occlusion},
                                     std::pair{0.5, gl::Culling::Gpu}, std::pair{0.8, gl::Culling::Frustum}}) {
        SCOPED_TRACE("culling " + std::to_string(int(culling)));
        std::vector<uint32_t> moved;
        scene::animate(*played, t, &moved);
        ASSERT_FALSE(moved.empty()) << "the reshaped forearm's instance";
        ASSERT_TRUE((*measurer)->moveInstances(*played, moved));
        auto frame = measureThroughItsCamera(*played, **measurer, culling);
        ASSERT_TRUE(frame) << frame.error();

        auto fresh = scene::loadScene(file, {.poseSeconds = t});
        ASSERT_TRUE(fresh) << fresh.error();
        auto freshMeasurer = measure::Measurer::create(*fresh);
        ASSERT_TRUE(freshMeasurer) << freshMeasurer.error();
        auto expected = measureThroughItsCamera(*fresh, **freshMeasurer, gl::Culling::Off);
        ASSERT_TRUE(expected) << expected.error();

        const auto& got = frame->comparison.classes;
        const auto& want = expected->comparison.classes;
        ASSERT_EQ(got.size(), want.size());
        int64_t differ = 0;
        for (size_t i = 0; i < got.size(); ++i) differ += got[i] != want[i];
        EXPECT_EQ(differ, 0) << "t = " << t << ": pixels classed otherwise than a fresh load's";
        EXPECT_LT(frame->figures().wrongPct, 1.0) << "t = " << t;
    }
}
