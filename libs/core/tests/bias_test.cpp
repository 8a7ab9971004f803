#include "shadowkit/core/bias.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace shadowkit::core;

TEST(BiasTest, RecommendedBiasTurnsReceiverPlaneBiasOnForWideKernelsOnly) {
    // Whether the recommended figures beat the alternatives is measured against ray-traced
    // truth (tests/eval_integration_test.cpp); here: the rule every caller inherits.
    for (const TechniqueInfo& t : allTechniques())
        for (DepthLayout layout : {DepthLayout::Hyperbolic, DepthLayout::Linear}) {
            for (const FilterSettings f :
                 {FilterSettings{ShadowFilter::Hard, 1}, FilterSettings{ShadowFilter::Pcf2, 1}}) {
                const BiasSettings b = recommendedBias(t.technique, layout, f);
                EXPECT_TRUE(validate(b)) << t.name;
                EXPECT_FALSE(b.receiverPlane) << t.name;
            }
            for (const FilterSettings f :
                 {FilterSettings{ShadowFilter::PcfGrid, 3}, FilterSettings{ShadowFilter::Poisson, 16}}) {
                const BiasSettings b = recommendedBias(t.technique, layout, f);
                EXPECT_TRUE(b.receiverPlane) << t.name;
                // The filter changes the receiver side only: the caster-side bias stays.
                EXPECT_EQ(b.slope, recommendedBias(t.technique, layout).slope);
                EXPECT_EQ(b.constant, recommendedBias(t.technique, layout).constant);
            }
        }
}

TEST(BiasTest, OutOfRangeValuesAreNamed) {
    BiasSettings b;
    b.slope = -1;
    EXPECT_EQ(validate(b).errorInfo().field, "bias.slope");
    b = BiasSettings{};
    b.normalOffset = 20;
    EXPECT_EQ(validate(b).errorInfo().field, "bias.normal_offset");
    b = BiasSettings{};
    b.normalOffsetFootprint = std::nan("");
    EXPECT_EQ(validate(b).errorInfo().field, "bias.normal_offset_footprint");
    b.normalOffsetFootprint = -0.5;
    EXPECT_EQ(validate(b).errorInfo().field, "bias.normal_offset_footprint");
    b.normalOffsetFootprint = 0.5;
    EXPECT_TRUE(validate(b));
}
