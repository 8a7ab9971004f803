#include "shadowkit/core/convex_body.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace shadowkit::core;

namespace {
Aabb unitBox() { return Aabb::fromMinMax(Vec3(0.0), Vec3(1.0)); }

// The vertices of an intersection of half-spaces found the slow way, independently of the
// clipper: every point where three of the planes meet and which lies inside all of them.
std::vector<Vec3> verticesByBruteForce(const std::vector<Plane>& planes, double eps) {
    std::vector<Vec3> out;
    for (size_t i = 0; i < planes.size(); ++i)
        for (size_t j = i + 1; j < planes.size(); ++j)
            for (size_t k = j + 1; k < planes.size(); ++k) {
                const glm::dmat3 normalsAsRows =
                    glm::transpose(glm::dmat3(planes[i].normal, planes[j].normal, planes[k].normal));
                if (std::abs(glm::determinant(normalsAsRows)) < 1e-9) continue; // no single point
                const Vec3 p = glm::inverse(normalsAsRows) * -Vec3(planes[i].d, planes[j].d, planes[k].d);
                bool inside = true;
                for (const Plane& plane : planes) inside = inside && plane.signedDistance(p) <= eps;
                bool known = false;
                for (const Vec3& q : out) known = known || glm::length(q - p) <= eps;
                if (inside && !known) out.push_back(p);
            }
    return out;
}

std::vector<Plane> boxPlanes(const Aabb& box) {
    return {{Vec3(-1, 0, 0), box.min.x}, {Vec3(1, 0, 0), -box.max.x}, {Vec3(0, -1, 0), box.min.y},
            {Vec3(0, 1, 0), -box.max.y}, {Vec3(0, 0, -1), box.min.z}, {Vec3(0, 0, 1), -box.max.z}};
}
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
    EXPECT_EQ(body.faceCount(), 6u);
    EXPECT_NEAR(body.bounds().max.x, 0.5, 1e-12);
}

TEST(ConvexBodyTest, DiagonalClipLeavesATetrahedronCorner) {
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(1, 0, 0), Vec3(1, 1, 1))); // x + y + z <= 1
    EXPECT_NEAR(body.volume(), 1.0 / 6.0, 1e-12);
    EXPECT_EQ(body.vertices().size(), 4u);
}

TEST(ConvexBodyTest, RangeAlongAnAxisIsTheBodysExtentThereAndEmptyForNoBody) {
    // The tetrahedron x, y, z >= 0, x + y + z <= 1 along (1, 2, 3): 0 at the origin, 3 at (0, 0, 1).
    ConvexBody body = ConvexBody::fromAabb(unitBox());
    body.clip(Plane::fromPointNormal(Vec3(1, 0, 0), Vec3(1, 1, 1)));
    const Vec2 range = body.rangeAlong(Vec3(1, 2, 3));
    EXPECT_NEAR(range.x, 0.0, 1e-12);
    EXPECT_NEAR(range.y, 3.0, 1e-12);
    EXPECT_NEAR(body.rangeAlong(Vec3(-1, 0, 0)).x, -1.0, 1e-12); // a negative axis turns it over
    const Vec2 none = ConvexBody().rangeAlong(Vec3(1, 0, 0));
    EXPECT_FALSE(none.x <= none.y); // nothing lies along it
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

TEST(ConvexBodyTest, ARandomlyClippedBoxHasExactlyTheVerticesThreePlanesMeetInInsideEveryHalfSpace) {
    // 400 boxes, each cut by 1-9 random planes through points inside it, up to 1 km from the
    // origin: the body's vertices are the brute-force ones (no vertex lost, none invented), each
    // face lies on one of the planes, faces point outwards (positive volume) and an empty
    // intersection gives the empty body.
    std::mt19937 rng(20261125);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int empty = 0, cut = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec3 centre = 1000.0 * Vec3(unit(rng), unit(rng), unit(rng));
        const Vec3 half =
            Vec3(1.0 + 50.0 * std::abs(unit(rng)), 1.0 + 5.0 * std::abs(unit(rng)), 1.0 + 50.0 * std::abs(unit(rng)));
        const Aabb box = Aabb::fromMinMax(centre - half, centre + half);
        std::vector<Plane> planes = boxPlanes(box);
        ConvexBody body = ConvexBody::fromAabb(box);
        const int cuts = 1 + trial % 9;
        for (int c = 0; c < cuts; ++c) {
            const Vec3 through = centre + half * Vec3(unit(rng), unit(rng), unit(rng));
            const Plane plane = Plane::fromPointNormal(through, Vec3(unit(rng), unit(rng), unit(rng)));
            planes.push_back(plane);
            body.clip(plane);
        }
        const double eps = 1e-7 * glm::length(half);
        const std::vector<Vec3> expected = verticesByBruteForce(planes, eps);
        if (expected.size() < 4) {
            EXPECT_TRUE(body.isEmpty()) << "trial " << trial;
            ++empty;
            continue;
        }
        ++cut;
        ASSERT_FALSE(body.isEmpty()) << "trial " << trial;
        const ConvexBody::Points got = body.vertices();
        EXPECT_EQ(got.size(), expected.size()) << "trial " << trial;
        for (const Vec3& p : expected) {
            double nearest = INFINITY;
            for (const Vec3& q : got) nearest = std::min(nearest, glm::length(q - p));
            EXPECT_LE(nearest, eps) << "trial " << trial << ": a vertex is missing";
        }
        for (size_t f = 0; f < body.faceCount(); ++f) {
            bool onAPlane = false;
            for (const Plane& plane : planes) {
                bool allOn = true;
                for (const Vec3& p : body.face(f)) allOn = allOn && std::abs(plane.signedDistance(p)) <= eps;
                onAPlane = onAPlane || allOn;
            }
            EXPECT_TRUE(onAPlane) << "trial " << trial << ", face " << f;
        }
        EXPECT_GT(body.volume(), 0.0) << "trial " << trial;
    }
    EXPECT_GT(empty, 20); // both outcomes met often enough to mean something
    EXPECT_GT(cut, 150);
}

TEST(ConvexBodyTest, SweepPlanesHoldTheRandomBodySweptAndTouchIt) {
    // For random bodies and directions: every vertex moved any distance along the sweep stays
    // inside every plane, and every plane touches the body (a facet, not a loose bound).
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const Aabb box = Aabb::fromMinMax(Vec3(-10.0), Vec3(10.0));
        ConvexBody body = ConvexBody::fromAabb(box);
        for (int c = 0; c < 5; ++c)
            body.clip(Plane::fromPointNormal(5.0 * Vec3(unit(rng), unit(rng), unit(rng)),
                                             Vec3(unit(rng), unit(rng), unit(rng))));
        if (body.isEmpty()) continue;
        const Vec3 dir = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
        const ConvexBody::Planes planes = body.sweepHalfSpaces(dir);
        const ConvexBody::Points verts = body.vertices();
        for (const Plane& plane : planes) {
            double highest = -INFINITY;
            for (const Vec3& v : verts) {
                highest = std::max(highest, plane.signedDistance(v));
                for (const double t : {0.0, 1.0, 100.0, 1e4})
                    EXPECT_LE(plane.signedDistance(v + t * dir), 1e-9 * (1.0 + t)) << "trial " << trial;
            }
            EXPECT_NEAR(highest, 0.0, 1e-9) << "trial " << trial << ": a plane that does not touch the body";
        }
    }
}

TEST(ConvexBodyTest, RandomBodiesHaveEulersCountOfEdgesEachOnTwoFacesAndConvexFaces) {
    // The body is held as vertices marked with their planes; its edges are found from the marks
    // alone (two shared planes, no third vertex on both). A wrong adjacency breaks Euler's
    // V − E + F = 2, or leaves an edge that does not lie on two faces' planes, or a face loop
    // that is not convex and counter-clockwise seen from outside.
    std::mt19937 rng(20261130);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Vec3 centre = 500.0 * Vec3(unit(rng), unit(rng), unit(rng));
        ConvexBody body = ConvexBody::fromAabb(Aabb::fromMinMax(centre - Vec3(5.0), centre + Vec3(5.0)));
        for (int c = 0; c < 1 + trial % 12; ++c) { // planes 1-4.5 m out, facing roughly away from the centre
            const Vec3 out = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
            body.clip(Plane::fromPointNormal(centre + (2.75 + 1.75 * unit(rng)) * out,
                                             out + 0.5 * Vec3(unit(rng), unit(rng), unit(rng))));
        }
        if (body.isEmpty()) continue;
        ++checked;
        const ConvexBody::Points vertices = body.vertices();
        const ConvexBody::Edges edges = body.edges();
        EXPECT_EQ(static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) +
                      static_cast<long>(body.faceCount()),
                  2)
            << "trial " << trial;
        std::vector<std::vector<Vec3>> faces;
        for (size_t f = 0; f < body.faceCount(); ++f) {
            const ConvexBody::Points loop = body.face(f);
            ASSERT_GE(loop.size(), 3u) << "trial " << trial;
            faces.emplace_back(loop.begin(), loop.end());
            const Vec3 n = glm::normalize(glm::cross(loop[1] - loop[0], loop[2] - loop[0]));
            for (size_t i = 0; i < loop.size(); ++i) { // every turn the same way
                const Vec3 &a = loop[i], &b = loop[(i + 1) % loop.size()], &c = loop[(i + 2) % loop.size()];
                EXPECT_GE(glm::dot(glm::cross(b - a, c - b), n), -1e-9) << "trial " << trial << ", face " << f;
            }
            // Outward: the body's centroid lies behind the face.
            Vec3 centroid(0.0);
            for (const Vec3& v : vertices) centroid += v / double(vertices.size());
            EXPECT_LT(glm::dot(centroid - loop[0], n), 0.0) << "trial " << trial << ", face " << f;
        }
        for (const auto& [a, b] : edges) { // each edge is a side of exactly two face loops
            int sides = 0;
            for (const std::vector<Vec3>& loop : faces)
                for (size_t i = 0; i < loop.size(); ++i) {
                    const Vec3 &p = loop[i], &q = loop[(i + 1) % loop.size()];
                    sides += (p == a && q == b) || (p == b && q == a);
                }
            EXPECT_EQ(sides, 2) << "trial " << trial;
        }
    }
    EXPECT_GT(checked, 250);
}

TEST(ConvexBodyTest, CutsThroughVerticesAndEdgesKeepTheExactBody) {
    // Degenerate cuts, where a plane passes exactly through existing vertices: the vertices on
    // it are marked, not doubled, and the body is the brute-force one.
    ConvexBody body = ConvexBody::fromAabb(Aabb::fromMinMax(Vec3(-1.0), Vec3(1.0)));
    std::vector<Plane> planes = boxPlanes(Aabb::fromMinMax(Vec3(-1.0), Vec3(1.0)));
    // y <= z through two opposite edges; x + y + z <= 1 through three corners; x <= z through
    // two vertices the first cut made; x - y + 0.5 z <= 0 through the centre.
    for (const Plane& plane :
         {Plane::fromPointNormal(Vec3(0.0), Vec3(0, 1, -1)), Plane::fromPointNormal(Vec3(1, -1, 1), Vec3(1, 1, 1)),
          Plane::fromPointNormal(Vec3(0.0), Vec3(1, 0, -1)), Plane::fromPointNormal(Vec3(0.0), Vec3(1, -1, 0.5))}) {
        body.clip(plane);
        planes.push_back(plane);
    }
    const std::vector<Vec3> expected = verticesByBruteForce(planes, 1e-9);
    const ConvexBody::Points got = body.vertices();
    ASSERT_EQ(got.size(), expected.size());
    for (const Vec3& p : expected) {
        double nearest = INFINITY;
        for (const Vec3& q : got) nearest = std::min(nearest, glm::length(q - p));
        EXPECT_LE(nearest, 1e-9);
    }
    EXPECT_EQ(static_cast<long>(got.size()) - static_cast<long>(body.edges().size()) +
                  static_cast<long>(body.faceCount()),
              2);
}

TEST(ConvexBodyTest, SweptUntilAPlaneIsTheBoxCutByTheSweepsPlanes) {
    // sweptUntil builds the swept body at once; cut by the rest of the box it must be the box
    // cut by every plane of sweepHalfSpaces: for random bodies, random sweeps and sweeps along
    // the axes (faces parallel to the sweep) and bodies touching the stop plane (cut by it).
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Aabb box = Aabb::fromMinMax(Vec3(-10.0), Vec3(10.0));
    const std::vector<Plane> walls = boxPlanes(box);
    int compared = 0;
    for (int trial = 0; trial < 600; ++trial) {
        ConvexBody body = ConvexBody::fromAabb(trial % 3 == 0 ? box : Aabb::fromMinMax(Vec3(-6.0), Vec3(4.0)));
        for (int c = 0; c < 1 + trial % 6; ++c)
            body.clip(Plane::fromPointNormal(5.0 * Vec3(unit(rng), unit(rng), unit(rng)),
                                             Vec3(unit(rng), unit(rng), unit(rng))));
        if (body.isEmpty()) continue;
        Vec3 dir = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
        if (trial % 4 == 1) dir = Vec3(0, 1, 0); // four faces of the box parallel to the sweep
        if (trial % 4 == 2) dir = glm::normalize(Vec3(1, 1, 0));
        size_t stop = 0;
        for (size_t f = 1; f < walls.size(); ++f)
            if (glm::dot(walls[f].normal, dir) > glm::dot(walls[stop].normal, dir)) stop = f;
        ConvexBody swept = body.sweptUntil(dir, walls[stop]);
        for (size_t f = 0; f < walls.size(); ++f)
            if (f != stop) swept.clip(walls[f]);
        ConvexBody expected = ConvexBody::fromAabb(box);
        const ConvexBody::Planes sweep = body.sweepHalfSpaces(dir);
        expected.clip(std::span<const Plane>(sweep.data(), sweep.size()));
        ASSERT_EQ(swept.isEmpty(), expected.isEmpty()) << "trial " << trial;
        ++compared;
        const ConvexBody::Points got = swept.vertices(), want = expected.vertices();
        ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
        for (const Vec3& p : want) {
            double nearest = INFINITY;
            for (const Vec3& q : got) nearest = std::min(nearest, glm::length(q - p));
            EXPECT_LE(nearest, 1e-9) << "trial " << trial;
        }
        EXPECT_NEAR(swept.volume(), expected.volume(), 1e-9 * expected.volume()) << "trial " << trial;
    }
    EXPECT_GT(compared, 400);
}
