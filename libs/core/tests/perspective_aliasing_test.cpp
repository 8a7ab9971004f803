#include "shadowkit/core/perspective_aliasing.h"

#include <gtest/gtest.h>

using namespace shadowkit::core;

// Wimmer et al. 2004, Figure 6: z_n = 1, z_f = 100 (values from equation (3)).
TEST(PerspectiveAliasingTest, UniformPeaksAt99AtTheNearPlane) {
    const AliasingCurve c = sampleAliasing(1, 100, kUniformN);
    EXPECT_NEAR(c.max, 99.0, 1e-9);
    EXPECT_EQ(c.argmaxZ, 1.0);
    EXPECT_NEAR(perspectiveAliasing(10, 1, 100, kUniformN), 9.9, 1e-12);
    EXPECT_NEAR(perspectiveAliasing(100, 1, 100, kUniformN), 0.99, 1e-12);
}

TEST(PerspectiveAliasingTest, PsmPeaksAt99AtTheFarPlane) {
    const AliasingCurve c = sampleAliasing(1, 100, 1.0); // n = z_n
    EXPECT_NEAR(c.max, 99.0, 1e-9);
    EXPECT_EQ(c.argmaxZ, 100.0);
    EXPECT_NEAR(perspectiveAliasing(1, 1, 100, 1.0), 0.99, 1e-12);
    EXPECT_NEAR(perspectiveAliasing(10, 1, 100, 1.0), 9.9, 1e-12);
}

TEST(PerspectiveAliasingTest, LispsmOptimumIsElevenWithEqualPeaksOf9Point9) {
    const double n = lispsmOptimalN(1, 100);
    EXPECT_NEAR(n, 11.0, 1e-12);
    EXPECT_NEAR(perspectiveAliasing(1, 1, 100, n), 9.9, 1e-9);
    EXPECT_NEAR(perspectiveAliasing(100, 1, 100, n), 9.9, 1e-9);
    EXPECT_NEAR(perspectiveAliasing(10, 1, 100, n), 3.27, 5e-3);
    const AliasingCurve c = sampleAliasing(1, 100, n);
    EXPECT_NEAR(c.max, 9.9, 1e-9);
    for (double v : c.dpds) EXPECT_LE(v, 9.9 + 1e-9);
    // Any other n has a larger maximum: n_opt is the minimax choice.
    for (double other : {5.0, 10.0, 12.0, 30.0}) EXPECT_GT(sampleAliasing(1, 100, other).max, c.max);
}

TEST(PerspectiveAliasingTest, LargeNConvergesToUniformWithoutOverflow) {
    EXPECT_NEAR(perspectiveAliasing(3, 1, 100, 1e12), perspectiveAliasing(3, 1, 100, kUniformN), 1e-6);
}

TEST(PerspectiveAliasingTest, GeneralPredictionReducesToEquationThreeAtNinetyDegrees) {
    for (double n : {1.0, 11.0, 40.0, kUniformN})
        EXPECT_NEAR(predictedMaxAliasing(1, 100, 99, 1.0, n), sampleAliasing(1, 100, n).max, 1e-9) << n;
    // Tilted towards the light, the same n leaves more error than at 90°.
    EXPECT_GT(predictedMaxAliasing(1, 100, 99, 0.5, 11.0), predictedMaxAliasing(1, 100, 99, 1.0, 11.0));
}
