// Opacity layers (RenderSettings::foliageOpacity, gl/src/opacity_layers.h,
// glsl/shadowkit_foliage_opacity.glsl's skFoliageTransmittance): leaves smaller than a texel cast
// a fraction of the light, stacked leaves multiply, a receiver between two layers of leaves is
// shadowed by the layer above it only, the ground beside a canopy's edge is partly shadowed under
// the sun's disk, a sunlit leaf is not shaded by its own layer, and the opaque casters still cast
// through the depth map; and the layers' first draw writes each texel the leaves cover once.
//
// The scene: a ground slab, and two horizontal alpha-tested cards whose texture is random noise
// covering half of each 3 cm cell (far finer than the map's 8 cm texels): the upper card at
// y = 7 over x, z ∈ [−2, 2], the lower at y = 5 over x ∈ [−2, 4], z ∈ [−2, 0]. An opaque plate at
// y = 6 (x ∈ [2.2, 3], z ∈ [−2, 0]) lies between them. The sun comes from −x at 45°, so a point
// at height h casts onto the ground h metres further along +x: the upper card onto x ∈ [5, 9], the
// lower onto x ∈ [3, 9] (z < 0), the plate onto x ∈ [8.2, 9], and the upper card's shadow crosses
// the plate's top.
#include "headless_gl_test.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace shadowkit;

namespace {

class FoliageOpacityTest : public gl::testing::HeadlessGlTest {};

// Instances in the order of the batches below (surfaceId = instance + 1).
constexpr uint32_t kGround = 1, kPlate = 2;

// A 128² texture whose texels are covered (alpha 1) or not (0) at random, half of each.
scene::Texture halfCoveredNoise() {
    scene::Image image;
    image.width = image.height = 128;
    image.rgba.resize(size_t(128) * 128 * 4);
    uint32_t state = 12345u;
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        state = state * 1664525u + 1013904223u; // a linear congruential generator: deterministic
        image.rgba[i] = image.rgba[i + 1] = image.rgba[i + 2] = 200;
        image.rgba[i + 3] = (state >> 31) != 0 ? 255 : 0;
    }
    return scene::Texture{.image = std::move(image)};
}

// A two-sided material alpha-tested at half coverage, textured by texture 0.
scene::Material alphaTested(const char* name) {
    return {.name = name,
            .baseColorTexture = 0,
            .alphaMode = scene::AlphaMode::Mask,
            .alphaCutoff = 0.5f,
            .doubleSided = true};
}

// A horizontal card at height y over [x0, x1] × [z0, z1].
void addHorizontalCard(scene::Mesh& mesh, float y, float x0, float x1, float z0, float z1) {
    const glm::mat4 partToObject = glm::translate(glm::mat4(1.0f), {0.5f * (x0 + x1), y, 0.5f * (z0 + z1)}) *
                                   glm::rotate(glm::mat4(1.0f), -0.5f * std::numbers::pi_v<float>, {1, 0, 0}) *
                                   glm::scale(glm::mat4(1.0f), {x1 - x0, z1 - z0, 1.0f}) *
                                   glm::translate(glm::mat4(1.0f), {0, -0.5f, 0});
    scene::addCard(mesh, partToObject, {0, 1}, {1, 0}, glm::vec3(0.3f, 0.6f, 0.2f));
}

scene::Scene cardsOverGround() {
    scene::Scene s;
    scene::Mesh ground, plate, cards;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {2, -0.5f, 0}), {12, 0.5f, 12}, glm::vec3(0.8f));
    scene::addBox(plate, glm::translate(glm::mat4(1.0f), {2.6f, 6, -1}), {0.4f, 0.05f, 1}, glm::vec3(0.8f));
    addHorizontalCard(cards, 7, -2, 2, -2, 2);
    addHorizontalCard(cards, 5, -2, 4, -2, 0);
    cards.material = 0;
    for (scene::Mesh* m : {&ground, &plate, &cards}) m->computeBounds();
    s.meshes = {ground, plate, cards};
    s.textures = {halfCoveredNoise()};
    s.materials = {alphaTested("leaves")};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}, {2, {glm::mat4(1.0f)}, false}};
    return s;
}

const core::DirectionalLight kSun = core::DirectionalLight::fromDirection({1, -1, 0}).value(); // from −x, 45°

struct Frame {
    core::PerspectiveCamera camera;
    core::RasterBuffers raster;
};

// A square camera looking straight down from wsEye, +x up the image.
core::PerspectiveCamera lookingDownFrom(const core::Vec3& wsEye) {
    core::PerspectiveCamera camera;
    camera.wsEye = wsEye;
    camera.wsDirection = {0, -1, 0};
    camera.wsUp = {1, 0, 0};
    camera.aspect = 1.0;
    camera.zNear = 1.0;
    camera.zFar = 40.0;
    return camera;
}

// `technique` Focused: one 256² map; Virtual: a clipmap of 64-texel pages, the level rule
// ⌊log2 footprint + lodBias⌋ over an image `imageHeight` pixels high.
core::ShadowSetup setupOf(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                          const scene::Scene& scene, core::Technique technique, int imageHeight) {
    auto setup = core::computeShadowSetup(
        {.camera = camera,
         .light = light,
         .wsSceneBounds = scene.wsBounds(),
         .technique = technique,
         .mapSize = 256,
         .virtualMaps = {
             .virtualTexels = 1024, .pageTexels = 64, .firstLevel = -4, .lodBias = 1.0, .imageHeight = imageHeight}});
    EXPECT_TRUE(setup) << setup.error();
    return setup ? std::move(setup).value() : core::ShadowSetup{};
}

// Looking straight down on the cards' shadows from above x = 5: no ray to the ground there
// passes through a card. Focused: 8 cm texels on the ground; Virtual: the ground 14 m below the
// eye (pixels of 6.3 cm) in texels of 12.5 cm (2^-3 m), coarser than the leaves' 3 cm cells too.
Frame render(gl::Renderer& renderer, const scene::Scene& scene, const gl::RenderSettings& settings,
             core::Technique technique = core::Technique::Focused) {
    const core::PerspectiveCamera camera = lookingDownFrom({5, 14, 0});
    auto raster =
        renderer.renderEvalBuffers(camera, kSun, setupOf(camera, kSun, scene, technique, settings.height), settings);
    EXPECT_TRUE(raster) << raster.error();
    return {camera, raster ? std::move(raster).value() : core::RasterBuffers{}};
}

struct Region {
    double mean = 0.0;
    double spread = 0.0;     // the terms' standard deviation
    double fractional = 0.0; // the share of its pixels strictly between 0.2 and 0.8
    int pixels = 0;
};

// The shadow terms of the pixels showing `surface` at world points (x, y, z), x ∈ [x0, x1],
// z ∈ [z0, z1], on a 5 cm grid.
Region termsOver(const Frame& f, uint32_t surface, double y, double x0, double x1, double z0, double z1) {
    Region r;
    double sum = 0.0, squares = 0.0;
    int fractional = 0;
    for (double x = x0; x <= x1; x += 0.05)
        for (double z = z0; z <= z1; z += 0.05) {
            const core::Vec4 c = f.camera.clipFromWorld() * core::Vec4(x, y, z, 1.0);
            const int px = static_cast<int>((c.x / c.w * 0.5 + 0.5) * f.raster.width);
            const int py = static_cast<int>((0.5 - c.y / c.w * 0.5) * f.raster.height);
            if (c.w <= 0.0 || px < 0 || py < 0 || px >= f.raster.width || py >= f.raster.height) continue;
            const size_t i = f.raster.index(px, py);
            if (f.raster.surfaceId[i] != surface) continue;
            const float term = f.raster.shadowTerm[i];
            sum += term;
            squares += double(term) * term;
            fractional += term > 0.2f && term < 0.8f;
            ++r.pixels;
        }
    if (r.pixels > 0) {
        r.mean = sum / r.pixels, r.fractional = double(fractional) / r.pixels;
        r.spread = std::sqrt(std::max(squares / r.pixels - r.mean * r.mean, 0.0));
    }
    return r;
}

gl::RenderSettings settings(bool foliageOpacity) {
    gl::RenderSettings s;
    s.width = s.height = 256;
    s.fogDensity = 0.0f;
    s.foliageOpacity = foliageOpacity;
    return s;
}

// The layers under a sun of 4° with PCSS (kernels up to 16 texels: the cap stays out of the way).
gl::RenderSettings underAWideSun() {
    gl::RenderSettings s = settings(true);
    s.filter = {core::ShadowFilter::Pcss, 32, 16.0f};
    s.sunAngleDegrees = 4.0;
    return s;
}

// A ground slab (its top at y = 0, centred on x = groundX, groundHalf wide each way) and one
// horizontal card covered whole (alpha 1 everywhere, yet alpha-tested) at height y over
// [x0, x1] × [z0, z1]; each mesh a batch of one instance.
scene::Scene groundAndCoveredCard(float groundX, float groundHalf, float y, float x0, float x1, float z0, float z1) {
    scene::Scene s;
    scene::Mesh ground, card;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {groundX, -0.5f, 0}), {groundHalf, 0.5f, groundHalf},
                  glm::vec3(0.8f));
    addHorizontalCard(card, y, x0, x1, z0, z1);
    card.material = 0;
    for (scene::Mesh* m : {&ground, &card}) m->computeBounds();
    s.meshes = {ground, card};
    scene::Texture covered = halfCoveredNoise();
    for (size_t i = 3; i < covered.image.rgba.size(); i += 4) covered.image.rgba[i] = 255;
    s.textures = {std::move(covered)};
    s.materials = {alphaTested("leaf")};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    return s;
}

// Four covered 2 m cards stacked 1 m apart, each its own batch, listed lowest first, so that
// only the lists' order (batches nearest the sun first) puts the top one first; under a sun
// straight overhead each covers the same texels of a map.
constexpr int kStackedCards = 4;
scene::Scene stackedCards() {
    scene::Scene s = groundAndCoveredCard(0, 4, 0, -1, 1, -1, 1);
    s.batches.pop_back();
    for (int i = 0; i < kStackedCards; ++i)
        s.batches.push_back({1, {glm::translate(glm::mat4(1.0f), {0, 2.0f + float(i), 0})}, false});
    return s;
}

// The texels of a size² map whose clip space is `clipFromWorld` that the horizontal square
// [−1, 1]² at height y covers: its projected corners' area (the shoelace formula).
double texelsCovered(const core::Mat4& clipFromWorld, double y, int size) {
    const core::Vec2 corner[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    core::Vec2 ndc[4];
    for (int i = 0; i < 4; ++i) {
        const core::Vec4 c = clipFromWorld * core::Vec4(corner[i].x, y, corner[i].y, 1.0);
        ndc[i] = core::Vec2(c) / c.w;
    }
    double twiceArea = 0.0;
    for (int i = 0; i < 4; ++i) twiceArea += ndc[i].x * ndc[(i + 1) % 4].y - ndc[(i + 1) % 4].x * ndc[i].y;
    return std::abs(twiceArea) / 2.0 * (size / 2.0) * (size / 2.0);
}

} // namespace

TEST_F(FoliageOpacityTest, TheFirstLeafsDrawWritesEachCoveredTexelOnceAndTheLayersCountEveryLeaf) {
    // Four cards over the same texels: the first leaf's draw, depth-tested with the top card drawn
    // first, passes one sample a texel the cards cover (four without its depth test, or with the
    // cards drawn lowest first); the transmittance's draw, with none, blends all four. Counted
    // against the cards' texels from the map's own projection, on a fixed map, and as a ratio on
    // virtual pages (whose guard bands cut the cards unevenly).
    const scene::Scene s = stackedCards();
    const core::DirectionalLight overhead = core::DirectionalLight::fromDirection({0, -1, 0}).value();
    const core::PerspectiveCamera camera = lookingDownFrom({0, 9, 0});
    for (const core::Technique technique : {core::Technique::Focused, core::Technique::Virtual}) {
        SCOPED_TRACE(core::techniqueName(technique));
        auto renderer = gl::Renderer::create(s);
        ASSERT_TRUE(renderer) << renderer.error();
        const auto setup = setupOf(camera, overhead, s, technique, settings(true).height);
        const auto stats = (*renderer)->render(camera, overhead, setup, settings(true));
        ASSERT_TRUE(stats) << stats.error();
        const gl::PassStats& shadow = stats->shadow;
        ASSERT_GT(shadow.firstLeafSamples, 1000u);
        EXPECT_NEAR(double(shadow.leafFragments) / double(shadow.firstLeafSamples), kStackedCards, 0.05);
        if (technique == core::Technique::Focused) {
            ASSERT_EQ(setup.views.size(), 1u);
            const double card = texelsCovered(setup.views[0].clipFromWorld, 2.0, 256);
            ASSERT_GT(card, 1000.0);
            EXPECT_NEAR(double(shadow.firstLeafSamples), card, 0.03 * card);
            EXPECT_NEAR(double(shadow.leafFragments), kStackedCards * card, 0.03 * kStackedCards * card);
        }
        // Read late, as an engine's frames read their figures: the same counts.
        auto late = gl::Renderer::create(s);
        ASSERT_TRUE(late) << late.error();
        (*late)->readGpuFiguresLate(true);
        ASSERT_TRUE((*late)->render(camera, overhead, setup, settings(true)));
        const std::vector<gl::GpuFigures> figures = (*late)->finishGpuFigures();
        ASSERT_EQ(figures.size(), 1u);
        EXPECT_EQ(figures[0].firstLeafSamples, shadow.firstLeafSamples);
        EXPECT_EQ(figures[0].leafFragments, shadow.leafFragments);
        // Without the layers, nothing is counted.
        const auto binary = (*renderer)->render(camera, overhead, setup, settings(false));
        ASSERT_TRUE(binary) << binary.error();
        EXPECT_EQ(binary->shadow.firstLeafSamples, 0u);
        EXPECT_EQ(binary->shadow.leafFragments, 0u);
    }
}

TEST_F(FoliageOpacityTest, LeavesFinerThanATexelCastAFractionAndStackedLayersMultiply) {
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Frame f = render(**renderer, s, settings(true));
    const Region upperOnly = termsOver(f, kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    const Region both = termsOver(f, kGround, 0.0, 5.5, 7.8, -1.6, -0.4);
    const Region lowerOnly = termsOver(f, kGround, 0.0, 4.2, 4.8, -1.6, -0.4);
    const Region open = termsOver(f, kGround, 0.0, 10.0, 11.0, -1.0, 1.0);
    for (const Region* r : {&upperOnly, &both, &lowerOnly, &open}) ASSERT_GT(r->pixels, 50);
    // One card covering half: half the light, as a fraction in nearly every pixel.
    EXPECT_NEAR(upperOnly.mean, 0.5, 0.1);
    EXPECT_NEAR(lowerOnly.mean, 0.5, 0.1);
    EXPECT_GT(upperOnly.fractional, 0.8);
    // Two: a half of a half (absorbances add, transmittances multiply).
    EXPECT_NEAR(both.mean, 0.25, 0.08);
    EXPECT_GT(open.mean, 0.99);
}

TEST_F(FoliageOpacityTest, AReceiverBetweenTwoLayersIsShadowedByTheOneAboveItAndOpaqueCastersStayHard) {
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Frame f = render(**renderer, s, settings(true));
    // The plate's top: under the upper card, over the lower one, which the same texels hold.
    const Region plateTop = termsOver(f, kPlate, 6.05, 2.3, 2.9, -1.6, -0.4);
    ASSERT_GT(plateTop.pixels, 20);
    EXPECT_NEAR(plateTop.mean, 0.5, 0.12);
    // The plate itself casts through the depth map: a hard shadow, whatever the leaves do.
    const Region underPlate = termsOver(f, kGround, 0.0, 8.35, 8.85, -1.6, -0.4);
    ASSERT_GT(underPlate.pixels, 20);
    EXPECT_LT(underPlate.mean, 0.02);
}

TEST_F(FoliageOpacityTest, WithoutOpacityLayersTheSameLeavesCastAllOrNothingPerPixel) {
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Frame f = render(**renderer, s, settings(false));
    const Region upperOnly = termsOver(f, kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    ASSERT_GT(upperOnly.pixels, 50);
    EXPECT_LT(upperOnly.fractional, 0.05);  // the hard test: each pixel lit or not
    EXPECT_NEAR(upperOnly.mean, 0.5, 0.15); // the coverage-keeping mips keep about half
}

TEST_F(FoliageOpacityTest, UnderTheSunsDiskTheLeavesTransmittanceIsAveragedOverItsCrossing) {
    // PCSS with a sun of 4°: the disk crosses the upper card 9.9 m up the light as a circle 70 cm
    // across, nine texels: the same half of the light on the mean, far less spread from pixel to
    // pixel than the point sun's lookup of one bilinear footprint.
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Region sharp = termsOver(render(**renderer, s, settings(true)), kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    const Region soft = termsOver(render(**renderer, s, underAWideSun()), kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    ASSERT_GT(soft.pixels, 50);
    EXPECT_NEAR(soft.mean, sharp.mean, 0.05);
    EXPECT_LT(soft.spread, 0.6 * sharp.spread) << "point sun " << sharp.spread << ", disk " << soft.spread;
}

TEST_F(FoliageOpacityTest, UnderTheSunsDiskTheGroundBesideACanopysEdgeIsPartlyShadowed) {
    // The upper card's edge z = 2 lies across the light, so it casts onto the ground along z = 2.
    // With a 4° sun the disk crosses the card 9.9 m up the light as a circle 35 cm in radius: the
    // ground 10–25 cm beyond the edge sees some of the card (a half-covered one) across part of the
    // disk, about 0.9 of the sun on the mean, though the map's texel above it holds no leaf. The
    // lookup must look for leaves over the disk, as PCSS's blocker search does; taken from the
    // receiver's own texel alone it drew that ground wholly lit, and so did a search in the
    // prefiltered layers while nothing had been drawn into them (seen while it was written). On
    // virtual pages the search reads the mip levels filtered over the pages' slots alone
    // (opacity_downsample.frag); without them it found no leaf there.
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    for (const core::Technique technique : {core::Technique::Focused, core::Technique::Virtual}) {
        const Frame f = render(**renderer, s, underAWideSun(), technique);
        const Region beside = termsOver(f, kGround, 0.0, 5.5, 7.8, 2.1, 2.25);
        const Region farther = termsOver(f, kGround, 0.0, 5.5, 7.8, 2.5, 2.8);
        ASSERT_GT(beside.pixels, 50);
        ASSERT_GT(farther.pixels, 50);
        EXPECT_LT(beside.mean, 0.97) << core::techniqueName(technique);
        EXPECT_GT(beside.mean, 0.75) << core::techniqueName(technique);
        EXPECT_GT(farther.mean, 0.99) << core::techniqueName(technique); // past the disk's reach: all the sun
    }
}

TEST_F(FoliageOpacityTest, ADiskInsideItsTexelTakesOneTapAndTheLightGrowsSmoothlyWithTheSun) {
    // The layers are constant over each 8 cm texel, so a disk inside a receiver's own texel takes
    // one tap, that texel's value — the point sun's lookup, exactly — and a disk reaching into the
    // neighbours takes the disk's taps. Under the upper card, 9.9 m up the light, suns of 0.01°,
    // 0.03°, 0.12° and 0.30° cross the leaves as disks 0.9 mm, 2.6 mm, 1.0 cm and 2.6 cm in radius:
    // the share of receivers whose disk leaves their texel grows with the disk, and with it the
    // frame's difference from the point sun's — from almost nothing — while the light on the mean
    // stays the point sun's (no step where disks begin to cross texels: no seam). Measured: 0.008,
    // 0.011, 0.028 and 0.064. Taken at one point whatever the disk (a one-tap test too loose), the
    // largest disk would equal the point sun; taps placed wrongly would move the smallest.
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Frame point = render(**renderer, s, settings(true));
    // Mean absolute difference over the ground pixels in some shadow in either frame.
    const auto difference = [](const Frame& x, const Frame& y) {
        double sum = 0.0;
        int pixels = 0;
        for (size_t i = 0; i < x.raster.shadowTerm.size(); ++i) {
            if (x.raster.surfaceId[i] != kGround || y.raster.surfaceId[i] != kGround) continue;
            if (std::min(x.raster.shadowTerm[i], y.raster.shadowTerm[i]) > 0.999f) continue; // open ground
            sum += std::abs(double(x.raster.shadowTerm[i]) - double(y.raster.shadowTerm[i]));
            ++pixels;
        }
        EXPECT_GT(pixels, 1000);
        return sum / std::max(pixels, 1);
    };
    const double pointMean = termsOver(point, kGround, 0.0, 5.5, 7.8, 0.4, 1.6).mean;
    EXPECT_NEAR(pointMean, 0.5, 0.1);
    std::vector<double> differences;
    for (const double degrees : {0.01, 0.03, 0.12, 0.30}) {
        gl::RenderSettings sun = underAWideSun();
        sun.sunAngleDegrees = degrees;
        const Frame f = render(**renderer, s, sun);
        EXPECT_NEAR(termsOver(f, kGround, 0.0, 5.5, 7.8, 0.4, 1.6).mean, pointMean, 0.01) << degrees << "°";
        differences.push_back(difference(f, point));
    }
    EXPECT_LT(differences.front(), 0.015) << ::testing::PrintToString(differences);
    for (size_t i = 1; i < differences.size(); ++i)
        EXPECT_GT(differences[i], differences[i - 1])
            << "the disks' differences " << ::testing::PrintToString(differences);
    EXPECT_GT(differences.back(), 0.03);
}

TEST_F(FoliageOpacityTest, ASunlitLeafIsNotShadedByItsOwnLayer) {
    // One horizontal card covering all it spans (a leaf larger than the texels) 3 m up, the sun 45°
    // above it and nothing else over it: every point of its top is in full sun. The layers hold
    // its depth at each texel's centre, so half of its points lie behind that depth, by up to 4 cm
    // (half an 8 cm texel times the slope, 1), and with the layers' first edge 0.3 m behind the
    // first leaf they read a share of the card's own 99 % absorbance without the lookup's bias (the
    // card's mean term was 0.93, under both suns).
    const scene::Scene s = groundAndCoveredCard(2, 12, 3, 3, 7, -2, 2);
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    constexpr uint32_t kCard = 2;
    for (const gl::RenderSettings& frameSettings : {settings(true), underAWideSun()}) {
        const Frame f = render(**renderer, s, frameSettings);
        const Region top = termsOver(f, kCard, 3.0, 3.3, 6.7, -1.7, 1.7); // 30 cm inside its edges
        ASSERT_GT(top.pixels, 500);
        EXPECT_GT(top.mean, 0.99) << "sun of " << frameSettings.sunAngleDegrees << "°";
        // Its shadow on the ground, 3 m along +x: the card's 1 % all but everywhere.
        const Region shadow = termsOver(f, kGround, 0.0, 6.3, 9.7, -1.7, 1.7);
        ASSERT_GT(shadow.pixels, 500);
        EXPECT_LT(shadow.mean, 0.05);
    }
}

TEST_F(FoliageOpacityTest, VirtualPagesCastTheLeavesFractionThroughTheirOwnLayers) {
    // The first two tests' figures, with the layers drawn page by page into the atlases beside the
    // depth atlas and read through the page table: half the light under one card, a quarter under
    // two, half on the plate's top between them, the plate's own shadow hard. Without the layers the
    // same pages cast all or nothing per pixel.
    const scene::Scene s = cardsOverGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const Frame f = render(**renderer, s, settings(true), core::Technique::Virtual);
    const auto pages = (*renderer)->lastVirtualPages();
    ASSERT_TRUE(pages);
    EXPECT_GT(pages->pagesRendered, 0);
    // The layers' atlases beside the depth atlas's 4 bytes a texel: 12 bytes a texel, the
    // prefiltered layers' 4 with their mips (at most a third more) and the first draw's depth 4.
    const double bytesPerTexel = 4.0 * double(pages->opacityBytes) / double(pages->poolBytes);
    EXPECT_GE(bytesPerTexel, 20.0);
    EXPECT_LE(bytesPerTexel, 20.0 + 4.0 / 3.0);
    const Region upperOnly = termsOver(f, kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    const Region both = termsOver(f, kGround, 0.0, 5.5, 7.8, -1.6, -0.4);
    const Region plateTop = termsOver(f, kPlate, 6.05, 2.3, 2.9, -1.6, -0.4);
    const Region underPlate = termsOver(f, kGround, 0.0, 8.35, 8.85, -1.6, -0.4);
    const Region open = termsOver(f, kGround, 0.0, 10.0, 11.0, -1.0, 1.0);
    for (const Region* r : {&upperOnly, &both, &open}) ASSERT_GT(r->pixels, 50);
    for (const Region* r : {&plateTop, &underPlate}) ASSERT_GT(r->pixels, 20);
    EXPECT_NEAR(upperOnly.mean, 0.5, 0.1);
    EXPECT_GT(upperOnly.fractional, 0.5);
    EXPECT_NEAR(both.mean, 0.25, 0.08);
    EXPECT_NEAR(plateTop.mean, 0.5, 0.12);
    EXPECT_LT(underPlate.mean, 0.02);
    EXPECT_GT(open.mean, 0.99);

    const Frame binary = render(**renderer, s, settings(false), core::Technique::Virtual);
    EXPECT_EQ((*renderer)->lastVirtualPages()->opacityBytes, 0);
    const Region binaryUpper = termsOver(binary, kGround, 0.0, 5.5, 7.8, 0.4, 1.6);
    ASSERT_GT(binaryUpper.pixels, 50);
    EXPECT_LT(binaryUpper.fractional, 0.05);
}

TEST_F(FoliageOpacityTest, AVirtualFrameFromCachedPagesEqualsAFreshOne) {
    // A page's layers are drawn with its depth and cached with it. The same sun and the same pages
    // hold other content with the layers on (the leaves in the layers) and off (in the depth): each
    // switch must draw the pages again, and a frame that draws no page reads what its pages keep.
    // Every frame equals a fresh renderer's first frame with the same settings.
    const scene::Scene s = cardsOverGround();
    const gl::RenderSettings on = underAWideSun();
    gl::RenderSettings off = on;
    off.foliageOpacity = false;
    const auto freshFrame = [&](const gl::RenderSettings& settings) {
        auto fresh = gl::Renderer::create(s);
        EXPECT_TRUE(fresh) << fresh.error();
        return fresh ? render(**fresh, s, settings, core::Technique::Virtual) : Frame{};
    };
    const Frame expectedOn = freshFrame(on), expectedOff = freshFrame(off);
    const auto largestDifference = [](const Frame& a, const Frame& b) {
        EXPECT_EQ(a.raster.shadowTerm.size(), b.raster.shadowTerm.size());
        double largest = 0.0;
        for (size_t i = 0; i < std::min(a.raster.shadowTerm.size(), b.raster.shadowTerm.size()); ++i)
            largest = std::max(largest, std::abs(double(a.raster.shadowTerm[i]) - b.raster.shadowTerm[i]));
        return largest;
    };
    // The leaves do cast through the layers, and differently from the depth test.
    EXPECT_NEAR(termsOver(expectedOn, kGround, 0.0, 5.5, 7.8, 0.4, 1.6).mean, 0.5, 0.1);
    EXPECT_GT(largestDifference(expectedOn, expectedOff), 0.5);

    auto reused = gl::Renderer::create(s);
    ASSERT_TRUE(reused) << reused.error();
    render(**reused, s, on, core::Technique::Virtual);
    struct Step {
        const char* what;
        const gl::RenderSettings* settings;
        const Frame* expected;
        bool drawsPages;
    };
    for (const Step& step :
         {Step{"layers turned off", &off, &expectedOff, true}, Step{"layers turned on again", &on, &expectedOn, true},
          Step{"from cached pages", &on, &expectedOn, false}}) {
        const Frame f = render(**reused, s, *step.settings, core::Technique::Virtual);
        ASSERT_TRUE((*reused)->lastVirtualPages());
        EXPECT_EQ((*reused)->lastVirtualPages()->pagesRendered > 0, step.drawsPages) << step.what;
        EXPECT_LT(largestDifference(f, *step.expected), 1e-5) << step.what;
    }
}
