// The truth sees what the camera pass draws: the back of a single-sided surface is culled by the
// raster and passed by the truth's camera rays, so `eval` scores what lies behind it instead of
// leaving the pixels out as a disagreement (docs/reliability.md, "The back of a single-sided
// surface"). Both sides read one rule, scene::Scene::seenFromFrontOnly. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class SingleSidedEvalTest : public gl::testing::HeadlessGlTest {};

constexpr uint32_t kGround = 1, kCard = 2; // surface ids: instance + 1

// A ground slab and a 6 m card 2 m over it facing down (away from a camera above it), placed by
// `worldFromCard`; `doubleSided` gives the card a material saying so.
scene::Scene cardOverGround(const glm::mat4& worldFromCard, bool doubleSided) {
    scene::Scene s;
    scene::Mesh ground, card;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, 0}), {20, 0.5f, 20}, glm::vec3(0.7f));
    const glm::mat4 partFacingDown =
        glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}) * glm::scale(glm::mat4(1.0f), {6, 6, 1});
    scene::addCard(card, partFacingDown, {0, 0}, {1, 1}, glm::vec3(0.3f, 0.6f, 0.2f));
    if (doubleSided) {
        s.materials = {{.name = "both sides", .doubleSided = true}};
        card.material = 0;
    }
    for (scene::Mesh* m : {&ground, &card}) m->computeBounds();
    s.meshes = {ground, card};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {worldFromCard}, false}};
    return s;
}

struct Seen {
    int rasterCard = 0, truthCard = 0; // pixels showing the card
    int agree = 0;                     // pixels where raster and truth show the same surface
    eval::Figures figures;
};

Seen measureCard(const scene::Scene& s) {
    auto measurer = measure::Measurer::create(s);
    EXPECT_TRUE(measurer) << measurer.error();
    if (!measurer) return {};
    core::PerspectiveCamera camera;
    camera.wsEye = {3, 9, 14};
    camera.wsDirection = core::Vec3(-1.5, 0, -1) - camera.wsEye;
    camera.aspect = 4.0 / 3.0;
    camera.zNear = 0.5;
    camera.zFar = 80;
    gl::RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.fogDensity = 0.0f;
    auto m = (*measurer)->measure({.camera = camera,
                                   .light = core::DirectionalLight::fromSunAngles(70, 120).value(),
                                   .wsSceneBounds = s.wsBounds(),
                                   .technique = core::Technique::Focused,
                                   .mapSize = 1024},
                                  settings);
    EXPECT_TRUE(m) << m.error();
    Seen seen;
    if (!m) return seen;
    for (size_t i = 0; i < m->truth->surfaceId.size(); ++i) {
        seen.rasterCard += m->raster.surfaceId[i] == kCard;
        seen.truthCard += m->truth->surfaceId[i] == kCard;
        seen.agree += m->raster.surfaceId[i] == m->truth->surfaceId[i];
    }
    seen.figures = m->figures();
    return seen;
}

} // namespace

TEST_F(SingleSidedEvalTest, TheBackOfASingleSidedCardIsSeenThroughByRasterAndTruthAlike) {
    const glm::mat4 worldFromCard = glm::translate(glm::mat4(1.0f), {-1.5f, 2.0f, -4.0f});
    const Seen back = measureCard(cardOverGround(worldFromCard, false));
    EXPECT_EQ(back.rasterCard, 0);
    EXPECT_EQ(back.truthCard, 0);
    // Every pixel shows the same surface to both (before, the card's ~880 pixels of 19,200 were
    // the truth's card and the raster's ground, all left out of the figures), and the ground
    // under the card — shaded by it, whichever side faces the sun — is scored and right.
    EXPECT_GE(back.agree, 160 * 120 - 20);
    EXPECT_LE(back.figures.excludedPx, 20);
    EXPECT_GT(back.figures.validPx, 12000);
    EXPECT_LT(back.figures.wrongPct, 1.0);

    // Double-sided, or single-sided in a mirrored batch (drawn from both sides), the card is seen
    // by both; mirrored through its own centre line it covers the same pixels.
    const Seen both = measureCard(cardOverGround(worldFromCard, true));
    const Seen mirrored = measureCard(cardOverGround(worldFromCard * glm::scale(glm::mat4(1.0f), {-1, 1, 1}), false));
    for (const Seen& seen : {both, mirrored}) {
        EXPECT_GT(seen.truthCard, 500);
        EXPECT_NEAR(seen.rasterCard, seen.truthCard, 20);
        EXPECT_GE(seen.agree, 160 * 120 - 40);
    }
    EXPECT_EQ(mirrored.truthCard, both.truthCard);
}
