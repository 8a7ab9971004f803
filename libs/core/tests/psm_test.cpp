#include "shadowkit/core/psm.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit::core;

namespace {

ShadowSetupInputs viewWithSun(const Vec3& wsTravel) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-500, 0, -500), Vec3(500, 30, 500));
    in.camera.wsEye = Vec3(0, 2, 0);
    in.camera.wsDirection = Vec3(0, 0, -1);
    in.camera.zNear = 0.5;
    in.camera.zFar = 200;
    in.light = DirectionalLight{glm::normalize(wsTravel)};
    in.technique = Technique::Psm;
    return in;
}

// Depth in the map of a world point (after the divide).
double mapDepth(const ShadowSetup& s, const Vec3& p) {
    const Vec4 c = s.views[0].clipFromWorld * Vec4(p, 1.0);
    return c.z / c.w;
}

} // namespace

TEST(PsmTest, SunAheadBehindAndOverheadAreTheThreeCasesAndKeepTheDepthOrderOfTheLight) {
    // Along every light ray, the point nearer the sun must get the smaller map depth: that is
    // the order the depth test needs, inverted in post-perspective space for a sun behind.
    // Travel directions: sun ahead (light_w > 0), sun behind (inverted), light ⟂ view.
    for (const Vec3& travel : {Vec3(0, -1, 1), Vec3(0, -1, -1), Vec3(1, -1, 0)}) {
        const auto setup = computeShadowSetup(viewWithSun(travel));
        ASSERT_TRUE(setup);
        const Vec3 towards = -glm::normalize(travel);
        const Vec3 receiver(3, 0.5, -20);
        const Vec3 caster = receiver + 8.0 * towards;
        EXPECT_LT(mapDepth(*setup, caster), mapDepth(*setup, receiver)) << travel.x << "," << travel.z;
        // ...and both land on the same texel (they are on one light ray).
        const Vec4 a = setup->views[0].clipFromWorld * Vec4(receiver, 1),
                   b = setup->views[0].clipFromWorld * Vec4(caster, 1);
        EXPECT_NEAR(a.x / a.w, b.x / b.w, 1e-9);
        EXPECT_NEAR(a.y / a.w, b.y / b.w, 1e-9);
    }
    // The sun ahead of the viewer (travelling towards +Z, i.e. towards the camera) makes
    // the light's PP w positive; behind makes it negative and inverts the depth order.
    EXPECT_GT(std::get<PsmWarp>(computeShadowSetup(viewWithSun({0, -1, 1}))->views[0].warp).lightW, 0.0);
    EXPECT_LT(std::get<PsmWarp>(computeShadowSetup(viewWithSun({0, -1, -1}))->views[0].warp).lightW, 0.0);
    EXPECT_TRUE(std::get<PsmWarp>(computeShadowSetup(viewWithSun({0, -1, -1}))->views[0].warp).inverted);
}

TEST(PsmTest, SlidesBackWhenCastersLieBehindTheViewer) {
    // Sun behind and low: B reaches far behind the eye, so the virtual camera must move
    // back until B starts at the near distance.
    const auto setup = computeShadowSetup(viewWithSun({0, -0.3, -1}));
    ASSERT_TRUE(setup);
    EXPECT_GT(std::get<PsmWarp>(setup->views[0].warp).slideBack, 10.0);
    for (const Vec3& p : setup->body.vertices()) EXPECT_GT((setup->views[0].clipFromWorld * Vec4(p, 1)).w, 0.0);
    // Sun ahead: nothing of B lies behind the viewer, no slide-back.
    EXPECT_NEAR(std::get<PsmWarp>(computeShadowSetup(viewWithSun({0, -0.3, 1}))->views[0].warp).slideBack, 0.0, 1e-9);
}

TEST(PsmTest, GivesNearReceiversMoreTexelsThanTheFocusedMap) {
    ShadowSetupInputs in = viewWithSun({1, -1, 0});
    const auto psm = computeShadowSetup(in);
    in.technique = Technique::Focused;
    const auto focused = computeShadowSetup(in);
    auto footprint = [](const ShadowSetup& s, const Vec3& a, const Vec3& b) {
        const Vec4 ca = s.views[0].clipFromWorld * Vec4(a, 1), cb = s.views[0].clipFromWorld * Vec4(b, 1);
        return glm::length(Vec2(ca) / ca.w - Vec2(cb) / cb.w);
    };
    const Vec3 a(0, 0, -2), b(0, 0, -3); // a metre of ground just in front of the viewer
    EXPECT_GT(footprint(*psm, a, b), 5.0 * footprint(*focused, a, b));
}
