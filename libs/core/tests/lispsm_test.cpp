#include "shadowkit/core/lispsm.h"
#include "shadowkit/core/perspective_aliasing.h"
#include "shadowkit/core/visible_depth.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit::core;

namespace {

// A level camera in the middle of a large scene; the sun at angle gamma from the view
// direction, in the vertical plane of the view.
ShadowSetupInputs levelView(double gammaDegrees, LispsmFormula formula = LispsmFormula::Paper) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-2000, -50, -2000), Vec3(2000, 50, 2000));
    in.camera.wsEye = Vec3(0, 0, 0);
    in.camera.wsDirection = Vec3(0, 0, -1);
    in.camera.wsUp = Vec3(0, 1, 0);
    in.camera.zNear = 1;
    in.camera.zFar = 100;
    in.camera.fovYDegrees = 40;
    in.camera.aspect = 1.0;
    const double g = glm::radians(gammaDegrees);
    in.light = DirectionalLight{Vec3(0, -std::sin(g), -std::cos(g))}; // angle g from (0,0,-1)
    in.technique = Technique::Lispsm;
    in.lispsm.formula = formula;
    return in;
}

// The spread of the camera's frustum corners along the view direction's part perpendicular
// to the light (LiSPSM's warp axis), from the camera's own parameters.
double frustumSpreadAcrossTheLight(const ShadowSetupInputs& in) {
    const PerspectiveCamera& c = in.camera;
    const Vec3 v = glm::normalize(c.wsDirection), l = glm::normalize(in.light.wsDirection);
    const Vec3 axis = glm::normalize(v - glm::dot(v, l) * l);
    const Vec3 right = glm::normalize(glm::cross(v, c.wsUp)), up = glm::cross(right, v);
    const double tanHalf = std::tan(glm::radians(c.fovYDegrees) / 2.0);
    double lo = INFINITY, hi = -INFINITY;
    for (const double z : {c.zNear, c.zFar})
        for (const double sx : {-1.0, 1.0})
            for (const double sy : {-1.0, 1.0}) {
                const Vec3 corner = c.wsEye + z * (v + sx * tanHalf * c.aspect * right + sy * tanHalf * up);
                lo = std::min(lo, glm::dot(corner, axis)), hi = std::max(hi, glm::dot(corner, axis));
            }
    return hi - lo;
}

} // namespace

TEST(LispsmTest, NEqualsTheClosedFormWhenViewIsPerpendicularToLight) {
    // B is the frustum swept upwards: its extent along the view is exactly z_f − z_n, so
    // both formulas give Wimmer et al. 2004's n_opt = z_n + √(z_n z_f) = 11.
    for (LispsmFormula f : {LispsmFormula::Paper, LispsmFormula::Scherzer}) {
        const auto setup = computeShadowSetup(levelView(90, f));
        ASSERT_TRUE(setup);
        EXPECT_NEAR(std::get<LispsmWarp>(setup->views[0].warp).d, 99.0, 1e-6);
        EXPECT_NEAR(std::get<LispsmWarp>(setup->views[0].warp).n, lispsmOptimalN(1, 100), 1e-6);
        EXPECT_FALSE(std::get<LispsmWarp>(setup->views[0].warp).uniform);
    }
}

TEST(LispsmTest, NGrowsWithoutBoundAndConvergesToUniformAsGammaGoesToZero) {
    double previous = 0.0;
    bool reachedUniform = false;
    for (double gamma : {90.0, 60.0, 30.0, 10.0, 3.0, 1.0, 0.3, 0.1, 0.03, 0.01, 0.001, 0.0}) {
        const auto setup = computeShadowSetup(levelView(gamma));
        ASSERT_TRUE(setup) << gamma;
        const Mat4& m = setup->views[0].clipFromWorld;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) ASSERT_TRUE(std::isfinite(m[c][r])) << "gamma " << gamma;
        if (std::get<LispsmWarp>(setup->views[0].warp).uniform) {
            reachedUniform = true;
            // The same matrix as the focused map: LiSPSM's limit is uniform shadow mapping.
            ShadowSetupInputs focused = levelView(gamma);
            focused.technique = Technique::Focused;
            const Mat4 u = computeShadowSetup(focused)->views[0].clipFromWorld;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], u[c][r], 1e-9) << "gamma " << gamma;
            continue;
        }
        const double n = std::get<LispsmWarp>(setup->views[0].warp).n;
        EXPECT_GT(n, previous) << "gamma " << gamma;
        previous = n;
    }
    EXPECT_TRUE(reachedUniform);
    EXPECT_GT(previous, 1000.0 * 10.0); // n was already huge before the switch
}

TEST(LispsmTest, WarpIsContinuousAtTheSwitchToUniform) {
    // Just below the switch the warped map must already be (nearly) the uniform one: compare
    // where a point in the middle of the view lands in the map.
    const Vec3 probe(3, -20, -50);
    double gamma = 1.0;
    ShadowSetup setup;
    for (; gamma > 1e-6; gamma *= 0.8) {
        auto s = computeShadowSetup(levelView(gamma));
        if (std::get<LispsmWarp>(s->views[0].warp).uniform) break;
        setup = *s;
    }
    ShadowSetupInputs focused = levelView(gamma);
    focused.technique = Technique::Focused;
    const Mat4 u = computeShadowSetup(focused)->views[0].clipFromWorld;
    const Vec4 a = setup.views[0].clipFromWorld * Vec4(probe, 1), b = u * Vec4(probe, 1);
    EXPECT_NEAR(a.x / a.w, b.x / b.w, 0.01);
    EXPECT_NEAR(a.y / a.w, b.y / b.w, 0.01);
}

TEST(LispsmTest, NearTexelsGrowAtTheExpenseOfFarOnes) {
    // Texel density along the view: the warped map gives the near end more of the map than
    // the uniform one does.
    const auto warped = computeShadowSetup(levelView(90));
    ShadowSetupInputs in = levelView(90);
    in.technique = Technique::Focused;
    const auto uniform = computeShadowSetup(in);
    auto mapY = [](const ShadowSetup& s, double z) {
        const Vec4 c = s.views[0].clipFromWorld * Vec4(0, -10, -z, 1);
        return c.y / c.w;
    };
    const double warpedNear = std::abs(mapY(*warped, 2) - mapY(*warped, 1));
    const double uniformNear = std::abs(mapY(*uniform, 2) - mapY(*uniform, 1));
    EXPECT_GT(warpedNear, 3.0 * uniformNear);
}

TEST(LispsmTest, WeightOverrideAndVisibleDepthChangeN) {
    ShadowSetupInputs in = levelView(90, LispsmFormula::Scherzer);
    const double base = std::get<LispsmWarp>(computeShadowSetup(in)->views[0].warp).n;
    in.lispsm.weight = 2.0;
    EXPECT_NEAR(std::get<LispsmWarp>(computeShadowSetup(in)->views[0].warp).n, 2.0 * base, 1e-9);
    in.lispsm.weight = 1.0;
    in.lispsm.nOverride = 42.0;
    EXPECT_EQ(std::get<LispsmWarp>(computeShadowSetup(in)->views[0].warp).n, 42.0);
    in.lispsm.nOverride.reset();
    // Nothing visible before 5 m nor beyond 20 m. Scherzer 2005 §4.4: Δz from the visible far
    // distance only (1 -> 20 m), so n shrinks (a stronger warp near the viewer); B stays the same.
    in.visibleDepth = Vec2(5, 20);
    const auto visible = computeShadowSetup(in);
    EXPECT_NEAR(std::get<LispsmWarp>(visible->views[0].warp).n, 1 + std::sqrt(1.0 * 20.0), 1e-6);
    EXPECT_NEAR(std::get<LispsmWarp>(visible->views[0].warp).d, 99.0, 1e-6);
    EXPECT_LT(std::get<LispsmWarp>(visible->views[0].warp).n, base);
    // visibleNear: z_n = 5 and Δz = 15 (5 -> 20 m): n balances the error over what is seen.
    in.lispsm.visibleNear = true;
    const auto nearToo = computeShadowSetup(in);
    EXPECT_NEAR(std::get<LispsmWarp>(nearToo->views[0].warp).n, 5 + std::sqrt(5.0 * 20.0), 1e-6);
    EXPECT_NEAR(std::get<LispsmWarp>(nearToo->views[0].warp).d, 99.0, 1e-6);
    // A range beyond the far plane (a stale or foreign measurement) cuts nothing: n as without.
    for (const bool visibleNear : {false, true}) {
        in.lispsm.visibleNear = visibleNear;
        in.visibleDepth = Vec2(150, 160);
        EXPECT_NEAR(std::get<LispsmWarp>(computeShadowSetup(in)->views[0].warp).n, base, 1e-9);
    }
    in.lispsm.visibleNear = false;
    in.visibleDepth = Vec2(20, 5);
    const auto reversed = computeShadowSetup(in);
    ASSERT_FALSE(reversed);
    EXPECT_EQ(reversed.errorInfo().field, "visible_depth");
    in.visibleDepth.reset();
    in.lispsm.weight = 0.0;
    EXPECT_FALSE(computeShadowSetup(in));
}

TEST(LispsmTest, MiddleVectorWarpsAlongTheBodyWhereTheCrossProductFollowsTheView) {
    // Looking down and sideways over a floor with the sun from the side: B (the frustum
    // clipped by the floor, swept to the light) is lopsided, so its middle vector and the
    // view direction, each made perpendicular to the light, are different warp axes.
    ShadowSetupInputs in = levelView(60);
    in.camera.wsDirection = Vec3(0.4, -1, -0.3);
    in.light = DirectionalLight{glm::normalize(Vec3(1, -1, 0.2))};
    const auto cross = computeShadowSetup(in);
    in.lispsm.direction = LispsmDirection::MiddleVector;
    const auto middle = computeShadowSetup(in);
    ASSERT_TRUE(cross);
    ASSERT_TRUE(middle);
    const Vec3 l = in.light.wsDirection;
    // Light space +y is the warp axis V_P: row 1 of lightFromWorld's rotation.
    auto warpAxis = [](const ShadowSetup& s) {
        const Mat4& m = s.views[0].lightFromWorld;
        return glm::normalize(Vec3(m[0][1], m[1][1], m[2][1]));
    };
    auto perpendicular = [&](const Vec3& v) { return glm::normalize(v - glm::dot(v, l) * l); };
    Vec3 sum(0.0);
    for (const Vec3& p : middle->body.vertices()) sum += p - in.camera.wsEye;
    EXPECT_NEAR(glm::dot(warpAxis(*middle), perpendicular(sum)), 1.0, 1e-9);
    EXPECT_NEAR(glm::dot(warpAxis(*cross), perpendicular(in.camera.wsDirection)), 1.0, 1e-9);
    EXPECT_LT(glm::dot(warpAxis(*middle), warpAxis(*cross)), std::cos(glm::radians(5.0))); // really another axis
    // Either way the whole of B stays in front of the projection centre and inside the map.
    for (const auto* s : {&cross, &middle})
        for (const Vec3& p : (*s)->body.vertices()) {
            const Vec4 c = (*s)->views[0].clipFromWorld * Vec4(p, 1);
            EXPECT_GT(c.w, 0.0);
            EXPECT_LE(std::abs(c.x / c.w), 1.0 + 1e-9);
            EXPECT_LE(std::abs(c.y / c.w), 1.0 + 1e-9);
        }
}

TEST(VisibleDepthTest, RangeOfDrawnPixelsOnlyAndNothingWithoutThem) {
    const std::vector<float> depths = {0.0f, 12.5f, 3.25f, 0.0f, NAN, 40.0f, -1.0f, INFINITY};
    const auto range = visibleDepthRange(depths);
    ASSERT_TRUE(range);
    EXPECT_EQ(range->x, 3.25);
    EXPECT_EQ(range->y, 40.0);
    EXPECT_FALSE(visibleDepthRange(std::vector<float>{0.0f, 0.0f}));
    EXPECT_FALSE(visibleDepthRange(std::vector<float>{}));
    const auto single = visibleDepthRange(std::vector<float>{7.0f});
    ASSERT_TRUE(single);
    EXPECT_GT(single->y, single->x); // a valid [near, far] for LispsmOptions
    EXPECT_TRUE(validateOptions(ShadowSetupInputs{.visibleDepth = *single}));
}

TEST(LispsmTest, TheDefaultMatrixGivesThePapersTexelDensityAlongTheViewAtAnyAngle) {
    // Wimmer et al. 2004 §4.4 (Figure 7): at angle γ a point at view depth z lies
    // u = (z − z_n) sin γ along the warp axis, and pixels per texel along the view follow
    //   dp/ds ∝ (u + n)² d / (z n (n + d) sin γ),
    // with Scherzer's n = (z_n + √(z_n (z_n + Δz))) / sin γ (Δz = d without a visible range).
    // Measured here from the matrix itself — ds/dz of the map coordinate along the view axis —
    // the curve must have that shape, up to a constant, where γ ≠ 90° makes n and the
    // projection centre matter. (Mutations this catches: n without its 1/sin γ gives a curve
    // 1.25–2.8× off in shape over these angles; a projection centre n/2 from B instead of n,
    // 2.8–3.5×; the curve as built stays within 3 %.)
    const double kAngles[] = {30.0, 45.0, 60.0, 120.0, 150.0};
    for (const double gamma : kAngles) {
        const ShadowSetupInputs in = levelView(gamma, LispsmOptions{}.formula);
        const auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << gamma;
        const LispsmWarp& warp = std::get<LispsmWarp>(setup->views[0].warp);
        ASSERT_FALSE(warp.uniform) << gamma;
        // d, B's depth along the warp axis, from the camera alone: the frustum lies inside the
        // scene box and sweeping it along the light does not move it along the axis (⟂ light),
        // so d is the spread of the frustum's corners along the axis.
        const double d = frustumSpreadAcrossTheLight(in);
        EXPECT_NEAR(warp.d, d, 1e-6 * d) << gamma;
        const double sinGamma = std::sin(glm::radians(gamma)), zNear = in.camera.zNear;
        const double n = (zNear + std::sqrt(zNear * (zNear + d))) / sinGamma;
        // Map coordinates (NDC x, y) of the view-axis point at depth z.
        auto mapAt = [&](double z) {
            const Vec4 c = setup->views[0].clipFromWorld * Vec4(in.camera.wsEye + z * in.camera.wsDirection, 1.0);
            return Vec2(c.x / c.w, c.y / c.w);
        };
        double lo = INFINITY, hi = 0.0;
        for (int i = 0; i <= 50; ++i) {
            const double z = zNear * std::pow(in.camera.zFar / zNear, i / 50.0), h = 1e-4 * z;
            const double measured = 1.0 / (z * glm::length(mapAt(z + h) - mapAt(z - h)) / (2.0 * h));
            const double u = (z - zNear) * sinGamma;
            const double paper = (u + n) * (u + n) * d / (z * n * (n + d) * sinGamma);
            lo = std::min(lo, measured / paper);
            hi = std::max(hi, measured / paper);
        }
        EXPECT_LT(hi / lo, 1.05) << "gamma " << gamma << ": the texel density's shape is not the paper's";
    }
}
