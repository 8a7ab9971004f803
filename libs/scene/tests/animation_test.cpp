// Movers: deterministic in time, on their circles over the ground, still at t = 0 where the
// still views have always seen them.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/forest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
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

TEST(Animation, ACircleAsKeysStraysFromItsArcByNoMoreThanAskedAndTurnsAsTheTrackTurns) {
    const scene::Scene s = forest(6);
    ASSERT_FALSE(s.tracks.empty());
    for (const double chord : {0.01, 0.05}) {
        for (const scene::Track& track : s.tracks) {
            const std::optional<scene::NodeMotion> keys = scene::circleAsKeys(track, s, chord);
            ASSERT_TRUE(keys);
            const scene::KeyframeChannel& translation = *keys->chain.at(0).translationKeys;
            const size_t n = translation.times.size() - 1; // intervals: the last key closes the loop
            EXPECT_GE(n, 16u);
            EXPECT_LE(n, 4096u);
            const double loop = 2.0 * std::numbers::pi * track.radius / std::abs(track.speed);
            EXPECT_NEAR(translation.times.back(), loop, 1e-9 * loop);
            // Midway between keys, where a chord strays most from its arc: r(1 − cos(π/N)) across,
            // within the bound asked, and as close to the ground; the turn is the track's to float
            // precision.
            double across = 0.0, up = 0.0;
            for (size_t k = 0; k < n; ++k) {
                const double t = (translation.times[k] + translation.times[k + 1]) / 2.0;
                const glm::dmat4 want(scene::trackTransform(track, s, t));
                const glm::dmat4 got = keys->sceneFromObjectAt(t);
                across = std::max(across, glm::length(glm::dvec2(got[3].x - want[3].x, got[3].z - want[3].z)));
                up = std::max(up, std::abs(got[3].y - want[3].y));
                for (int c = 0; c < 3; ++c)
                    EXPECT_LT(glm::length(glm::dvec3(got[c]) - glm::dvec3(want[c])), 1e-5) << "t = " << t;
                // A loop later, the same place.
                EXPECT_LT(glm::distance(glm::dvec3(keys->sceneFromObjectAt(t + loop)[3]), glm::dvec3(got[3])), 1e-6);
            }
            EXPECT_LE(across, chord + 1e-5) << "radius " << track.radius;
            EXPECT_LE(up, chord + 1e-5) << "radius " << track.radius;
        }
    }
    scene::Track still = s.tracks.front();
    still.speed = 0.0;
    EXPECT_FALSE(scene::circleAsKeys(still, s)) << "a mover that stands still needs no keys";
}
