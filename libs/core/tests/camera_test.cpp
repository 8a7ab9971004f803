#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"

#include <gtest/gtest.h>

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
