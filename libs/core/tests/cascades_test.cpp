#include "setup_configs.h"
#include "shadowkit/core/cascade_splits.h"
#include "shadowkit/core/cascades.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit::core;

TEST(CascadeSplitsTest, MonotonicFromNearToFarForEveryCountAndLambda) {
    for (int n = 1; n <= 8; ++n)
        for (double lambda : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const auto z = practicalSplits(0.1, 1500.0, n, lambda);
            ASSERT_EQ(z.size(), size_t(n) + 1);
            EXPECT_EQ(z.front(), 0.1);
            EXPECT_EQ(z.back(), 1500.0);
            for (size_t i = 1; i < z.size(); ++i) EXPECT_GT(z[i], z[i - 1]) << n << " " << lambda;
        }
}

TEST(CascadeSplitsTest, LambdaZeroIsUniformAndOneIsLogarithmic) {
    const auto uniform = practicalSplits(1, 101, 4, 0.0);
    for (int i = 0; i <= 4; ++i) EXPECT_NEAR(uniform[size_t(i)], 1 + 25.0 * i, 1e-9);
    const auto logarithmic = practicalSplits(1, 10000, 4, 1.0);
    for (int i = 0; i <= 4; ++i) EXPECT_NEAR(logarithmic[size_t(i)], std::pow(10.0, i), 1e-9);
    // In between: each split between the two schemes.
    const auto half = practicalSplits(1, 10000, 4, 0.5);
    const auto u = practicalSplits(1, 10000, 4, 0.0);
    for (int i = 1; i < 4; ++i) {
        EXPECT_GT(half[size_t(i)], logarithmic[size_t(i)]);
        EXPECT_LT(half[size_t(i)], u[size_t(i)]);
    }
}

namespace {

ShadowSetupInputs cascadedView() {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-512, 0, -512), Vec3(512, 30, 512));
    in.camera.wsEye = Vec3(10.3, 3.1, 20.7);
    in.camera.wsDirection = Vec3(0.3, -0.1, -1);
    in.camera.zNear = 0.5;
    in.camera.zFar = 400;
    in.light = DirectionalLight::fromSunAngles(35, 120).value();
    in.technique = Technique::Csm;
    return in;
}

Vec2 texelOf(const ShadowView& v, const Vec3& ws, int mapSize) {
    const Vec4 c = v.clipFromWorld * Vec4(ws, 1.0);
    return (Vec2(c) / c.w * 0.5 + 0.5) * double(mapSize);
}

} // namespace

TEST(CascadesTest, OneViewPerSplitCoveringNearToFarWithTheBlendBandOverlapping) {
    ShadowSetupInputs in = cascadedView();
    in.cascades.blendBand = 0.1;
    const auto setup = computeShadowSetup(in);
    ASSERT_TRUE(setup);
    ASSERT_EQ(setup->views.size(), 4u);
    EXPECT_EQ(setup->views.front().split->x, 0.5);
    EXPECT_EQ(setup->views.back().split->y, 400.0);
    for (size_t i = 1; i < 4; ++i) {
        const Vec2 prev = *setup->views[i - 1].split, cur = *setup->views[i].split;
        // Overlaps the previous split by 10 % of that split's own range (its range without
        // the band it reaches back over itself, so at most 10 % of its extended range).
        EXPECT_LT(cur.x, prev.y);
        EXPECT_LE(prev.y - cur.x, 0.1 * (prev.y - prev.x) + 1e-9);
        EXPECT_GT(cur.y, prev.y);
    }
}

TEST(CascadesTest, VisibleDepthPlacesTheSplitsOverWhatIsSeenAndKeepsNearToFarCovered) {
    ShadowSetupInputs in = cascadedView();
    in.visibleDepth = Vec2(6.0, 120.0);
    const auto setup = computeShadowSetup(in);
    ASSERT_TRUE(setup);
    ASSERT_EQ(setup->views.size(), 4u);
    // The ends stay at the planes, so every fragment still has a map; the inner splits are
    // the practical scheme over [6, 120] m (Lauritzen et al. 2011), not over [0.5, 400] m.
    EXPECT_EQ(setup->views.front().split->x, 0.5);
    EXPECT_EQ(setup->views.back().split->y, 400.0);
    const SplitDistances visible = practicalSplits(6.0, 120.0, 4, in.cascades.lambda);
    for (size_t i = 1; i < 4; ++i) {
        EXPECT_NEAR(setup->views[i].split->x, visible[i], 1e-9);
        EXPECT_NEAR(setup->views[i - 1].split->y, visible[i], 1e-9);
        EXPECT_GT(visible[i], 6.0);
        EXPECT_LT(visible[i], 120.0);
    }
    // The focus body is never narrowed: B is the one without a visible range.
    in.visibleDepth.reset();
    const ConvexBody::Points without = computeShadowSetup(in)->body.vertices(), with = setup->body.vertices();
    ASSERT_EQ(without.size(), with.size());
    for (size_t i = 0; i < with.size(); ++i) EXPECT_EQ(without[i], with[i]);
    // Explicit splits win over the visible range.
    in.visibleDepth = Vec2(6.0, 120.0);
    in.cascades.splits = {0.5, 10, 50, 150, 400};
    const auto explicitSplits = computeShadowSetup(in);
    ASSERT_TRUE(explicitSplits);
    EXPECT_EQ(explicitSplits->views[1].split->x, 10.0);
}

TEST(CascadesTest, StabilisedSplitsMoveByWholeTexelsUnderCameraTranslation) {
    ShadowSetupInputs in = cascadedView();
    in.cascades.stabilize = true;
    in.mapSize = 1024;
    const auto before = computeShadowSetup(in);
    ASSERT_TRUE(before);
    for (const Vec3 step : {Vec3(0.37, 0.0, -0.21), Vec3(-3.3, 0.5, 1.9), Vec3(0.01, 0.0, 0.002)}) {
        ShadowSetupInputs moved = in;
        moved.camera.wsEye += step;
        const auto after = computeShadowSetup(moved);
        ASSERT_TRUE(after);
        for (size_t i = 0; i < before->views.size(); ++i) {
            // Same texel size, and a fixed world point's texel position changes by an integer.
            EXPECT_DOUBLE_EQ(before->views[i].clipFromWorld[0][0], after->views[i].clipFromWorld[0][0]);
            const Vec3 probe = in.camera.wsEye + 0.5 * (before->views[i].split->x + before->views[i].split->y) *
                                                     glm::normalize(in.camera.wsDirection);
            const Vec2 d = texelOf(after->views[i], probe, 1024) - texelOf(before->views[i], probe, 1024);
            EXPECT_NEAR(d.x, std::round(d.x), 1e-6) << "split " << i;
            EXPECT_NEAR(d.y, std::round(d.y), 1e-6) << "split " << i;
        }
    }
    // Rotation does not change the texel size either (the extent is a bounding sphere).
    ShadowSetupInputs turned = in;
    turned.camera.wsDirection = Vec3(-0.8, -0.1, -0.4);
    const auto rotated = computeShadowSetup(turned);
    for (size_t i = 0; i < before->views.size(); ++i)
        EXPECT_DOUBLE_EQ(before->views[i].clipFromWorld[0][0], rotated->views[i].clipFromWorld[0][0]);
}

TEST(CascadesTest, UnstabilisedSplitsDoSwim) {
    // The control: without stabilisation the same translation moves texels by fractions.
    ShadowSetupInputs in = cascadedView();
    const auto before = computeShadowSetup(in);
    in.camera.wsEye += Vec3(0.37, 0.0, -0.21);
    const auto after = computeShadowSetup(in);
    const Vec3 probe(20, 0, -30);
    const Vec2 d = texelOf(after->views[0], probe, 2048) - texelOf(before->views[0], probe, 2048);
    EXPECT_GT(std::abs(d.x - std::round(d.x)) + std::abs(d.y - std::round(d.y)), 1e-3);
}

TEST(CascadesTest, ExplicitSplitsAndBadOptionsAreChecked) {
    ShadowSetupInputs in = cascadedView();
    in.cascades.count = 3;
    in.cascades.splits = {0.5, 10, 60, 400};
    const auto setup = computeShadowSetup(in);
    ASSERT_TRUE(setup);
    EXPECT_EQ(setup->views[1].split->x, 10.0);
    EXPECT_EQ(setup->views[1].split->y, 60.0);
    in.cascades.splits = {0.5, 60, 10, 400};
    EXPECT_FALSE(computeShadowSetup(in));
    in.cascades.splits = {1, 10, 60, 400};
    EXPECT_FALSE(computeShadowSetup(in));
    in.cascades.splits.clear();
    in.cascades.count = 9;
    EXPECT_FALSE(computeShadowSetup(in));
    in.cascades.count = 4;
    in.cascades.stabilize = true;
    in.cascades.warp = CascadeWarp::Lispsm;
    const auto both = computeShadowSetup(in);
    ASSERT_FALSE(both);
    EXPECT_NE(both.error().find("stabilisation"), std::string::npos);
    in.cascades.warp = CascadeWarp::None;
    in.mapSize = 1023;
    EXPECT_FALSE(computeShadowSetup(in)); // texel snapping needs an even map size
}

TEST(CascadesTest, PerSplitLispsmWarpsEachSplitWhereFocusedSplitsStayAffine) {
    // The same splits with and without the per-split warp: with it every split is a real
    // LiSPSM frustum (no fall-back to its uniform limit, w varying over the split), without
    // it every split is an orthographic crop (w = 1 everywhere).
    ShadowSetupInputs in = cascadedView();
    const auto plain = computeShadowSetup(in);
    in.cascades.warp = CascadeWarp::Lispsm;
    const auto warped = computeShadowSetup(in);
    ASSERT_TRUE(plain);
    ASSERT_TRUE(warped);
    ASSERT_EQ(plain->views.size(), warped->views.size());
    const Vec3 forward = glm::normalize(in.camera.wsDirection);
    for (size_t i = 0; i < warped->views.size(); ++i) {
        const ShadowView& w = warped->views[i];
        const ShadowView& p = plain->views[i];
        EXPECT_EQ(*w.split, *p.split);
        ASSERT_TRUE(std::holds_alternative<LispsmWarp>(w.warp)) << "split " << i;
        EXPECT_FALSE(std::get<LispsmWarp>(w.warp).uniform) << "split " << i << " fell back to uniform";
        EXPECT_TRUE(std::holds_alternative<std::monostate>(p.warp));
        // Points at the split's near and far end, on the view axis.
        const Vec4 nearP(in.camera.wsEye + w.split->x * forward, 1.0),
            farP(in.camera.wsEye + w.split->y * forward, 1.0);
        EXPECT_GT(std::abs((w.clipFromWorld * farP).w - (w.clipFromWorld * nearP).w), 1e-3) << "split " << i;
        EXPECT_NEAR((p.clipFromWorld * farP).w, (p.clipFromWorld * nearP).w, 1e-9) << "split " << i;
    }
}

TEST(CascadesTest, EachSplitIsItsSlicesOwnSetUpWithAndWithoutTheWarp) {
    // Cascades cut every split's focus body from the view's V ∩ S (two planes) instead of
    // computing it afresh: each split's map must still be the focused (or LiSPSM) map of its
    // slice of the frustum, computed on its own. Over 300 random configurations, up to 1 km out.
    shadowkit::core::testing::ConfigGenerator gen(36);
    int compared = 0;
    for (int i = 0; i < 300; ++i) {
        ShadowSetupInputs in = gen.next();
        in.technique = Technique::Csm;
        in.cascades.count = 1 + i % 4;
        in.cascades.blendBand = i % 2 ? 0.1 : 0.0;
        in.cascades.warp = i % 3 == 0 ? CascadeWarp::Lispsm : CascadeWarp::None;
        in.cascades.stabilize = false; // a stabilised split is fitted to its sphere, not its body
        const auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        for (const ShadowView& view : setup->views) {
            ShadowSetupInputs slice = in;
            slice.technique = in.cascades.warp == CascadeWarp::Lispsm ? Technique::Lispsm : Technique::Focused;
            slice.camera.zNear = view.split->x;
            slice.camera.zFar = view.split->y;
            const auto own = computeShadowSetup(slice);
            ASSERT_TRUE(own) << own.error();
            const Mat4 &a = view.clipFromWorld, &b = own->views[0].clipFromWorld;
            double scale = 0.0;
            for (int c = 0; c < 4; ++c) scale = std::max(scale, glm::length(b[c]));
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    ASSERT_NEAR(a[c][r], b[c][r], 1e-7 * scale) << "config " << i << ", split " << view.split->x;
            ++compared;
        }
    }
    EXPECT_GT(compared, 600);
}
