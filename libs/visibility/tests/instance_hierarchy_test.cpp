#include "shadowkit/core/camera.h"
#include "shadowkit/visibility/instance_hierarchy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace shadowkit::core;
using namespace shadowkit::visibility;

namespace {

std::vector<Aabb> randomBoxes(std::mt19937& rng, size_t n, double world) {
    std::uniform_real_distribution<double> pos(-world, world), size(0.1, 20.0);
    std::vector<Aabb> boxes;
    for (size_t i = 0; i < n; ++i) {
        const Vec3 c(pos(rng), 0.02 * pos(rng), pos(rng)), h(size(rng), size(rng), size(rng));
        boxes.push_back(Aabb::fromMinMax(c - h, c + h));
    }
    return boxes;
}

PerspectiveCamera randomCamera(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    PerspectiveCamera cam;
    cam.wsEye = Vec3(300 * u(rng), 5 + 40 * std::abs(u(rng)), 300 * u(rng));
    cam.wsDirection = Vec3(u(rng), -0.5 * std::abs(u(rng)), u(rng));
    if (glm::length(cam.wsDirection) < 0.1) cam.wsDirection = Vec3(0, 0, -1);
    cam.zNear = 0.5;
    cam.zFar = 50 + 400 * std::abs(u(rng));
    return cam;
}

bool outsideSome(std::span<const HalfSpace> volume, const Aabb& b) {
    for (const HalfSpace& h : volume) {
        bool allOut = true;
        for (const Vec3& c : b.corners()) allOut = allOut && glm::dot(Vec3(h), c) + h.w < 0.0;
        if (allOut) return true;
    }
    return false;
}

std::vector<uint32_t> sorted(std::vector<uint32_t> v) {
    std::sort(v.begin(), v.end());
    return v;
}

} // namespace

TEST(InstanceHierarchyTest, QueryEqualsTheBruteForceCornerTestForRandomFrusta) {
    std::mt19937 rng(7);
    const std::vector<Aabb> boxes = randomBoxes(rng, 5000, 500);
    const InstanceHierarchy tree(boxes);
    size_t total = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const PerspectiveCamera cam = randomCamera(rng);
        const auto volume = clipVolume(cam.clipFromWorld(), trial % 2 == 0);
        std::vector<uint32_t> expected;
        for (uint32_t i = 0; i < boxes.size(); ++i)
            if (!outsideSome(volume, boxes[i])) expected.push_back(i);
        std::vector<uint32_t> got;
        tree.query(volume, got);
        ASSERT_EQ(sorted(got), expected) << "trial " << trial;
        total += got.size();
    }
    EXPECT_GT(total, 0u);                  // the frusta do see something
    EXPECT_LT(total, 200u * boxes.size()); // and not everything
}

TEST(InstanceHierarchyTest, EveryBoxHoldingAPointOfTheFrustumIsFound) {
    // Conservativeness against the geometry itself, not against the same corner test.
    std::mt19937 rng(11);
    const std::vector<Aabb> boxes = randomBoxes(rng, 3000, 200);
    const InstanceHierarchy tree(boxes);
    std::uniform_real_distribution<double> u(-1.0, 1.0), depth(0.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
        const PerspectiveCamera cam = randomCamera(rng);
        const Mat4 worldFromClip = glm::inverse(cam.clipFromWorld());
        std::vector<uint32_t> got;
        tree.query(clipVolume(cam.clipFromWorld()), got);
        std::sort(got.begin(), got.end());
        for (int k = 0; k < 200; ++k) {
            const Vec4 p = worldFromClip * Vec4(u(rng), u(rng), depth(rng), 1.0);
            const Vec3 ws = Vec3(p) / p.w;
            for (uint32_t i = 0; i < boxes.size(); ++i) {
                if (boxes[i].contains(ws)) {
                    ASSERT_TRUE(std::binary_search(got.begin(), got.end(), i)) << i;
                }
            }
        }
    }
}

TEST(InstanceHierarchyTest, BoundsAreTheUnionAndFollowUpdates) {
    std::mt19937 rng(3);
    std::vector<Aabb> boxes = randomBoxes(rng, 1000, 100);
    InstanceHierarchy tree(boxes);
    Aabb all;
    for (const Aabb& b : boxes) all.extend(b);
    EXPECT_EQ(tree.bounds().min, all.min);
    EXPECT_EQ(tree.bounds().max, all.max);

    // Move a tenth of the items far away: bounds grow to hold them, queries find them there.
    for (uint32_t i = 0; i < boxes.size(); i += 10) {
        boxes[i] = Aabb::fromMinMax(boxes[i].min + Vec3(5000, 0, 0), boxes[i].max + Vec3(5000, 0, 0));
        tree.update(i, boxes[i]);
    }
    all = Aabb{};
    for (const Aabb& b : boxes) all.extend(b);
    EXPECT_EQ(tree.bounds().max, all.max);
    const std::vector<HalfSpace> farSide = {HalfSpace(1, 0, 0, -4000)}; // x >= 4000
    std::vector<uint32_t> got;
    tree.query(farSide, got);
    got = sorted(got);
    ASSERT_EQ(got.size(), 100u);
    for (size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got[k], 10 * k);
}

TEST(InstanceHierarchyTest, DegenerateInputsHaveDefinedAnswers) {
    const InstanceHierarchy empty(std::span<const Aabb>{});
    EXPECT_TRUE(empty.bounds().isEmpty());
    std::vector<uint32_t> got;
    empty.query(std::vector<HalfSpace>{HalfSpace(0, 1, 0, 0)}, got);
    EXPECT_TRUE(got.empty());

    // Coincident boxes (no centre extent to split by) and an empty box among them.
    std::vector<Aabb> same(100, Aabb::fromMinMax(Vec3(-1), Vec3(1)));
    same[50] = Aabb{};
    const InstanceHierarchy stacked(same);
    stacked.query(std::vector<HalfSpace>{}, got); // no half-space: everything that exists
    EXPECT_EQ(got.size(), 99u);
    got.clear();
    stacked.query(std::vector<HalfSpace>{HalfSpace(0, 1, 0, -2)}, got); // y >= 2: nothing
    EXPECT_TRUE(got.empty());
}

TEST(ClipVolumeTest, HalfSpacesAgreeWithTheClipTestForPerspectiveAndOrthographicMaps) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-60.0, 60.0);
    PerspectiveCamera cam;
    cam.wsEye = Vec3(1, 2, 3);
    cam.wsDirection = Vec3(0.3, -0.2, -1);
    cam.zFar = 50;
    const Mat4 ortho = orthoZeroToOne(-10, 14, -6, 9, 2, 40) * cam.viewFromWorld();
    for (const Mat4& m : {cam.clipFromWorld(), ortho}) {
        const auto volume = clipVolume(m);
        for (int k = 0; k < 20000; ++k) {
            const Vec3 p(u(rng), u(rng), u(rng));
            const Vec4 c = m * Vec4(p, 1.0);
            const bool clipInside = c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && c.z >= 0 && c.z <= c.w;
            bool planesInside = true;
            for (const HalfSpace& h : volume) planesInside = planesInside && glm::dot(Vec3(h), p) + h.w >= 0.0;
            ASSERT_EQ(clipInside, planesInside) << p.x << " " << p.y << " " << p.z;
        }
    }
}

// Items that wander stretch the leaves they were built into: the surface-area cost says how
// much, and a rebuild over the current boxes brings it back while queries stay exact.
TEST(InstanceHierarchyTest, WanderingItemsDegradeTheTreeAndARebuildRestoresIt) {
    std::mt19937 rng(21);
    std::vector<Aabb> boxes = randomBoxes(rng, 4000, 500);
    InstanceHierarchy tree(boxes);
    EXPECT_DOUBLE_EQ(tree.degradation(), 1.0);
    // A tenth of the items jump somewhere else in the world.
    const std::vector<Aabb> elsewhere = randomBoxes(rng, 400, 500);
    for (uint32_t k = 0; k < 400; ++k) tree.update(10 * k, boxes[10 * k] = elsewhere[k]);
    EXPECT_GT(tree.degradation(), 1.25);
    tree.rebuild();
    EXPECT_LT(tree.degradation(), 1.0 + 1e-12);
    EXPECT_EQ(tree.size(), boxes.size());
    for (int trial = 0; trial < 50; ++trial) {
        const auto volume = clipVolume(randomCamera(rng).clipFromWorld());
        std::vector<uint32_t> expected, got;
        for (uint32_t i = 0; i < boxes.size(); ++i)
            if (!outsideSome(volume, boxes[i])) expected.push_back(i);
        tree.query(volume, got);
        ASSERT_EQ(sorted(got), expected) << "trial " << trial;
    }
}
