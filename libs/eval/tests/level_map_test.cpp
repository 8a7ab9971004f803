// The report's level map (level_map.h): each shadowed pixel's caster is the instance its shadow
// ray meets first, and the figures split the shadowed pixels by the level that caster was drawn at.
#include "truth_scenes.h"

#include "shadowkit/eval/level_map.h"
#include "shadowkit/eval/truth.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;
using namespace shadowkit::test;

namespace {

constexpr int kWidth = 160, kHeight = 120;

// The ground (instance 0) under two boxes placed as two instances of one mesh (1 and 2), the
// second stacked above the first so that their shadows coincide where they overlap.
scene::Scene groundAndTwoStackedBoxes() {
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), {1, 0.25f, 1}, glm::vec3(0.8f));
    scene::Scene s = groundAnd(box, glm::translate(glm::mat4(1.0f), {-1.5f, 2.0f, 0}));
    s.batches.back().worldFromObject.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 4.0f, 0.5f)));
    return s;
}

} // namespace

TEST(LevelMapTest, AShadowedPixelsCasterIsTheFirstInstanceItsShadowRayMeets) {
    const scene::Scene s = groundAndTwoStackedBoxes();
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(80, 30).value();
    const eval::TruthBuffers truth = eval::computeTruth(**rays, cameraLookingAtOrigin(), sun, kWidth, kHeight);
    const std::vector<uint32_t> casters = eval::castersAt(**rays, truth, sun);
    const core::Vec3 towards = sun.wsTowardsLight();
    int lower = 0, upper = 0;
    for (size_t i = 0; i < casters.size(); ++i) {
        const bool shadowed = truth.surfaceId[i] != 0 && truth.facesLight[i] && !truth.lit[i];
        ASSERT_EQ(casters[i] != 0, shadowed) << i << ": a caster exactly where the truth is in shadow";
        if (truth.surfaceId[i] != kGroundId || !shadowed) continue;
        // On the ground, the lower box (y 1.75–2.25) is met before the upper one (3.75–4.25):
        // a ray entering the lower box's footprint at its bottom meets it there; one that crosses
        // both its bottom and its top outside (by a margin: its sides) passes it by.
        const core::Vec3 p = truth.wsPosition[i];
        auto footprint = [&](double y, double margin) {
            const core::Vec3 at = p + (y - p.y) / towards.y * towards;
            return std::abs(at.x + 1.5) < 1.0 + margin && std::abs(at.z) < 1.0 + margin;
        };
        const bool insideLower = footprint(1.75, -0.01);
        const bool outsideLower = !footprint(1.75, 0.01) && !footprint(2.25, 0.01);
        if (insideLower) {
            EXPECT_EQ(casters[i], 2u) << i;
            ++lower;
        }
        if (outsideLower) {
            EXPECT_EQ(casters[i], 3u) << i;
            ++upper;
        }
    }
    EXPECT_GT(lower, 50);
    EXPECT_GT(upper, 50);
}

TEST(LevelMapTest, ShadowedPixelsSplitByTheirCastersLevelAndFalseLightCountsPerLevel) {
    // Four pixels: a surface at level 0 lit; one shadowed by instance 1 (drawn at level 2) and
    // rendered lit; one shadowed by instance 2 (level 0) rendered shadowed; one whose caster no
    // pass drew (instance 3); and the sky.
    const std::vector<uint32_t> surface = {1, 1, 1, 1, 0}, casters = {0, 2, 3, 4, 0};
    const std::vector<uint8_t> camera = {0, 1, 0, eval::kLevelNotDrawn}, sunLevels = {0, 2, 0, eval::kLevelNotDrawn};
    const eval::LevelMap map = eval::levelMap(surface, casters, camera, sunLevels, 5, 1);
    EXPECT_EQ(map.surface, (std::vector<uint8_t>{0, 0, 0, 0, eval::kLevelNotDrawn}));
    EXPECT_EQ(map.caster, (std::vector<uint8_t>{eval::kNoCaster, 2, 0, eval::kLevelNotDrawn, eval::kNoCaster}));
    eval::Comparison comparison;
    using C = eval::PixelClass;
    comparison.classes = {C::LitCorrect, C::FalseLit, C::ShadowCorrect, C::FalseLit, C::NotEvaluated};
    const std::vector<eval::CasterLevelFigures> figures = eval::casterLevelFigures(map, comparison);
    ASSERT_EQ(figures.size(), 3u);
    EXPECT_EQ(figures[0].level, 0);
    EXPECT_EQ(figures[0].shadowedPx, 1);
    EXPECT_EQ(figures[0].falseLitPx, 0);
    EXPECT_EQ(figures[1].level, 2);
    EXPECT_EQ(figures[1].falseLitPx, 1);
    EXPECT_EQ(figures[2].level, eval::kLevelNotDrawn);
    EXPECT_EQ(figures[2].falseLitPx, 1);
    // An excluded pixel (raster and ray disagree on the surface) is not split, whatever its caster.
    comparison.classes[2] = C::Excluded;
    EXPECT_EQ(eval::casterLevelFigures(map, comparison).size(), 2u);
    // The picture: the caster's colour where the truth shadows, the legend under the pixels.
    const scene::Image image = eval::levelMapImage(map);
    EXPECT_EQ(image.width, 5);
    EXPECT_GT(image.height, 1);
    const uint8_t* second = image.pixel(1, 0);
    EXPECT_TRUE(std::equal(second, second + 3, eval::levelColor(2)));
}
