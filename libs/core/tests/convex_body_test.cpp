#include "shadowkit/core/convex_body.h"

#include <gtest/gtest.h>

using namespace shadowkit::core;

namespace {
Aabb unitBox() { return Aabb::fromMinMax(Vec3(0.0), Vec3(1.0)); }
} // namespace

TEST(ConvexBodyTest, BoxHasEightVerticesAndItsVolume) {
    const ConvexBody body = ConvexBody::fromAabb(Aabb::fromMinMax(Vec3(-1, 0, 2), Vec3(1, 3, 6)));
    EXPECT_EQ(body.vertices().size(), 8u);
    EXPECT_NEAR(body.volume(), 2.0 * 3.0 * 4.0, 1e-9);
}

TEST(ConvexBodyTest, ClipThroughTheMiddleHalvesTheVolumeAndAddsACap) {
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(0.5), Vec3(1, 0, 0))); // keep x <= 0.5
    EXPECT_NEAR(body.volume(), 0.5, 1e-12);
    EXPECT_EQ(body.faces().size(), 6u);
    EXPECT_NEAR(body.bounds().max.x, 0.5, 1e-12);
}

TEST(ConvexBodyTest, DiagonalClipLeavesATetrahedronCorner) {
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(1, 0, 0), Vec3(1, 1, 1))); // x + y + z <= 1
    EXPECT_NEAR(body.volume(), 1.0 / 6.0, 1e-12);
    EXPECT_EQ(body.vertices().size(), 4u);
}

TEST(ConvexBodyTest, PlaneOutsideKeepsEverythingAndPlaneBeyondEmptiesIt) {
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(2, 0, 0), Vec3(1, 0, 0)));
    EXPECT_NEAR(body.volume(), 1.0, 1e-12);
    body.clip(Plane::fromPointNormal(Vec3(-1, 0, 0), Vec3(1, 0, 0))); // keep x <= -1
    EXPECT_TRUE(body.isEmpty());
    EXPECT_TRUE(body.vertices().empty());
}

TEST(ConvexBodyTest, ClipAlongAFaceLeavesNoFlatSliver) {
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(0, 0, 0), Vec3(1, 0, 0))); // keep x <= 0: only the face
    EXPECT_TRUE(body.isEmpty());
}

TEST(ConvexBodyTest, SweepOfACubeReachesTheBoxWallTowardsTheSweep) {
    // A small cube in the middle of a large box, swept along +y and then cut by the box:
    // the result is a column from the cube up to the top of the box.
    const ConvexBody cube = ConvexBody::fromAabb(Aabb::fromMinMax(Vec3(4), Vec3(6)));
    ConvexBody column = ConvexBody::fromAabb(Aabb::fromMinMax(Vec3(0), Vec3(10)));
    column.clip(cube.sweepHalfSpaces(Vec3(0, 1, 0)));
    const Aabb b = column.bounds();
    EXPECT_NEAR(b.min.y, 4.0, 1e-9);
    EXPECT_NEAR(b.max.y, 10.0, 1e-9);
    EXPECT_NEAR(b.min.x, 4.0, 1e-9);
    EXPECT_NEAR(b.max.x, 6.0, 1e-9);
    EXPECT_NEAR(column.volume(), 2.0 * 2.0 * 6.0, 1e-9);
}

TEST(ConvexBodyTest, ObliqueSweepIsExactWhereExitPointsWouldLoseVolume) {
    // Swept diagonally, rays from the cube's vertices leave the box through different
    // faces. The exact swept body contains every point p + t·dir still inside the box.
    const ConvexBody cube = ConvexBody::fromAabb(Aabb::fromMinMax(Vec3(1, 1, 1), Vec3(3, 2, 3)));
    const Aabb box = Aabb::fromMinMax(Vec3(0), Vec3(10));
    ConvexBody swept = ConvexBody::fromAabb(box);
    const Vec3 dir = glm::normalize(Vec3(1, 0.7, 0.2));
    swept.clip(cube.sweepHalfSpaces(dir));
    for (double x = 1; x <= 3; x += 0.5)
        for (double y = 1; y <= 2; y += 0.25)
            for (double z = 1; z <= 3; z += 0.5)
                for (double t = 0; t < 20; t += 0.5) {
                    const Vec3 p = Vec3(x, y, z) + t * dir;
                    if (box.contains(p)) {
                        EXPECT_TRUE(swept.contains(p, 1e-9)) << p.x << "," << p.y << "," << p.z;
                    }
                }
    // ...and nothing behind the cube (against the sweep).
    EXPECT_FALSE(swept.contains(Vec3(2, 1.5, 2) - 0.9 * dir, 1e-9));
    EXPECT_FALSE(swept.contains(Vec3(0.2, 9.5, 0.2), 1e-9));
}
