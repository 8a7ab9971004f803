// The filters' text form (the CLI, configuration files and reports share it) and its checks.
#include "shadowkit/core/bias.h"
#include "shadowkit/core/shadow_filter.h"

#include <gtest/gtest.h>

using namespace shadowkit::core;

TEST(ShadowFilterTest, EveryFilterNameParsesBackToItself) {
    for (const char* name : {"hard", "pcf2", "pcf:1", "pcf:9", "poisson:1", "poisson:32", "pcss", "pcss:1", "pcss:32",
                             "msm", "msm:0", "msm:8"}) {
        const auto f = parseFilter(name);
        ASSERT_TRUE(f) << name << ": " << f.error();
        EXPECT_EQ(filterName(*f), name);
        EXPECT_TRUE(validate(*f)) << name;
    }
    // pcss:16 is the default's long form: the short name is the one reports print.
    EXPECT_EQ(filterName(parseFilter("pcss:16").value()), "pcss");
    EXPECT_EQ(filterName(parseFilter("msm:2").value()), "msm");
    EXPECT_EQ(parseFilter("msm")->taps, kMsmBlurTexels);
    EXPECT_FALSE(isWideKernel(parseFilter("msm").value())); // one lookup at the receiver: no receiver plane
}

TEST(ShadowFilterTest, PcssTakesItsOwnDefaultsAndWidestKernel) {
    const FilterSettings pcss = parseFilter("pcss").value();
    EXPECT_EQ(pcss.kind, ShadowFilter::Pcss);
    EXPECT_EQ(pcss.taps, kPcssTaps);
    EXPECT_EQ(pcss.radiusTexels, kPcssMaxRadiusTexels);
    EXPECT_EQ(parseFilter("pcss:8")->radiusTexels, kPcssMaxRadiusTexels);
    // It reads texels away from the receiver: receiver-plane bias, as the wide PCF kernels.
    EXPECT_TRUE(isWideKernel(pcss));
    for (const TechniqueInfo& t : allTechniques())
        EXPECT_TRUE(recommendedBias(t.technique, DepthLayout::Linear, pcss).receiverPlane);
}

TEST(ShadowFilterTest, MalformedNamesAndOutOfRangeTapsAreOneErrorNamingTheFilter) {
    for (const char* name :
         {"", "soft", "pcss:", "pcss:0", "pcss:33", "pcss:4x", "pcss:-1", "poisson", "pcf:10", "msm:9", "msm:-1"}) {
        const auto f = parseFilter(name);
        ASSERT_FALSE(f) << name;
        EXPECT_EQ(f.errorInfo().field, "filter") << name;
        EXPECT_NE(f.error().find("pcss[:N]"), std::string::npos) << f.error(); // the choices are listed
        EXPECT_NE(f.error().find("msm[:N]"), std::string::npos) << f.error();
    }
    FilterSettings f{ShadowFilter::Pcss, 40};
    EXPECT_EQ(validate(f).errorInfo().field, "filter.taps");
    EXPECT_NE(validate(f).error().find("pcss"), std::string::npos);
    f = {ShadowFilter::Pcss, 16, 0.0f};
    EXPECT_EQ(validate(f).errorInfo().field, "filter.radius");
}
