#include "shadowkit/core/convex_body_structure.h"
#include "shadowkit/core/focus_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <thread>
#include <vector>

using namespace shadowkit::core;

namespace {

// A box cut by planes: the body, and the planes that define it (the box's, then the cuts).
struct Cut {
    ConvexBody body;
    std::vector<Plane> definition;
};

Cut cutBox(const Aabb& box, const std::vector<Plane>& cuts) {
    Cut out{ConvexBody::fromAabb(box), {}};
    for (const Plane& p : boxFaces(box)) out.definition.push_back(p);
    for (const Plane& p : cuts) {
        out.body.clip(p);
        out.definition.push_back(p);
    }
    return out;
}

std::span<const Plane> span(const std::vector<Plane>& planes) { return {planes.data(), planes.size()}; }

// Vertices sorted by their coordinates, to compare bodies held in different orders.
std::vector<Vec3> sortedVertices(const ConvexBody& body) {
    std::vector<Vec3> out;
    for (const Vec3& p : body.vertices()) out.push_back(p);
    std::sort(out.begin(), out.end(), [](const Vec3& a, const Vec3& b) {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    });
    return out;
}

// Every vertex of each within eps of one of the other's.
bool sameVertices(const ConvexBody& a, const ConvexBody& b, double eps) {
    const ConvexBody::Points pa = a.vertices(), pb = b.vertices();
    if (pa.size() != pb.size()) return false;
    auto covered = [&](const ConvexBody::Points& from, const ConvexBody::Points& in) {
        return std::all_of(from.begin(), from.end(), [&](const Vec3& p) {
            return std::any_of(in.begin(), in.end(), [&](const Vec3& q) { return glm::length(p - q) <= eps; });
        });
    };
    return covered(pa, pb) && covered(pb, pa);
}

// A plane through a point near the box's centre with a random normal.
Plane randomCut(std::mt19937& rng, const Aabb& box) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Vec3 n(unit(rng), unit(rng), unit(rng));
    const Vec3 at = box.center() + 0.3 * box.extent() * Vec3(unit(rng), unit(rng), unit(rng));
    return Plane::fromPointNormal(at, glm::length(n) > 1e-3 ? n : Vec3(1, 0, 0));
}

// The plane turned by up to `turn` radians about a random axis and moved by up to `shift` metres.
Plane moved(std::mt19937& rng, const Plane& p, double turn, double shift) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Vec3 n = glm::normalize(p.normal + turn * Vec3(unit(rng), unit(rng), unit(rng)));
    return {n, p.d + shift * unit(rng)};
}

} // namespace

TEST(ConvexBodyStructureTest, AResolvedBodyIsTheIntersectionClippedAfreshOrNothing) {
    // Box cut by 3-6 planes, remembered; then every plane moved a little (most structures still
    // fit) or a lot (many do not). Whatever resolve() returns must be the body clipped afresh
    // from the moved planes; small moves must mostly be resolved, large ones sometimes refused.
    std::mt19937 rng(20261201);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    struct Tally {
        int resolved = 0, refused = 0;
    };
    for (const double scale : {0.002, 0.2}) {
        Tally tally;
        for (int trial = 0; trial < 300; ++trial) {
            const Vec3 centre = 1000.0 * Vec3(unit(rng), unit(rng), unit(rng));
            const Vec3 half = 1.0 + 50.0 * glm::abs(Vec3(unit(rng), unit(rng), unit(rng)));
            const Aabb box = Aabb::fromMinMax(centre - half, centre + half);
            std::vector<Plane> cuts;
            for (int k = 0, n = 3 + trial % 4; k < n; ++k) cuts.push_back(randomCut(rng, box));
            const Cut before = cutBox(box, cuts);
            ConvexBodyStructure structure;
            if (!structure.remember(before.body, span(before.definition))) continue;

            const double size = glm::length(box.extent());
            const Vec3 shift = scale * size * Vec3(unit(rng), unit(rng), unit(rng));
            const Aabb movedBox = Aabb::fromMinMax(box.min + shift, box.max + shift);
            std::vector<Plane> movedCuts;
            for (const Plane& p : cuts) movedCuts.push_back(moved(rng, p, scale, scale * size));
            const Cut after = cutBox(movedBox, movedCuts);
            const std::optional<ConvexBody> resolved = structure.resolve(span(after.definition));
            if (!resolved) {
                ++tally.refused;
                continue;
            }
            ++tally.resolved;
            ASSERT_TRUE(sameVertices(*resolved, after.body, 1e-9 * (size + glm::length(centre))))
                << "trial " << trial << " at scale " << scale;
            EXPECT_EQ(resolved->faceCount(), after.body.faceCount());
            EXPECT_NEAR(resolved->volume(), after.body.volume(), 1e-9 * after.body.volume());
        }
        if (scale < 0.01) {
            EXPECT_GT(tally.resolved, 3 * tally.refused) << "small moves should keep most structures";
        } else {
            EXPECT_GT(tally.refused, 20) << "large moves must change some structures";
            EXPECT_GT(tally.resolved, 0);
        }
    }
}

TEST(ConvexBodyStructureTest, ACutThatReachesAnotherCornerIsNotResolved) {
    const Aabb box = Aabb::fromMinMax(Vec3(0.0), Vec3(1.0));
    // x + y + z <= 2.5 cuts the corner (1, 1, 1) off: a triangle and seven corners. At 2.4 it
    // still does; at 1.5 it cuts three more corners off and the cap is a hexagon: as many
    // vertices, another structure.
    auto corner = [](double at) { return Plane::fromPointNormal(Vec3(at, 0, 0), Vec3(1, 1, 1)); };
    const Cut triangle = cutBox(box, {corner(2.5)});
    ConvexBodyStructure structure;
    ASSERT_TRUE(structure.remember(triangle.body, span(triangle.definition)));
    EXPECT_EQ(triangle.body.vertices().size(), 10u);

    const Cut nearly = cutBox(box, {corner(2.4)});
    const std::optional<ConvexBody> resolved = structure.resolve(span(nearly.definition));
    ASSERT_TRUE(resolved.has_value());
    EXPECT_TRUE(sameVertices(*resolved, nearly.body, 1e-12));

    const Cut hexagon = cutBox(box, {corner(1.5)});
    EXPECT_EQ(hexagon.body.vertices().size(), 10u);
    EXPECT_FALSE(structure.resolve(span(hexagon.definition)).has_value());
    // A cut moved to pass exactly through a corner: that corner on four planes is no simple
    // vertex, and nothing re-solved from three of them can be trusted.
    EXPECT_FALSE(structure.resolve(span(cutBox(box, {corner(2.0)}).definition)).has_value());
}

TEST(ConvexBodyStructureTest, OnlySimpleBodiesMadeOfTheirDefinitionAreRemembered) {
    const Aabb box = Aabb::fromMinMax(Vec3(0.0), Vec3(1.0));
    ConvexBodyStructure structure;
    // A pyramid's apex on four planes.
    std::vector<Plane> pyramid;
    for (const Vec3& n : {Vec3(1, 0, 1), Vec3(-1, 0, 1), Vec3(0, 1, 1), Vec3(0, -1, 1)})
        pyramid.push_back(Plane::fromPointNormal(Vec3(0.5, 0.5, 1.0), n));
    const Cut apex = cutBox(box, pyramid);
    ASSERT_FALSE(apex.body.isEmpty());
    EXPECT_FALSE(structure.remember(apex.body, span(apex.definition)));
    EXPECT_FALSE(structure.holds());
    // A face that is not in the definition.
    const Cut half = cutBox(box, {Plane::fromPointNormal(Vec3(0.5), Vec3(1, 0, 0))});
    std::vector<Plane> withoutTheCut(half.definition.begin(), half.definition.end() - 1);
    EXPECT_FALSE(structure.remember(half.body, span(withoutTheCut)));
    EXPECT_FALSE(structure.remember(ConvexBody(), span(half.definition)));
    // A face named twice in the definition (as a box's face is in a sweep's planes and the box's):
    // the copy is that face, not a plane its vertices must lie strictly inside.
    std::vector<Plane> twice = half.definition;
    twice.push_back(half.definition[0]);
    ASSERT_TRUE(structure.remember(half.body, span(twice)));
    const std::optional<ConvexBody> again = structure.resolve(span(twice));
    ASSERT_TRUE(again.has_value());
    EXPECT_TRUE(sameVertices(*again, half.body, 1e-12));
    // ...but a copy that has moved off the face is a plane like any other.
    twice.back().d += 0.25; // -x <= -0.25: cuts the face x = 0 off
    EXPECT_FALSE(structure.resolve(span(twice)).has_value());
}

TEST(ConvexBodyStructureTest, TheSameBodyToTheLastBitWhicheverOrderItWasBuiltIn) {
    // Two cuts in either order give one body held with its faces in two orders; resolved, each
    // vertex is solved from its planes in the order of their values, so the two agree exactly.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 centre = 500.0 * Vec3(unit(rng), unit(rng), unit(rng));
        const Aabb box = Aabb::fromMinMax(centre - Vec3(20.0), centre + Vec3(30.0, 25.0, 40.0));
        std::vector<Plane> cuts{randomCut(rng, box), randomCut(rng, box), randomCut(rng, box)};
        std::vector<Plane> reversed(cuts.rbegin(), cuts.rend());
        ConvexBodyStructures forward, backward;
        const Cut a = cutBox(box, cuts), b = cutBox(box, reversed);
        const ConvexBody ra = forward.remember(a.body, span(a.definition));
        const ConvexBody rb = backward.remember(b.body, span(b.definition));
        ConvexBodyStructure probe;
        if (!probe.remember(a.body, span(a.definition))) continue;
        ++compared;
        EXPECT_EQ(sortedVertices(ra), sortedVertices(rb)) << "trial " << trial;
    }
    EXPECT_GT(compared, 150);
}

TEST(ConvexBodyStructureTest, VisibleSceneBodyIsTheSameWhateverFrameCameBefore) {
    // A thread's first V ∩ S is clipped afresh; on another thread the same camera after a
    // neighbouring one is re-solved from that one's structure. Bit for bit the same, and the
    // same as the box clipped by the frustum.
    const Aabb scene = Aabb::fromMinMax(Vec3(-500, -2, -500), Vec3(500, 30, 500));
    PerspectiveCamera camera;
    camera.wsEye = Vec3(10, 5, 3);
    camera.wsDirection = Vec3(1, -0.1, 0.3);
    camera.wsUp = Vec3(0, 1, 0);
    camera.zNear = 0.5;
    camera.zFar = 800;
    PerspectiveCamera before = camera;
    before.wsEye += Vec3(0.3, 0.0, -0.2);
    before.wsDirection += Vec3(0.0, 0.0, 0.01);

    std::vector<Vec3> alone, after;
    std::thread([&] { alone = sortedVertices(visibleSceneBody(camera, scene)); }).join();
    std::thread([&] {
        (void)visibleSceneBody(before, scene);
        after = sortedVertices(visibleSceneBody(camera, scene));
    }).join();
    EXPECT_EQ(alone, after);
    ConvexBody clipped = ConvexBody::fromAabb(sceneBoxForFocus(scene));
    clipped.clip(camera.wsFrustumPlanes());
    EXPECT_TRUE(sameVertices(visibleSceneBody(camera, scene), clipped, 1e-9));
}
