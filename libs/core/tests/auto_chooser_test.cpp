// The per-frame chooser (core/auto_chooser.h): its first frame is the full search, later frames
// track the full search's objective along a moving camera at a few set-ups a frame, it finds a
// better family after a cut, it is deterministic, and nothing seen keeps the choice.
#include "ground_receivers.h"

#include "shadowkit/core/auto_chooser.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace shadowkit;
using namespace shadowkit::core;
using core::testing::groundView;
using core::testing::kGroundHeight;
using core::testing::kGroundWidth;

namespace {

// The ground the camera sees: a grid of points of the plane y = 0 inside its frustum.
std::vector<ReceiverSample> visibleGround(const PerspectiveCamera& camera, double spacing) {
    std::vector<ReceiverSample> out;
    const Mat4 clipFromWorld = camera.clipFromWorld();
    const double reach = camera.zFar;
    for (double x = camera.wsEye.x - reach; x <= camera.wsEye.x + reach; x += spacing)
        for (double z = camera.wsEye.z - reach; z <= camera.wsEye.z + reach; z += spacing) {
            const Vec4 c = clipFromWorld * Vec4(x, 0.0, z, 1.0);
            if (c.w > 0.0 && std::abs(c.x) < c.w && std::abs(c.y) < c.w && c.z > 0.0 && c.z < c.w)
                out.push_back({Vec3(x, 0.0, z), Vec3(0.0, 1.0, 0.0)});
        }
    return out;
}

// Frame f of a path over the ground: forward 1.5 m a frame, turning and pitching slowly.
ShadowSetupInputs pathFrame(int f) {
    ShadowSetupInputs in = groundView(30.0, 70.0);
    const double yaw = glm::radians(0.6 * f), pitch = -0.05 - 0.15 * (0.5 + 0.5 * std::sin(f * 0.05));
    in.camera.wsDirection = Vec3(-std::sin(yaw), pitch, -std::cos(yaw));
    in.camera.wsEye = Vec3(0.0, 1.8 + 0.05 * f, -1.5 * f);
    in.camera.zFar = 200.0;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-600.0, -1.0, -800.0), Vec3(600.0, 20.0, 400.0));
    return in;
}

} // namespace

TEST(AutoChooserTest, TheFirstFrameIsTheFullSearchAndLaterFramesCostFourSetups) {
    const ShadowSetupInputs in = pathFrame(0);
    const auto receivers = visibleGround(in.camera, 4.0);
    AutoOptions options;
    options.texelBudget = int64_t(4) << 20;
    AutoChooser chooser(options);
    auto first = chooser.choose(in, kGroundWidth, kGroundHeight, receivers);
    auto model = SamplingErrorModel::create(in.camera, kGroundWidth, kGroundHeight, receivers);
    auto full = chooseAuto(in, options, *model);
    ASSERT_TRUE(first && full);
    EXPECT_EQ(describe(*first), describe(*full));
    EXPECT_EQ(first->objective, full->objective);
    EXPECT_EQ(chooser.candidates(), 10u); // four single maps; 2, 3, 4 cascades unwarped and warped
    EXPECT_GT(first->setupsTried, 100);
    for (int f = 1; f < 20; ++f) {
        const ShadowSetupInputs frame = pathFrame(f);
        auto next = chooser.choose(frame, kGroundWidth, kGroundHeight, visibleGround(frame.camera, 4.0));
        ASSERT_TRUE(next);
        EXPECT_LE(next->setupsTried, 4);
        EXPECT_LE(next->predicted.samples, options.searchSamples);
        EXPECT_EQ(next->inputs.camera.wsEye, frame.camera.wsEye);
    }
    chooser.reset();
    auto again = chooser.choose(in, kGroundWidth, kGroundHeight, receivers);
    ASSERT_TRUE(again);
    EXPECT_EQ(describe(*again), describe(*full)); // after a reset, the full search again
}

TEST(AutoChooserTest, TracksTheFullSearchAlongAPath) {
    for (const int cascades : {1, 0}) {
        AutoOptions options;
        options.texelBudget = int64_t(4) << 20;
        options.cascades = cascades;
        options.searchSamples = 100000; // every receiver, so both are judged on the same samples
        AutoChooser chooser(options);
        std::vector<double> ratios;
        for (int f = 0; f < 120; ++f) {
            const ShadowSetupInputs in = pathFrame(f);
            const auto receivers = visibleGround(in.camera, 4.0);
            auto tracked = chooser.choose(in, kGroundWidth, kGroundHeight, receivers);
            auto model = SamplingErrorModel::create(in.camera, kGroundWidth, kGroundHeight, receivers);
            auto best = chooseAuto(in, options, *model);
            ASSERT_TRUE(tracked && best);
            ratios.push_back(tracked->objective / best->objective); // below 1 where tracking beats the grid's bracket
        }
        std::sort(ratios.begin(), ratios.end());
        double mean = 0.0;
        for (const double r : ratios) mean += r / double(ratios.size());
        // The figures of docs/error-driven.md. Parameters frozen at the first frame's (the step's probe never
        // kept, families still switching) gave a mean of 1.06, a p90 of 1.12-1.15 and a worst
        // frame of 1.34 on this path.
        std::printf("tracked / full search objective, %s: mean %.4f p90 %.4f max %.4f\n",
                    cascades == 1 ? "one map" : "any count", mean, ratios[108], ratios.back());
        EXPECT_LE(mean, 1.03) << "cascades " << cascades;
        EXPECT_LE(ratios[108], 1.08) << "cascades " << cascades;
        EXPECT_LE(ratios.back(), 1.2) << "cascades " << cascades;
    }
}

// A cut to a view another family suits better, without reset(): one candidate a frame in turn
// catches up, so within a few rounds the choice is as good as the full search's.
TEST(AutoChooserTest, FindsTheBetterFamilyAfterACut) {
    AutoOptions options;
    options.texelBudget = int64_t(4) << 20;
    AutoChooser chooser(options);
    const ShadowSetupInputs ground = pathFrame(0);
    ASSERT_TRUE(chooser.choose(ground, kGroundWidth, kGroundHeight, visibleGround(ground.camera, 4.0)));
    ShadowSetupInputs aerial = ground;
    aerial.camera.wsEye = Vec3(0.0, 150.0, 0.0);
    aerial.camera.wsDirection = glm::normalize(Vec3(0.0, -1.0, -0.05)); // straight down: PSM's case
    const auto receivers = visibleGround(aerial.camera, 4.0);
    auto model = SamplingErrorModel::create(aerial.camera, kGroundWidth, kGroundHeight, receivers);
    auto best = chooseAuto(aerial, options, *model);
    auto before = chooseAuto(
        ground, options,
        *SamplingErrorModel::create(ground.camera, kGroundWidth, kGroundHeight, visibleGround(ground.camera, 4.0)));
    ASSERT_TRUE(best && before);
    ASSERT_NE(best->inputs.technique, before->inputs.technique) << "the cut must change the family";
    double objective = 0.0;
    std::string chosen;
    for (size_t f = 0; f < 3 * chooser.candidates(); ++f) {
        auto next = chooser.choose(aerial, kGroundWidth, kGroundHeight, receivers);
        ASSERT_TRUE(next);
        objective = next->objective;
        chosen = describe(*next);
    }
    auto subsampled = model->subsampled(options.searchSamples);
    auto bestThere = chooseAuto(aerial, options, subsampled);
    EXPECT_LE(objective, 1.1 * bestThere->objective) << chosen << " against " << describe(*bestThere);
}

TEST(AutoChooserTest, IsDeterministicAndKeepsItsChoiceWhenNothingIsSeen) {
    AutoOptions options;
    options.texelBudget = int64_t(4) << 20;
    AutoChooser a(options), b(options);
    for (int f = 0; f < 30; ++f) {
        const ShadowSetupInputs in = pathFrame(f);
        const auto receivers = visibleGround(in.camera, 4.0);
        auto ca = a.choose(in, kGroundWidth, kGroundHeight, receivers),
             cb = b.choose(in, kGroundWidth, kGroundHeight, receivers);
        ASSERT_TRUE(ca && cb);
        EXPECT_EQ(describe(*ca), describe(*cb));
        EXPECT_EQ(ca->objective, cb->objective);
    }
    const ShadowSetupInputs in = pathFrame(30);
    auto seen = a.choose(in, kGroundWidth, kGroundHeight, visibleGround(in.camera, 4.0));
    auto unseen = a.choose(pathFrame(31), kGroundWidth, kGroundHeight, {});
    ASSERT_TRUE(seen && unseen);
    EXPECT_EQ(describe(*unseen), describe(*seen));
    EXPECT_EQ(unseen->inputs.camera.wsEye, pathFrame(31).camera.wsEye);
    EXPECT_EQ(unseen->setupsTried, 0);
    // Bad options and inputs are errors naming the field, on any frame.
    AutoOptions bad = options;
    bad.searchSamples = 3;
    EXPECT_EQ(AutoChooser(bad).choose(in, kGroundWidth, kGroundHeight, {}).errorInfo().field, "auto.search_samples");
    ShadowSetupInputs badInputs = in;
    badInputs.mapSize = 3;
    EXPECT_EQ(a.choose(badInputs, kGroundWidth, kGroundHeight, {}).errorInfo().field, "map_size");
}
