#include "shadowkit/core/camera.h"
#include "shadowkit/core/wireframe.h"

#include <gtest/gtest.h>

using namespace shadowkit::core;

TEST(WireframeTest, ClipVolumeEdgesJoinTheFrustumCornersThatMapBackToTheClipCube) {
    PerspectiveCamera cam;
    cam.wsEye = {3, 2, 1};
    cam.wsDirection = {1, -0.2, -0.5};
    cam.zNear = 0.5;
    cam.zFar = 40.0;
    const std::vector<Edge> edges = clipVolumeEdges(cam.clipFromWorld());
    ASSERT_EQ(edges.size(), 12u);
    for (const Edge& e : edges)
        for (const Vec3& p : {e.first, e.second}) {
            const Vec4 cs = cam.clipFromWorld() * Vec4(p, 1.0);
            EXPECT_NEAR(std::abs(cs.x / cs.w), 1.0, 1e-9);
            EXPECT_NEAR(std::abs(cs.y / cs.w), 1.0, 1e-9);
            EXPECT_TRUE(std::abs(cs.z / cs.w) < 1e-9 || std::abs(cs.z / cs.w - 1.0) < 1e-9);
        }
    // Four edges run from the near plane to the far plane, each 40 − 0.5 m deep along the view.
    int depthEdges = 0;
    for (const Edge& e : edges) {
        const double along = std::abs(glm::dot(e.second - e.first, glm::normalize(cam.wsDirection)));
        if (along > 1.0) {
            ++depthEdges;
            EXPECT_NEAR(along, 39.5, 1e-9);
        }
    }
    EXPECT_EQ(depthEdges, 4);
}

TEST(WireframeTest, ASingularMatrixGivesNoEdges) { EXPECT_TRUE(clipVolumeEdges(Mat4(0.0)).empty()); }

TEST(WireframeTest, ABoxHasTwelveEdgesAndAnEmptyBodyNone) {
    const ConvexBody box = ConvexBody::fromAabb(Aabb::fromMinMax({0, 0, 0}, {1, 2, 3}));
    const std::vector<Edge> edges = bodyEdges(box);
    EXPECT_EQ(edges.size(), 12u);
    double total = 0.0;
    for (const Edge& e : edges) total += glm::length(e.second - e.first);
    EXPECT_NEAR(total, 4.0 * (1 + 2 + 3), 1e-9);
    EXPECT_TRUE(bodyEdges(ConvexBody{}).empty());
}
