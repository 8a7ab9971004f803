// Keyframed motion (keyframes.h) against values worked independently: a cubic polynomial that
// Hermite interpolation must reproduce exactly, rotations by angles about one axis, and a
// chain whose composition is checked against a rotation done by hand.
#include "shadowkit/scene/keyframes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace shadowkit::scene;

namespace {

using Interpolation = KeyframeChannel::Interpolation;

KeyframeChannel keyedChannel(Interpolation interpolation, std::vector<double> times, std::vector<glm::dvec4> values,
                             double loopSeconds = 0.0) {
    KeyframeChannel c;
    c.interpolation = interpolation;
    c.times = std::move(times);
    c.values = std::move(values);
    c.loopSeconds = loopSeconds;
    return c;
}

// A turn of `degrees` about +y as glTF writes a quaternion: (x, y, z, w).
glm::dvec4 aboutY(double degrees) {
    const double half = glm::radians(degrees) / 2.0;
    return {0.0, std::sin(half), 0.0, std::cos(half)};
}

// The angle about +y of a unit quaternion that turns about +y.
double degreesAboutY(const glm::dvec4& q) {
    EXPECT_NEAR(q.x, 0.0, 1e-12);
    EXPECT_NEAR(q.z, 0.0, 1e-12);
    EXPECT_NEAR(glm::length(q), 1.0, 1e-12);
    return glm::degrees(2.0 * std::atan2(q.y, q.w));
}

} // namespace

TEST(KeyframesTest, LinearAndStepBetweenKeysAndClampedOutsideThem) {
    const KeyframeChannel linear = keyedChannel(Interpolation::Linear, {1.0, 3.0}, {{0, 0, 0, 0}, {4, -2, 8, 0}});
    EXPECT_EQ(linear.at(2.0, false), glm::dvec4(2, -1, 4, 0));
    EXPECT_EQ(linear.at(1.5, false), glm::dvec4(1, -0.5, 2, 0));
    EXPECT_EQ(linear.at(0.0, false), glm::dvec4(0, 0, 0, 0)) << "before the first key: the first value";
    EXPECT_EQ(linear.at(7.0, false), glm::dvec4(4, -2, 8, 0)) << "after the last key: the last value";
    const KeyframeChannel step =
        keyedChannel(Interpolation::Step, {0.0, 1.0, 2.0}, {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}});
    EXPECT_EQ(step.at(0.99, false).x, 1.0);
    EXPECT_EQ(step.at(1.0, false).x, 2.0) << "a key holds from its own time";
    EXPECT_EQ(step.at(1.7, false).x, 2.0);
    const KeyframeChannel single = keyedChannel(Interpolation::Linear, {0.5}, {{9, 9, 9, 0}});
    EXPECT_EQ(single.at(-3.0, false), glm::dvec4(9, 9, 9, 0)) << "one key: its value at every time";
    EXPECT_EQ(single.at(12.0, false), glm::dvec4(9, 9, 9, 0));
}

TEST(KeyframesTest, AnAnimationLoopsOverItsLengthForwardAndBackInTime) {
    const KeyframeChannel c = keyedChannel(Interpolation::Linear, {0.0, 2.0}, {{0, 0, 0, 0}, {2, 0, 0, 0}}, 4.0);
    EXPECT_DOUBLE_EQ(c.at(1.0, false).x, 1.0);
    EXPECT_DOUBLE_EQ(c.at(5.0, false).x, 1.0);
    EXPECT_DOUBLE_EQ(c.at(3.0, false).x, 2.0) << "past its own last key, before the animation's length: held";
    EXPECT_DOUBLE_EQ(c.at(-3.0, false).x, 1.0) << "t = −3 is t = 1 of the loop";
}

// Hermite interpolation with the tangents a curve's derivatives reproduces any cubic exactly:
// p(t) = t³ − 2t² + 0.5, p'(t) = 3t² − 4t, keyed at uneven times.
TEST(KeyframesTest, CubicSplineReproducesACubicFromItsDerivatives) {
    const auto p = [](double t) { return t * t * t - 2 * t * t + 0.5; };
    const auto dp = [](double t) { return 3 * t * t - 4 * t; };
    std::vector<double> times{0.0, 0.4, 1.5, 2.0};
    std::vector<glm::dvec4> values;
    for (double t : times) {
        values.push_back({dp(t), 0, 0, 0}); // in-tangent
        values.push_back({p(t), 0, 0, 0});
        values.push_back({dp(t), 0, 0, 0}); // out-tangent
    }
    const KeyframeChannel c = keyedChannel(Interpolation::CubicSpline, times, values);
    for (double t = 0.0; t <= 2.0; t += 0.05) EXPECT_NEAR(c.at(t, false).x, p(t), 1e-12) << "t = " << t;
}

TEST(KeyframesTest, RotationsTurnAlongTheShorterArcAndStayUnit) {
    const KeyframeChannel c = keyedChannel(Interpolation::Linear, {0.0, 1.0}, {aboutY(0.0), aboutY(90.0)});
    EXPECT_NEAR(degreesAboutY(c.at(0.5, true)), 45.0, 1e-9);
    EXPECT_NEAR(degreesAboutY(c.at(0.25, true)), 22.5, 1e-9) << "slerp turns at an even rate";
    // The second key written as −q (the same rotation): still 45°, not the long way round.
    const KeyframeChannel negated = keyedChannel(Interpolation::Linear, {0.0, 1.0}, {aboutY(0.0), -aboutY(90.0)});
    EXPECT_NEAR(degreesAboutY(negated.at(0.5, true)), 45.0, 1e-9);
    // 350° to 10°: 20° through 0, not 340° the other way.
    const KeyframeChannel across = keyedChannel(Interpolation::Linear, {0.0, 1.0}, {aboutY(350.0), aboutY(10.0)});
    const double half = degreesAboutY(across.at(0.5, true));
    EXPECT_NEAR(std::remainder(half, 360.0), 0.0, 1e-9);
    // A quaternion written unnormalised (an exporter's rounding) comes back unit.
    const KeyframeChannel loose = keyedChannel(Interpolation::Step, {0.0}, {2.0 * aboutY(30.0)});
    EXPECT_NEAR(degreesAboutY(loose.at(0.0, true)), 30.0, 1e-9);
}

// A parent turning +90° about y over a second, a child fixed 1 m along its +x: at t = 1 the
// child stands at (0, 0, −1) — +x turned +90° about +y, by the right-hand rule.
TEST(KeyframesTest, AChainComposesParentBeforeChildAndFixedNodesFold) {
    NodeMotion motion;
    MotionNode parent;
    parent.translation = {5, 0, 0};
    parent.rotationKeys = std::make_shared<const KeyframeChannel>(
        keyedChannel(Interpolation::Linear, {0.0, 1.0}, {aboutY(0.0), aboutY(90.0)}));
    motion.chain.push_back(parent);
    glm::dmat4 parentFromChild(1.0);
    parentFromChild[3] = glm::dvec4(1, 0, 0, 1);
    motion.chain.push_back({.fixed = parentFromChild});
    motion.nodeFromObject[3] = glm::dvec4(0, 2, 0, 1); // 2 m up in the child's frame
    const glm::dvec4 origin(0, 0, 0, 1);
    const glm::dvec4 at0 = motion.sceneFromObjectAt(0.0) * origin;
    const glm::dvec4 at1 = motion.sceneFromObjectAt(1.0) * origin;
    EXPECT_NEAR(glm::distance(glm::dvec3(at0), glm::dvec3(6, 2, 0)), 0.0, 1e-12);
    EXPECT_NEAR(glm::distance(glm::dvec3(at1), glm::dvec3(5, 2, -1)), 0.0, 1e-12);
    // The scale of a node scales what hangs below it, after its rotation.
    motion.chain[0].scale = {2, 2, 2};
    EXPECT_NEAR(glm::distance(glm::dvec3(motion.sceneFromObjectAt(1.0) * origin), glm::dvec3(5, 4, -2)), 0.0, 1e-12);
}
