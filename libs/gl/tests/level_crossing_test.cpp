// Crossing between levels of detail (RenderSettings::lodFade, LodChoice::fadeBand): an instance
// whose allowed error lies in the band below a coverage-keeping level's bound is drawn at both
// levels, and the two draws keep complementary pixels of an ordered dither (material.glsl).
// The share follows the formula at the band's ends; the lists hold both entries and nothing
// else changes; and drawn, the two levels cover each pixel and each shadow-map texel exactly
// once — a card whose two levels are the same quad in two colours shows each colour in its
// share and casts the same shadow as either level alone. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "visibility.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/mesh_lod.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

using namespace shadowkit;

namespace {

class LevelCrossingTest : public gl::testing::HeadlessGlTest {};

TEST(LevelCrossingShare, IsZeroBelowTheBandAndRisesToAllButTheLastStepAtTheBound) {
    constexpr double kBound = 2.0;
    for (const double band : {0.1, 0.25, 0.5, 0.9}) {
        // Below the band, nothing crosses; at its start, the coarser level has no share.
        EXPECT_EQ(gl::fadeStepsOf(0.5 * (1.0 - band) * kBound, kBound, band), 0u) << band;
        EXPECT_EQ(gl::fadeStepsOf((1.0 - band) * kBound, kBound, band), 0u) << band;
        // Half-way through the band, half the pixels (within the rounding of the share's floor).
        EXPECT_NEAR(double(gl::fadeStepsOf((1.0 - 0.5 * band) * kBound, kBound, band)), gl::kFadeSteps / 2, 1.0)
            << band;
        // Just below the bound, all but the last step (at the bound the pass takes the level).
        EXPECT_EQ(gl::fadeStepsOf(kBound * (1.0 - 1e-9), kBound, band), gl::kFadeSteps - 1) << band;
        uint32_t last = 0;
        for (double a = (1.0 - band) * kBound; a < kBound; a += 0.001 * kBound) {
            const uint32_t steps = gl::fadeStepsOf(a, kBound, band);
            EXPECT_GE(steps, last) << "not monotone at " << a; // nearer the bound, more of the coarser level
            EXPECT_LT(steps, gl::kFadeSteps);
            last = steps;
        }
    }
    // No band, no crossing; a level without error is taken outright, never crossed into.
    EXPECT_EQ(gl::fadeStepsOf(0.99 * kBound, kBound, 0.0), 0u);
    EXPECT_EQ(gl::fadeStepsOf(1.0, 0.0, 0.5), 0u);
}

// Random cameras over a small leafy forest, levels by pixels with coverage levels taken far
// nearer than by default: with a band, every crossing instance has one entry in its level's list
// and one, marked coarser, in the next level's, with the same share; without the crossing
// entries the lists are those of no band at all.
TEST_F(LevelCrossingTest, ACrossingInstanceIsInBothLevelsListsAndChangesNothingElse) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    std::vector<scene::MeshLods> lods;
    for (const scene::Mesh& mesh : forest.meshes) lods.push_back(scene::buildLods(mesh));
    gl::Visibility visibility(forest, lods);
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), between(0.0, 1.0);
    size_t crossings = 0;
    for (int c = 0; c < 45; ++c) {
        core::PerspectiveCamera camera;
        camera.wsEye = core::Vec3(120.0 * unit(random), 5.0 + 60.0 * between(random), 120.0 * unit(random));
        camera.wsDirection = core::Vec3(unit(random), -0.5 * between(random) - 0.1, unit(random));
        camera.zFar = 400.0;
        const double band = 0.1 + 0.8 * between(random);
        const gl::LodChoice plain{{camera.clipFromWorld(), 0.5 * 256, 0.25}, std::nullopt, false, 16.0, 0.0};
        gl::LodChoice crossing = plain;
        crossing.fadeBand = band;
        const auto volume = visibility::clipVolume(camera.clipFromWorld());
        gl::PassList without, with;
        visibility.collect(volume, true, &plain, without);
        visibility.collect(volume, true, &crossing, with);
        gl::PassList stripped = with; // the crossing entries' level-chosen halves, unmarked
        stripped.indices.clear();
        for (size_t slot = 0; slot < with.count.size(); ++slot) {
            stripped.first[slot] = uint32_t(stripped.indices.size());
            stripped.count[slot] = 0;
            for (uint32_t k = 0; k < with.count[slot]; ++k) {
                const uint32_t entry = with.indices[with.first[slot] + k];
                const uint32_t steps = (entry >> gl::kListIndexBits) & (gl::kFadeSteps - 1);
                if ((entry & gl::kFadeIncoming) != 0) {
                    // Its partner: the same instance and share in the previous level's list.
                    ASSERT_GT(slot % gl::kMaxLodLevels, 0u) << "case " << c;
                    ASSERT_NE(steps, 0u) << "case " << c;
                    const auto begin = with.indices.begin() + with.first[slot - 1];
                    EXPECT_NE(std::find(begin, begin + with.count[slot - 1], entry & ~gl::kFadeIncoming),
                              begin + with.count[slot - 1])
                        << "case " << c << ": instance " << gl::instanceOfEntry(entry) << " crosses from nowhere";
                    ++crossings;
                    continue;
                }
                stripped.indices.push_back(gl::instanceOfEntry(entry));
                ++stripped.count[slot];
            }
        }
        EXPECT_EQ(stripped.count, without.count) << "case " << c;
        EXPECT_EQ(stripped.indices, without.indices) << "case " << c;
        // Every outgoing entry with a share has its coarser partner (counted from that side).
        size_t outgoing = 0, incoming = 0;
        for (const uint32_t entry : with.indices)
            if ((entry >> gl::kListIndexBits) != 0) ++((entry & gl::kFadeIncoming) != 0 ? incoming : outgoing);
        EXPECT_EQ(outgoing, incoming) << "case " << c;
    }
    EXPECT_GT(crossings, 100u); // the cases reach the band
}

// A horizontal card of 6 × 6 m, 3 m over a ground slab, seen straight down from 10 m on a square
// image, the sun from −x at 45° so that its shadow reaches out beside it. Its one authored coarser
// level is the same quad `coarserLift` metres higher, keeping coverage, with a red texture of its
// own in place of the material's white one: which level drew a pixel shows in its colour, and
// with no lift both cast the same depth.
constexpr int kSide = 128;
constexpr double kFovDegrees = 60.0, kDistance = 10.0;

scene::Texture solid(uint8_t r, uint8_t g, uint8_t b) {
    scene::Image image(4, 4);
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        image.rgba[i] = r, image.rgba[i + 1] = g, image.rgba[i + 2] = b, image.rgba[i + 3] = 255;
    }
    return scene::Texture{.image = std::move(image)};
}

// The camera's allowed error at the card's centre, in metres (visibility.cpp's rule): a pixel
// bound of 0.25 over half the image's side per NDC unit, one NDC unit being d·tan(fov/2) metres.
double allowedAtTheCard() {
    return 0.25 * kDistance * std::tan(0.5 * kFovDegrees * std::numbers::pi / 180.0) / (0.5 * kSide);
}

scene::Scene cardWithTwoColouredLevels(float coarserError, float coarserLift = 0.0f) {
    scene::Scene s;
    scene::Mesh ground, card;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, 0}), {12, 0.5f, 12}, glm::vec3(0.8f));
    for (const float height : {3.0f, 3.0f + coarserLift}) {
        const glm::mat4 partToObject = glm::translate(glm::mat4(1.0f), {0, height, 0}) *
                                       glm::rotate(glm::mat4(1.0f), -0.5f * std::numbers::pi_v<float>, {1, 0, 0}) *
                                       glm::scale(glm::mat4(1.0f), {6, 6, 1}) *
                                       glm::translate(glm::mat4(1.0f), {0, -0.5f, 0});
        scene::addCard(card, partToObject, {0, 1}, {1, 0}, glm::vec3(1.0f));
    }
    // The full mesh is the first quad, the coarser level the second.
    const size_t half = card.indices.size() / 2;
    card.authoredLods.push_back({.indices = std::vector<uint32_t>(card.indices.begin() + half, card.indices.end()),
                                 .objectError = coarserError,
                                 .keepsCoverage = true,
                                 .texture = 1});
    card.indices.resize(half);
    card.material = 0;
    for (scene::Mesh* m : {&ground, &card}) m->computeBounds();
    s.meshes = {ground, card};
    s.textures = {solid(255, 255, 255), solid(255, 0, 0)};
    s.materials = {scene::Material{.name = "card",
                                   .baseColorTexture = 0,
                                   .alphaMode = scene::AlphaMode::Mask,
                                   .alphaCutoff = 0.5f,
                                   .doubleSided = true}};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    return s;
}

TEST_F(LevelCrossingTest, TheTwoLevelsDrawEachPixelAndEachTexelOnceInTheirShares) {
    // The coarser level errs 25 times the camera's allowance there: at foliage scale 1 the card is
    // drawn full and, with a band of 0.9 centred on the bound, does not cross yet (1 / 25 < 0.55);
    // at scale 64 it is drawn coarse; at scale 20.5 it stands at 0.82 of the bound, 0.3 of the way
    // through the band (RenderSettings::lodFade).
    const double allowed = allowedAtTheCard();
    const scene::Scene scene = cardWithTwoColouredLevels(float(25.0 * allowed));
    auto renderer = gl::Renderer::create(scene);
    ASSERT_TRUE(renderer) << renderer.error();
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 3 + kDistance, 0};
    camera.wsDirection = {0, -1, 0};
    camera.wsUp = {0, 0, -1};
    camera.fovYDegrees = kFovDegrees;
    camera.aspect = 1.0;
    camera.zNear = 1.0;
    camera.zFar = 30.0;
    const core::DirectionalLight sun = core::DirectionalLight::fromDirection({1, -1, 0}).value();
    auto setup = core::computeShadowSetup({.camera = camera,
                                           .light = sun,
                                           .wsSceneBounds = scene.wsBounds(),
                                           .technique = core::Technique::Focused,
                                           .mapSize = 256});
    ASSERT_TRUE(setup) << setup.error();
    gl::RenderSettings settings = gl::testing::smallFrame(kSide, kSide, gl::Culling::Frustum);
    settings.filter.kind = core::ShadowFilter::Hard; // a hole in the map would show as a lit pixel
    auto draw = [&](float foliageScale, float fade, gl::Culling culling) {
        settings.lodFoliageScale = foliageScale;
        settings.lodFade = fade;
        settings.culling = culling;
        const auto frame = (*renderer)->render(camera, sun, *setup, settings);
        EXPECT_TRUE(frame) << frame.error();
        return (*renderer)->readColor();
    };
    const scene::Image full = draw(1.0f, 0.9f, gl::Culling::Frustum);
    const scene::Image coarse = draw(64.0f, 0.0f, gl::Culling::Frustum);
    const scene::Image crossing = draw(20.5f, 0.9f, gl::Culling::Frustum);
    ASSERT_EQ(full.rgba.size(), crossing.rgba.size());
    auto at = [](const scene::Image& image, size_t p) {
        return std::array{image.rgba[4 * p], image.rgba[4 * p + 1], image.rgba[4 * p + 2]};
    };
    size_t card = 0, coarser = 0, shadowed = 0, neither = 0;
    for (size_t p = 0; p < full.rgba.size() / 4; ++p) {
        if (at(full, p) == at(coarse, p)) {
            // The ground, lit and shadowed: both levels cast the same depth, so the crossing card's
            // map (its texels split between the two draws) must hold it all.
            EXPECT_EQ(at(crossing, p), at(full, p)) << "ground pixel " << p % kSide << ", " << p / kSide;
            shadowed += at(full, p)[0] < 200; // lit ground is 231 there, shadowed 130
            continue;
        }
        ++card;
        if (at(crossing, p) == at(coarse, p))
            ++coarser;
        else if (at(crossing, p) != at(full, p))
            ++neither;
    }
    EXPECT_EQ(neither, 0u) << "card pixels drawn by neither level, or by both";
    ASSERT_GT(card, size_t(kSide * kSide) / 10);
    EXPECT_GT(shadowed, size_t(kSide * kSide) / 20); // the shadow is in the picture
    // (0.82 − 0.55) / 0.9 = 0.3 of the card's pixels.
    EXPECT_NEAR(double(coarser) / double(card), 0.3, 0.05);
    // GPU-driven culling draws the same lists, so the same pixels.
    EXPECT_EQ(draw(20.5f, 0.9f, gl::Culling::Gpu).rgba, crossing.rgba);
}

// Virtual pages: a page is drawn into whichever atlas slot is free, so the dither is taken over
// the page's texels in its level, not the atlas's (DepthPassUniforms::ditherOrigin). With the
// coarser level 1 m above the finer, the depth a texel holds depends on which level the dither
// gives it: frames from pages kept across a moving camera must equal those of fresh pages.
TEST_F(LevelCrossingTest, VirtualPagesCrossAlikeInWhicheverAtlasSlotTheyLie) {
    const scene::Scene scene = cardWithTwoColouredLevels(float(25.0 * allowedAtTheCard()), 1.0f);
    auto cached = gl::Renderer::create(scene);
    ASSERT_TRUE(cached) << cached.error();
    const core::DirectionalLight sun = core::DirectionalLight::fromDirection({1, -1, 0.3}).value();
    gl::RenderSettings settings = gl::testing::smallFrame(kSide, kSide, gl::Culling::Frustum);
    settings.filter.kind = core::ShadowFilter::Hard;
    settings.lodFade = 0.9f;
    int reused = 0, crossed = 0;
    for (const float foliageScale : {4.0f, 9.0f, 16.0f, 24.0f}) {
        settings.lodFoliageScale = foliageScale;
        for (int frame = 0; frame < 4; ++frame) {
            core::PerspectiveCamera camera;
            camera.wsEye = {0.4 * frame, 3 + kDistance, 2.0};
            camera.wsDirection = core::Vec3(0, 3, 0) - camera.wsEye;
            camera.fovYDegrees = kFovDegrees;
            camera.aspect = 1.0;
            camera.zNear = 1.0;
            camera.zFar = 30.0;
            core::ShadowSetupInputs in{.camera = camera, .light = sun, .wsSceneBounds = scene.wsBounds()};
            in.technique = core::Technique::Virtual;
            in.virtualMaps.imageHeight = kSide;
            in.virtualMaps.virtualTexels = 4096;
            const core::ShadowSetup setup = core::computeShadowSetup(in).value();
            const auto stats = (*cached)->render(camera, sun, setup, settings);
            ASSERT_TRUE(stats && stats->virtualPages) << (stats ? "no page stats" : stats.error());
            reused += stats->virtualPages->pagesRequested - stats->virtualPages->pagesRendered;
            auto fresh = gl::Renderer::create(scene);
            ASSERT_TRUE(fresh);
            const auto a = (*cached)->renderEvalBuffers(camera, sun, setup, settings);
            const auto b = (*fresh)->renderEvalBuffers(camera, sun, setup, settings);
            gl::RenderSettings switching = settings;
            switching.lodFade = 0.0f;
            const auto c = (*fresh)->renderEvalBuffers(camera, sun, setup, switching);
            ASSERT_TRUE(a && b && c);
            // Equal but for a lookup rounding to the neighbouring texel: a kept page lies in another
            // atlas slot than a fresh one, so a receiver on a texel's border may round either way, and
            // the crossing's dither makes neighbouring texels hold depths a metre apart (one pixel in
            // this test's 16 frames on llvmpipe). A dither taken over the atlas instead of the page
            // differs in 74–120 of a frame's pixels here.
            int differ = 0;
            for (size_t i = 0; i < a->shadowTerm.size(); ++i) differ += a->shadowTerm[i] != b->shadowTerm[i];
            EXPECT_LE(differ, 4) << "scale " << foliageScale << ", frame " << frame;
            crossed += b->shadowTerm != c->shadowTerm;
        }
    }
    EXPECT_GT(reused, 0) << "no page was kept across frames";
    EXPECT_GT(crossed, 0) << "no frame's pages crossed levels";
}

} // namespace
