#include "shadowkit/core/bias.h"

#include <gtest/gtest.h>

using namespace shadowkit::core;

TEST(BiasTest, RecommendedBiasIsValidForEveryTechniqueAndLayout) {
    for (const TechniqueInfo& t : allTechniques())
        for (DepthLayout layout : {DepthLayout::Hyperbolic, DepthLayout::Linear}) {
            const BiasSettings b = recommendedBias(t.technique, layout);
            EXPECT_TRUE(validate(b)) << t.name;
            EXPECT_GT(b.slope + b.constant + b.normalOffset, 0.0) << t.name << ": no bias at all means acne";
        }
    // Uniform maps have large texels: no normal offset there (it would detach shadows).
    EXPECT_EQ(recommendedBias(Technique::Focused, DepthLayout::Hyperbolic).normalOffset, 0.0);
}

TEST(BiasTest, OutOfRangeValuesAreNamed) {
    BiasSettings b;
    b.slope = -1;
    EXPECT_NE(validate(b).error().find("slope"), std::string::npos);
    b = BiasSettings{};
    b.normalOffset = 20;
    EXPECT_NE(validate(b).error().find("normal offset"), std::string::npos);
}
