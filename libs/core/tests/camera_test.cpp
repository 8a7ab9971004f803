#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace shadowkit::core;

namespace {
PerspectiveCamera obliqueCamera() {
    PerspectiveCamera cam;
    cam.wsEye = Vec3(3, 2, -1);
    cam.wsDirection = Vec3(1, -0.3, -2);
    cam.wsUp = Vec3(0, 1, 0);
    cam.fovYDegrees = 50;
    cam.aspect = 1.5;
    cam.zNear = 0.25;
    cam.zFar = 80;
    return cam;
}
} // namespace

TEST(CameraTest, FrustumCornersMapToTheClipCubeCornersWithZeroToOneDepth) {
    const PerspectiveCamera cam = obliqueCamera();
    const Mat4 clipFromWorld = cam.clipFromWorld();
    const auto corners = cam.wsFrustumCorners();
    const double xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
    for (size_t i = 0; i < 8; ++i) {
        const Vec4 cs = clipFromWorld * Vec4(corners[i], 1.0);
        const Vec3 ndc = Vec3(cs) / cs.w;
        EXPECT_NEAR(ndc.x, xs[i % 4], 1e-9);
        EXPECT_NEAR(ndc.y, ys[i % 4], 1e-9);
        EXPECT_NEAR(ndc.z, i < 4 ? 0.0 : 1.0, 1e-9);
    }
}

TEST(CameraTest, FrustumPlanesPassThroughTheCornersAndPointOutwards) {
    const PerspectiveCamera cam = obliqueCamera();
    const auto planes = cam.wsFrustumPlanes();
    const auto corners = cam.wsFrustumCorners();
    const Vec3 inside = cam.wsEye + 10.0 * glm::normalize(cam.wsDirection);
    for (const Plane& p : planes) {
        EXPECT_LT(p.signedDistance(inside), 0.0);
        for (const Vec3& c : corners) EXPECT_LE(p.signedDistance(c), 1e-9);
    }
    EXPECT_GT(planes[0].signedDistance(cam.wsEye), 0.0); // the eye is in front of the near plane
}

TEST(CameraTest, ValidateNamesTheBadField) {
    PerspectiveCamera cam = obliqueCamera();
    cam.zNear = 5;
    cam.zFar = 5;
    ASSERT_FALSE(cam.validate());
    EXPECT_NE(cam.validate().error().find("near"), std::string::npos);
    cam = obliqueCamera();
    cam.wsDirection = Vec3(0);
    EXPECT_NE(cam.validate().error().find("direction"), std::string::npos);
    cam = obliqueCamera();
    cam.wsUp = cam.wsDirection * 3.0;
    EXPECT_NE(cam.validate().error().find("up"), std::string::npos);
    cam = obliqueCamera();
    cam.fovYDegrees = 180;
    EXPECT_NE(cam.validate().error().find("fov"), std::string::npos);
    EXPECT_TRUE(obliqueCamera().validate());
    // An eye past the world's end (a ray origin Embree would abort on at 1.8e18 m), and one at it.
    cam = obliqueCamera();
    cam.wsEye = Vec3(0, 1e20, 0);
    ASSERT_FALSE(cam.validate());
    EXPECT_NE(cam.validate().error().find("camera eye: at most 1e13 m"), std::string::npos);
    cam.wsEye = Vec3(0, 0.9e13, 0);
    EXPECT_TRUE(cam.validate());
}

namespace {

// A turntable's camera at frame k: round a centre at 20 m, 6 m up, looking at the centre, 1.5°
// a frame, and rising `climb` metres a frame (a helix: a turn and a slide along its axis).
PerspectiveCamera turntable(double k, double climb = 0.0) {
    const Vec3 wsCentre(5.0, 2.0, -3.0);
    const double a = glm::radians(1.5 * k);
    PerspectiveCamera c = obliqueCamera();
    c.wsEye = wsCentre + Vec3(20.0 * std::sin(a), 6.0 + climb * k, 20.0 * std::cos(a));
    c.wsDirection = wsCentre + Vec3(0.0, climb * k, 0.0) - c.wsEye;
    return c;
}

void expectSameCamera(const PerspectiveCamera& got, const PerspectiveCamera& want, const std::string& what) {
    EXPECT_LT(glm::length(got.wsEye - want.wsEye), 1e-6) << what;
    EXPECT_LT(glm::length(glm::normalize(got.wsDirection) - glm::normalize(want.wsDirection)), 1e-9) << what;
    // The up hint may turn with the camera; the image's up may not.
    const Mat4 gotView = got.viewFromWorld(), wantView = want.viewFromWorld();
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(Vec3(gotView[c]) - Vec3(wantView[c])), 1e-9) << what;
}

} // namespace

TEST(ExtrapolatedCamera, AFrameStepRepeatedFollowsATurntableAndAHelixExactly) {
    // The motion from frame 9 to frame 10 repeated k frames is frame 10 + k, whole or fractional,
    // a quarter turn and more: a straight-line extrapolation would leave the circle on its tangent.
    for (const double climb : {0.0, 0.25})
        for (const double k : {0.0, 1.0, 7.5, 60.0, 200.0})
            expectSameCamera(extrapolatedCamera(turntable(9.0, climb), turntable(10.0, climb), k),
                             turntable(10.0 + k, climb),
                             "climb " + std::to_string(climb) + ", " + std::to_string(k) + " frames on");
}

TEST(ExtrapolatedCamera, ASlideGoesOnInAStraightLineAndATurnInPlaceTurnsPastAQuarter) {
    PerspectiveCamera before = obliqueCamera(), now = before;
    now.wsEye += Vec3(0.3, 0.1, -0.2);
    PerspectiveCamera want = now;
    want.wsEye = before.wsEye + 41.0 * (now.wsEye - before.wsEye);
    expectSameCamera(extrapolatedCamera(before, now, 40.0), want, "a slide");
    // A pan of 2° a frame about the vertical through the eye: 60 frames on it has turned 120°.
    auto panned = [&](double degrees) {
        PerspectiveCamera c = obliqueCamera();
        const double a = glm::radians(degrees);
        const Vec3 d = c.wsDirection;
        c.wsDirection = Vec3(d.x * std::cos(a) + d.z * std::sin(a), d.y, -d.x * std::sin(a) + d.z * std::cos(a));
        return c;
    };
    expectSameCamera(extrapolatedCamera(panned(0.0), panned(2.0), 60.0), panned(122.0), "a pan");
    expectSameCamera(extrapolatedCamera(now, now, 100.0), now, "a still camera");
}

TEST(LightTest, SunAnglesFollowTheCompassConvention) {
    // Elevation 90: straight down. Azimuth 90 at the horizon: the sun is east (+X), so the
    // light travels west (-X).
    EXPECT_NEAR(DirectionalLight::fromSunAngles(90, 0)->wsDirection.y, -1.0, 1e-12);
    const Vec3 east = DirectionalLight::fromSunAngles(0, 90)->wsDirection;
    EXPECT_NEAR(east.x, -1.0, 1e-12);
    EXPECT_NEAR(azimuthDegreesOf(Vec3(0, 0, -1)), 0.0, 1e-12);
    EXPECT_NEAR(azimuthDegreesOf(Vec3(1, 0, 0)), 90.0, 1e-12);
    EXPECT_FALSE(DirectionalLight::fromDirection(Vec3(0)));
    EXPECT_FALSE(DirectionalLight::fromSunAngles(95, 0));
}
