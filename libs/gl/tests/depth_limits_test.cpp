// The limits benchmark (depth_limits.h) measures what it says: its fill draw writes every
// texel once per layer and its grid tiles the map exactly once, as GL counts them, so its
// rates are rates of known work. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/gl/depth_limits.h"

#include <gtest/gtest.h>

using namespace shadowkit;

namespace {
class DepthLimitsTest : public gl::testing::HeadlessGlTest {};
} // namespace

TEST_F(DepthLimitsTest, FillAndGridDrawsDoTheWorkTheirRatesCount) {
    const gl::DepthLimitsOptions small{
        .mapTexels = 96, .fillLayers = 5, .gridCells = 40, .largeTriangles = 6, .repeats = 2};
    const auto limits = gl::measureDepthLimits(small);
    ASSERT_TRUE(limits) << limits.error();
    // Back to front, every layer passes the depth test at every texel.
    EXPECT_EQ(limits->fillSamples, 5u * 96u * 96u);
    // 40 × 40 cells over 96² texels: cells do not fall on texel edges, and still every sample is
    // covered by exactly one triangle (GL's rasterisation rules): written once.
    EXPECT_EQ(limits->gridSamples, 96u * 96u);
    EXPECT_EQ(limits->smallTriangles, 2u * 40u * 40u);
    EXPECT_EQ(limits->largeTriangles, 6u);
    EXPECT_GT(limits->fillSamplesPerSecond, 0.0);
    EXPECT_GT(limits->smallTrianglesPerSecond, 0.0);
    EXPECT_GT(limits->largeTrianglesPerSecond, 0.0);
}

TEST_F(DepthLimitsTest, OptionsOutOfRangeAreRefusedByName) {
    EXPECT_EQ(gl::measureDepthLimits({.mapTexels = 8}).errorInfo().field, "limits.map_texels");
    EXPECT_EQ(gl::measureDepthLimits({.fillLayers = 0}).errorInfo().field, "limits.fill_layers");
    EXPECT_EQ(gl::measureDepthLimits({.gridCells = 5000}).errorInfo().field, "limits.grid_cells");
    EXPECT_EQ(gl::measureDepthLimits({.largeTriangles = 3}).errorInfo().field, "limits.large_triangles");
    EXPECT_EQ(gl::measureDepthLimits({.repeats = 0}).errorInfo().field, "limits.repeats");
}
