#include "shadowkit/visibility/receiver_mask.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

using namespace shadowkit::core;
using namespace shadowkit::visibility;

namespace {

// Sun straight overhead: map x = world x, map y = world -z (looking down), 100 m square.
Mat4 overheadMap() {
    const Mat4 lightFromWorld = glm::lookAt(Vec3(0, 100, 0), Vec3(0, 0, 0), Vec3(0, 0, -1));
    return glm::orthoRH_ZO(-50.0, 50.0, -50.0, 50.0, 0.0, 200.0) * lightFromWorld;
}
Aabb box(Vec3 lo, Vec3 hi) { return Aabb::fromMinMax(lo, hi); }

} // namespace

TEST(ReceiverMask, KeepsACasterAboveAVisibleReceiverOnly) {
    for (const bool linear : {false, true}) {
        const std::optional<Vec4> row = linear ? std::optional(Vec4(0, -1.0 / 200, 0, 0.5)) : std::nullopt;
        ReceiverMask mask(64, overheadMap(), row);
        mask.mark(Vec3(10, 0, 10)); // a visible point on the ground
        mask.finish(1);
        EXPECT_TRUE(mask.mayShadow(box(Vec3(9, 5, 9), Vec3(11, 8, 11))));        // straight above it
        EXPECT_FALSE(mask.mayShadow(box(Vec3(9, -8, 9), Vec3(11, -5, 11))));     // below it: farther from the sun
        EXPECT_FALSE(mask.mayShadow(box(Vec3(-30, 5, -30), Vec3(-28, 8, -28)))); // over unseen ground
        EXPECT_TRUE(mask.mayShadow(box(Vec3(11.6, 5, 10), Vec3(12, 8, 10.5))));  // one mask texel aside: the dilation
        EXPECT_FALSE(mask.mayShadow(box(Vec3(200, 5, 10), Vec3(210, 8, 11))));   // outside the map
    }
}

TEST(ReceiverMask, NoCasterThatCouldShadowAMarkedTexelIsCulled) {
    // Brute force against the definition: a box must be kept when some marked texel under
    // its footprint (dilated) holds a receiver farther from the light than the box's top.
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-55.0, 55.0), h(-5.0, 5.0), s(0.1, 12.0);
    const Mat4 map = overheadMap();
    ReceiverMask mask(32, map, std::nullopt);
    std::vector<Vec3> receivers;
    for (int i = 0; i < 40; ++i) receivers.push_back(Vec3(u(rng), h(rng), u(rng)));
    for (const Vec3& r : receivers) mask.mark(r);
    mask.finish(1);
    for (int i = 0; i < 5000; ++i) {
        const Vec3 c(u(rng), h(rng), u(rng)), e(s(rng), s(rng), s(rng));
        const Aabb b = box(c - e, c + e);
        // Needed: a receiver inside the map lies under the box (its x, z within the box's) and
        // below the box's top, i.e. farther from the overhead sun than the box's nearest point.
        bool needed = false;
        for (const Vec3& r : receivers) {
            const bool under = r.x >= b.min.x && r.x <= b.max.x && r.z >= b.min.z && r.z <= b.max.z;
            const bool inMap = std::abs(r.x) < 50 && std::abs(r.z) < 50;
            needed = needed || (under && inMap && r.y < b.max.y - 1e-6);
        }
        if (needed) {
            ASSERT_TRUE(mask.mayShadow(b)) << "box " << i;
        }
    }
}

TEST(ReceiverMask, AReceiverBehindAWarpCentreKeepsEverything) {
    const Mat4 perspective =
        glm::perspectiveRH_ZO(1.0, 1.0, 1.0, 100.0) * glm::lookAt(Vec3(0, 50, 0), Vec3(0, 0, 0), Vec3(0, 0, -1));
    ReceiverMask mask(16, perspective, std::nullopt);
    mask.mark(Vec3(0, 80, 0)); // above the centre: behind it
    mask.finish(0);
    EXPECT_TRUE(mask.everything());
    EXPECT_TRUE(mask.mayShadow(box(Vec3(30, 0, 30), Vec3(31, 1, 31))));
}

TEST(ReceiverMask, EmptyMaskCullsEveryCaster) {
    ReceiverMask mask(16, overheadMap(), std::nullopt);
    mask.finish(2);
    EXPECT_EQ(mask.markedTexels(), 0u);
    EXPECT_FALSE(mask.mayShadow(box(Vec3(-1, 0, -1), Vec3(1, 10, 1))));
}
