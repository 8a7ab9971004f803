// The soft truth (the sun as a disk) against closed forms: its sample directions fill the cone
// uniformly, a point-like sun gives the hard truth exactly, a straight edge's penumbra is the
// disk's chord-area fraction, and two independent sample sets agree within their errors.
#include "truth_scenes.h"

#include "shadowkit/eval/html_report.h"
#include "shadowkit/eval/maps.h"
#include "shadowkit/eval/report.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace shadowkit;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A ground slab with its top at y = 0 and a box caster of half extents `half` centred at `centre`.
scene::Scene groundAndBox(const glm::vec3& centre, const glm::vec3& half) {
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), half, glm::vec3(0.8f));
    return test::groundAnd(box, glm::translate(glm::mat4(1.0f), centre));
}

// Ground points (y = 0, facing up) at the given x, z = 0: a one-row TruthBuffers.
eval::TruthBuffers groundPoints(const std::vector<double>& xs) {
    eval::TruthBuffers t;
    t.width = static_cast<int>(xs.size()), t.height = 1;
    for (double x : xs) {
        t.surfaceId.push_back(1);
        t.viewDepth.push_back(1.0f);
        t.wsPosition.push_back({x, 0.0, 0.0});
        t.wsNormal.push_back({0.0f, 1.0f, 0.0f});
        t.facesLight.push_back(1);
        t.lit.push_back(1);
    }
    return t;
}

} // namespace

TEST(SoftTruthTest, ConeDirectionsFillTheConeUniformlyInSolidAngle) {
    for (const core::Vec3 axis : {core::Vec3(0, 1, 0), core::Vec3(0, 0, -1), glm::normalize(core::Vec3(1, 2, -3))}) {
        const double halfAngle = 0.5 * 0.53 * kPi / 180.0; // the real sun: 4.6 mrad
        const double capArea = 1.0 - std::cos(halfAngle);
        double meanFraction = 0.0;
        core::Vec3 mean(0.0);
        const int k = 64;
        for (int y = 0; y < k; ++y)
            for (int x = 0; x < k; ++x) {
                const core::Vec3 d = eval::coneDirection(axis, halfAngle, (x + 0.5) / k, (y + 0.5) / k);
                EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
                const double angle = std::acos(std::min(1.0, glm::dot(d, axis)));
                ASSERT_LE(angle, halfAngle * (1.0 + 1e-6));
                // Uniform in solid angle: the cap fraction (1 - cos θ) / (1 - cos α) is uniform on [0, 1].
                meanFraction += (1.0 - glm::dot(d, axis)) / capArea;
                mean += d;
            }
        EXPECT_NEAR(meanFraction / (k * k), 0.5, 2e-3) << "axis " << axis.x << "," << axis.y << "," << axis.z;
        // Symmetric round the axis: the mean direction is the axis (a half-disk would tilt it by ~α/2).
        const double tilt = std::acos(std::min(1.0, glm::dot(glm::normalize(mean), axis)));
        EXPECT_LT(tilt, 0.01 * halfAngle);
    }
}

TEST(SoftTruthTest, APointLikeSunIsTheHardTruthExactly) {
    const scene::Scene s = groundAndBox({0, 2.5f, 0}, {1, 0.5f, 1.5f});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50, 120).value();
    const eval::TruthBuffers hard = eval::computeTruth(**rays, test::cameraLookingAtOrigin(), sun, 160, 120);
    const eval::SoftTruth soft = eval::computeSoftTruth(**rays, hard, {sun.wsTowardsLight(), 0.0});
    int shadowed = 0;
    for (size_t i = 0; i < hard.surfaceId.size(); ++i) {
        if (hard.surfaceId[i] == 0 || !hard.facesLight[i]) {
            EXPECT_TRUE(std::isnan(soft.visibility[i]));
            continue;
        }
        ASSERT_EQ(soft.visibility[i], hard.lit[i] ? 1.0f : 0.0f) << "pixel " << i;
        shadowed += !hard.lit[i];
    }
    EXPECT_GT(shadowed, 100);
    EXPECT_EQ(soft.penumbraPoints, 0u);
}

TEST(SoftTruthTest, AStraightEdgesPenumbraIsTheDisksChordAreaFraction) {
    // A plate covering x < 0 at height h under an overhead sun of angular radius α: from ground
    // point x the plate's edge is at angle atan(x / h) from the disk's centre, so the visible
    // fraction is the disk's area beyond a chord at c = atan(x / h) / α from its centre:
    // 1 - (acos c - c sqrt(1 - c²)) / π. The penumbra is 2 h tan α wide.
    const double h = 10.0, diameterDegrees = 2.0, alpha = 0.5 * diameterDegrees * kPi / 180.0;
    const scene::Scene s = groundAndBox({-20.0f, float(h) + 0.05f, 0}, {20, 0.05f, 20});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const double halfWidth = h * std::tan(alpha);
    std::vector<double> xs;
    for (int i = -24; i <= 24; ++i) xs.push_back(halfWidth * i / 20.0); // across it and a little beyond
    eval::SoftTruthOptions options;
    options.samples = 1024;
    const eval::SoftTruth soft =
        eval::computeSoftTruth(**rays, groundPoints(xs), {{0, 1, 0}, diameterDegrees}, options);
    double meanError = 0.0;
    for (size_t i = 0; i < xs.size(); ++i) {
        const double c = std::clamp(std::atan(xs[i] / h) / alpha, -1.0, 1.0);
        const double expected = 1.0 - (std::acos(c) - c * std::sqrt(1.0 - c * c)) / kPi;
        // Sampled points: within 4 standard errors (and the small-angle model's 0.005); probe-decided
        // ones within the 1.3 % the rim's probes guarantee.
        EXPECT_NEAR(soft.visibility[i], expected, 4.0 * soft.standardError[i] + 0.013) << "x = " << xs[i];
        meanError += std::abs(soft.visibility[i] - expected);
    }
    EXPECT_LT(meanError / static_cast<double>(xs.size()), 0.01);
    EXPECT_EQ(soft.visibility.front(), 0.0f); // beyond the penumbra: umbra and full sun
    EXPECT_EQ(soft.visibility.back(), 1.0f);
    EXPECT_GE(soft.penumbraPoints, 35u); // the 39 points strictly inside (a probe set may miss the rim)
}

TEST(SoftTruthTest, TwoIndependentSampleSetsAgreeWithinTheirStandardErrors) {
    const scene::Scene s = groundAndBox({0, 2.5f, 0}, {1, 0.5f, 1.5f});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50, 120).value();
    const eval::TruthBuffers hits = eval::computeTruth(**rays, test::cameraLookingAtOrigin(), sun, 160, 120);
    const eval::SunDisk disk{sun.wsTowardsLight(), 10.0}; // a large sun: a penumbra several pixels wide
    eval::SoftTruthOptions a, b;
    b.seed = 2;
    const eval::SoftTruth first = eval::computeSoftTruth(**rays, hits, disk, a);
    const eval::SoftTruth second = eval::computeSoftTruth(**rays, hits, disk, b);
    int both = 0, outside = 0, differ = 0;
    for (size_t i = 0; i < hits.surfaceId.size(); ++i) {
        if (first.standardError[i] == 0.0f || second.standardError[i] == 0.0f) continue; // a probe-decided point
        ++both;
        const double sigma = std::hypot(first.standardError[i], second.standardError[i]);
        outside += std::abs(first.visibility[i] - second.visibility[i]) > 3.0 * sigma;
        differ += first.visibility[i] != second.visibility[i];
    }
    EXPECT_GT(both, 100);
    // Beyond 3 sigma for at most 1 % (a normal law gives 0.3 %; the bound overestimates sigma).
    EXPECT_LE(outside, both / 100);
    EXPECT_GT(differ, both / 2); // independent sets: not the same rays twice
}

TEST(SoftTruthTest, SoftFiguresAreTheMeanErrorsOverTheValidPixelsAndThePenumbra) {
    using PC = eval::PixelClass;
    eval::SoftTruth soft;
    soft.visibility = {1.0f, 0.0f, 0.5f, 0.25f, std::nanf(""), 0.5f, 1.0f};
    soft.seconds = 2.0;
    soft.rays = 42;
    const std::vector<float> rendered = {1.0f, 1.0f, 0.0f, 0.25f, 0.0f, 1.0f, 0.0f};
    // The last two pixels are not valid in the hard comparison (excluded, not evaluated); the fifth
    // has no soft truth.
    const std::vector<PC> classes = {PC::LitCorrect, PC::FalseLit, PC::ShadowCorrect, PC::LitCorrect,
                                     PC::LitCorrect, PC::Excluded, PC::NotEvaluated};
    const eval::SoftFigures f = eval::compareSoft(rendered, soft, classes, 0.53);
    EXPECT_EQ(f.comparedPx, 4);
    EXPECT_EQ(f.penumbraPx, 2); // visibilities 0.5 and 0.25
    EXPECT_DOUBLE_EQ(f.softMae, (0.0 + 1.0 + 0.5 + 0.0) / 4.0);
    EXPECT_DOUBLE_EQ(f.penumbraMae, (0.5 + 0.0) / 2.0);
    EXPECT_DOUBLE_EQ(f.softWrongPct, 50.0); // errors 1 and 0.5 exceed 0.25
    EXPECT_EQ(f.truthRays, 42u);
    EXPECT_DOUBLE_EQ(f.sunAngleDegrees, 0.53);
}

TEST(SoftTruthTest, ThePenumbraWidthRatioIsTheRenderedBandsWidthOverTheTrueOnes) {
    // One row across a straight edge: the true visibility ramps from 1 to 0 over 20 pixels, the
    // rendered one over 10 (too hard), 40 (too soft) or not at all (the hard test).
    const int width = 100;
    auto ramp = [&](double widthPx) {
        std::vector<float> v(width);
        for (int x = 0; x < width; ++x)
            v[x] = static_cast<float>(std::clamp(0.5 - (x + 0.5 - 50.0) / widthPx, 0.0, 1.0));
        return v;
    };
    eval::SoftTruth soft;
    soft.width = width, soft.height = 1;
    soft.visibility = ramp(20.0);
    const std::vector<eval::PixelClass> classes(width, eval::PixelClass::LitCorrect);
    EXPECT_NEAR(eval::compareSoft(ramp(10.0), soft, classes, 0.53).penumbraWidthRatio, 0.5, 0.06);
    EXPECT_NEAR(eval::compareSoft(ramp(40.0), soft, classes, 0.53).penumbraWidthRatio, 2.0, 0.06);
    EXPECT_NEAR(eval::compareSoft(soft.visibility, soft, classes, 0.53).penumbraWidthRatio, 1.0, 1e-12);
    EXPECT_EQ(eval::compareSoft(ramp(1e-6), soft, classes, 0.53).penumbraWidthRatio, 0.0); // hard edges
    // No true penumbra (a point-like sun's hard truth): no ratio to give.
    soft.visibility = ramp(1e-6);
    EXPECT_TRUE(std::isnan(eval::compareSoft(ramp(10.0), soft, classes, 0.53).penumbraWidthRatio));
}

TEST(SoftTruthTest, TheFiguresLineSaysAHardShadowIsHardAndAMissingWidthIsMissing) {
    eval::SoftFigures figures;
    figures.penumbraWidthRatio = 0.93;
    EXPECT_NE(eval::softFiguresLine(figures).find("penumbra width ×0.93"), std::string::npos);
    figures.penumbraWidthRatio = 0.0;
    const std::string hard = eval::softFiguresLine(figures);
    EXPECT_NE(hard.find("penumbrae drawn hard (width ×0)"), std::string::npos) << hard;
    EXPECT_EQ(hard.find("×0.00"), std::string::npos) << hard;
    // No true penumbra to measure a width against (a view of a pixel or two): said, not "×nan".
    figures.penumbraWidthRatio = std::nan("");
    const std::string none = eval::softFiguresLine(figures);
    EXPECT_NE(none.find("no penumbra in the truth"), std::string::npos) << none;
    EXPECT_EQ(none.find("nan"), std::string::npos) << none;
}

TEST(SoftTruthTest, AViewThatComparedNoPixelIsWarnedOfAndOneThatDidIsNot) {
    eval::Figures figures; // valid_px 0, wrong_pct 0: what the sky gives
    const std::string warning = eval::nothingComparedWarning("paper", figures);
    EXPECT_NE(warning.find("view paper: no pixel was compared"), std::string::npos) << warning;
    figures.validPx = 1;
    EXPECT_TRUE(eval::nothingComparedWarning("paper", figures).empty());
}

TEST(SoftTruthTest, AViewMostOfWhoseSunlitPixelsWereLeftOutIsWarnedOf) {
    eval::Figures figures;
    figures.validPx = 400;
    figures.excludedPx = 600; // 60 % of the 1,000 sunlit pixels left out
    const std::string warning = eval::mostlyLeftOutWarning("aerial", figures);
    EXPECT_NE(warning.find("view aerial: 60 % of its sunlit pixels were left out"), std::string::npos) << warning;
    figures.validPx = 600;
    figures.excludedPx = 400; // most compared
    EXPECT_TRUE(eval::mostlyLeftOutWarning("aerial", figures).empty());
    figures.validPx = 0; // none: the nothing-compared warning's, not this one's
    EXPECT_TRUE(eval::mostlyLeftOutWarning("aerial", figures).empty());
}

TEST(SoftTruthTest, TheSoftErrorMapIsRedWhereTooDarkBlueWhereTooLightAndGreyWhereRight) {
    using PC = eval::PixelClass;
    using C = eval::ErrorMapColors;
    eval::SoftTruth soft;
    soft.width = 5, soft.height = 1;
    soft.visibility = {1.0f, 0.0f, 0.5f, 0.5f, 1.0f};
    const std::vector<float> rendered = {0.0f, 1.0f, 0.5f, 0.25f, 1.0f};
    eval::Comparison comparison;
    comparison.classes = {PC::FalseShadow, PC::FalseLit, PC::LitCorrect, PC::ShadowCorrect, PC::Excluded};
    const scene::Image image = eval::softErrorMapImage(rendered, soft, comparison);
    const auto is = [&](int x, const uint8_t(&rgb)[3]) {
        const uint8_t* p = image.pixel(x, 0);
        return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    };
    EXPECT_TRUE(is(0, C::falseShadow));  // error −1: shadow where the whole sun is seen
    EXPECT_TRUE(is(1, C::falseLit));     // +1
    EXPECT_TRUE(is(2, C::litCorrect));   // right
    EXPECT_TRUE(is(4, C::notEvaluated)); // not compared
    // A quarter too dark: a quarter of the way from grey to red.
    const uint8_t* p = image.pixel(3, 0);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(p[k], C::litCorrect[k] + 0.25 * (C::falseShadow[k] - C::litCorrect[k]), 0.51) << k;
}

TEST(SoftTruthTest, ASphereLightOfRadiusZeroIsTheLampsHardTruthExactly) {
    const scene::Scene s = groundAndBox({0, 2.5f, 0}, {1, 0.5f, 1.5f});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50, 120).value();
    const eval::TruthBuffers hits = eval::computeTruth(**rays, test::cameraLookingAtOrigin(), sun, 160, 120);
    const core::PointLight lamp{.wsPosition = {1.5, 6, 1}, .range = 12};
    const eval::TruthBuffers hard = eval::underLight(**rays, hits, lamp);
    const eval::SoftTruth soft = eval::computeSphereSoftTruth(**rays, hard, {lamp.wsPosition, 0.0});
    int shadowed = 0, lit = 0;
    for (size_t i = 0; i < hard.surfaceId.size(); ++i) {
        if (!hard.facesLight[i]) {
            EXPECT_TRUE(std::isnan(soft.visibility[i])) << "pixel " << i << ": out of the lamp's reach";
            continue;
        }
        ASSERT_EQ(soft.visibility[i], hard.lit[i] ? 1.0f : 0.0f) << "pixel " << i;
        shadowed += !hard.lit[i], lit += hard.lit[i];
    }
    EXPECT_GT(shadowed, 100);
    EXPECT_GT(lit, 100);
}

TEST(SoftTruthTest, ASphereLightsPenumbraUnderAnEdgeIsTheDisksChordAreaFraction) {
    // A thin plate covering x < 0 at height h, a lamp of radius R at height H right above its edge.
    // From ground point x the ray to the lamp's point at offset l along x passes height h at
    // x + (l − x) h / H, so the lamp is seen where l ≥ −x (H − h) / h: the disk's area beyond a chord
    // at c = x (H − h) / (h R) from its centre, 1 − (acos c − c √(1 − c²)) / π, over a penumbra
    // 2 h R / (H − h) wide (similar triangles; the disk seen from near under the lamp, so flat).
    const double h = 2.0, H = 5.0, R = 0.2;
    const scene::Scene s = groundAndBox({-20.0f, float(h) + 0.001f, 0}, {20, 0.001f, 20});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const double halfWidth = h * R / (H - h);
    std::vector<double> xs;
    for (int i = -24; i <= 24; ++i) xs.push_back(halfWidth * i / 20.0);
    eval::SoftTruthOptions options;
    options.samples = 1024;
    const eval::SoftTruth soft = eval::computeSphereSoftTruth(**rays, groundPoints(xs), {{0, H, 0}, R}, options);
    double meanError = 0.0;
    for (size_t i = 0; i < xs.size(); ++i) {
        const double c = std::clamp(xs[i] * (H - h) / (h * R), -1.0, 1.0);
        const double expected = 1.0 - (std::acos(c) - c * std::sqrt(1.0 - c * c)) / kPi;
        EXPECT_NEAR(soft.visibility[i], expected, 4.0 * soft.standardError[i] + 0.013) << "x = " << xs[i];
        meanError += std::abs(soft.visibility[i] - expected);
    }
    EXPECT_LT(meanError / static_cast<double>(xs.size()), 0.01);
    EXPECT_EQ(soft.visibility.front(), 0.0f);
    EXPECT_EQ(soft.visibility.back(), 1.0f);
    // The rays stop at the lamp's surface: a caster beyond the lamp (a ceiling above it) hides nothing.
    const scene::Scene ceiling = groundAndBox({0.0f, float(H) + 1.0f, 0}, {20, 0.05f, 20});
    auto ceilingRays = eval::RayScene::build(ceiling);
    ASSERT_TRUE(ceilingRays);
    const eval::SoftTruth under = eval::computeSphereSoftTruth(**ceilingRays, groundPoints(xs), {{0, H, 0}, R});
    for (const float v : under.visibility) EXPECT_EQ(v, 1.0f);
}

TEST(SoftTruthTest, TheHtmlReportShowsTheSoftFiguresWithTheirMeaningOnlyWhereThereAreAny) {
    eval::HtmlEntry hard, soft;
    hard.label = "hard";
    soft.label = "pcss";
    soft.report.soft = eval::SoftFigures{.sunAngleDegrees = 0.53,
                                         .softMae = 0.0049,
                                         .penumbraMae = 0.133,
                                         .softWrongPct = 0.4,
                                         .penumbraWidthRatio = 0.99};
    eval::HtmlReport report;
    report.entries = {hard};
    EXPECT_EQ(eval::htmlReport(report).find("penumbra_width_ratio"), std::string::npos);
    report.entries = {hard, soft};
    const std::string page = eval::htmlReport(report);
    for (const char* shown : {"<td>0.0049</td>", "<td>0.133</td>", "<td>0.99</td>", "<code>penumbra_mae</code>",
                              "<code>penumbra_width_ratio</code>", "<td>—</td>"}) // the hard entry has none
        EXPECT_NE(page.find(shown), std::string::npos) << shown;
}

TEST(SoftTruthTest, TheSoftTruthPictureIsGreyBetweenTheUmbrasAndTheSunsAsTheDiskIsSeen) {
    // A box over the ground under an 8° sun: each pixel of the soft picture is the hard picture's
    // shadowed grey where none of the disk is seen, its lit grey where all of it is, and strictly
    // between in the penumbra.
    const scene::Scene s = groundAndBox({0, 2.5f, 0}, {1, 0.5f, 1.5f});
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50, 120).value();
    const eval::TruthBuffers truth = eval::computeTruth(**rays, test::cameraLookingAtOrigin(), sun, 160, 120);
    const eval::SoftTruth soft = eval::computeSoftTruth(**rays, truth, {sun.wsTowardsLight(), 8.0});
    eval::TruthBuffers dark = truth, bright = truth;
    std::ranges::fill(dark.lit, false);
    std::ranges::fill(bright.lit, true);
    const scene::Image picture = eval::softTruthShadowImage(truth, soft, sun);
    const scene::Image umbra = eval::truthShadowImage(dark, sun), lit = eval::truthShadowImage(bright, sun);
    int penumbra = 0;
    for (int y = 0; y < truth.height; ++y)
        for (int x = 0; x < truth.width; ++x) {
            const size_t i = size_t(y) * truth.width + x;
            const int g = picture.pixel(x, y)[0], g0 = umbra.pixel(x, y)[0], g1 = lit.pixel(x, y)[0];
            if (!truth.facesLight[i] || truth.surfaceId[i] == 0) {
                EXPECT_EQ(g, g0) << x << ", " << y; // facing away, or sky: as the hard picture
                continue;
            }
            const float v = soft.visibility[i];
            if (v == 0.0f) {
                EXPECT_EQ(g, g0) << x << ", " << y;
            }
            if (v == 1.0f) {
                EXPECT_EQ(g, g1) << x << ", " << y;
            }
            if (v > 0.1f && v < 0.9f && g1 - g0 >= 20) {
                EXPECT_GT(g, g0) << x << ", " << y;
                EXPECT_LT(g, g1) << x << ", " << y;
                ++penumbra;
            }
        }
    EXPECT_GT(penumbra, 50) << "no penumbra in view: the test checks little";
}
