// Movers: deterministic in time, on their circles over the ground, still at t = 0 where the
// still views have always seen them.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/forest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

using namespace shadowkit;

namespace {

scene::Scene forest(int movers) {
    scene::ForestOptions o;
    o.trees = 50;
    o.terrainSize = 200.0;
    o.terrainResolution = 32;
    o.movers = movers;
    return scene::makeForest(o);
}

core::Vec3 positionOf(const scene::Scene& s, const scene::Track& track) {
    return core::Vec3(s.batches[track.batch].worldFromObject[track.instance][3]);
}

} // namespace

TEST(Animation, EveryMoverHasATrackAndTimeZeroChangesNothing) {
    scene::Scene s = forest(6);
    ASSERT_EQ(s.tracks.size(), 6u);
    const scene::Scene before = s;
    std::vector<uint32_t> moved;
    scene::animate(s, 0.0, &moved);
    ASSERT_EQ(moved.size(), 6u);
    for (size_t b = 0; b < s.batches.size(); ++b)
        EXPECT_EQ(s.batches[b].worldFromObject, before.batches[b].worldFromObject);
    for (size_t k = 0; k < moved.size(); ++k) {
        const scene::Track& t = s.tracks[k];
        EXPECT_TRUE(s.batches[t.batch].dynamic);
        EXPECT_EQ(moved[k], s.globalIndex({t.batch, t.instance}));
        EXPECT_EQ(s.locate(moved[k])->batch, t.batch);
        EXPECT_EQ(s.locate(moved[k])->instance, t.instance);
    }
}

TEST(Animation, MoversFollowTheGroundAtTheirSpeedAndTheSameTimeGivesTheSamePlaces) {
    scene::Scene s = forest(8);
    for (const double t : {0.5, 3.0, 17.25}) {
        scene::animate(s, t);
        const scene::Scene first = s;
        scene::animate(s, 100.0);
        scene::animate(s, t);
        for (size_t b = 0; b < s.batches.size(); ++b)
            EXPECT_EQ(s.batches[b].worldFromObject, first.batches[b].worldFromObject) << t;
        for (const scene::Track& track : s.tracks) {
            const core::Vec3 p = positionOf(s, track);
            EXPECT_NEAR(std::hypot(p.x - track.centreX, p.z - track.centreZ), track.radius, 1e-3);
            EXPECT_NEAR(p.y, s.groundHeightAt(p.x, p.z) + track.lift, 1e-3);
        }
    }
    // Over a short step each covers speed × dt along its circle (the chord, to 1e-3).
    for (const scene::Track& track : s.tracks) {
        scene::animate(s, 1.0);
        const core::Vec3 a = positionOf(s, track);
        scene::animate(s, 1.1);
        const core::Vec3 b = positionOf(s, track);
        const double arc = std::abs(track.speed) * 0.1;
        EXPECT_NEAR(std::hypot(b.x - a.x, b.z - a.z), 2.0 * track.radius * std::sin(arc / (2.0 * track.radius)), 1e-3);
    }
}

TEST(Animation, SeveralSpeedsBothWaysAndAThousandMoversStayOnTheTerrain) {
    scene::Scene s = forest(1000);
    ASSERT_EQ(s.tracks.size(), 1000u);
    std::set<double> speeds;
    bool clockwise = false, anticlockwise = false;
    for (const scene::Track& t : s.tracks) {
        speeds.insert(std::abs(t.speed));
        clockwise |= t.speed > 0, anticlockwise |= t.speed < 0;
        EXPECT_LT(t.radius, 100.0); // inside the 200 m terrain
    }
    EXPECT_GE(speeds.size(), 4u);
    EXPECT_TRUE(clockwise && anticlockwise);
}
