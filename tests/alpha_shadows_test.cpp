// Alpha-tested casters, end to end: a leaf card's holes let the sun through in the shadow
// maps and in the ray-traced truth alike. CTest label `gl`: headless on Mesa llvmpipe.
#include "headless_gl_test.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/material.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>

using namespace shadowkit;

namespace {

// A 4 × 4 m card standing in the plane x = 0 (facing +x, z in [-2, 2], y in [0.5, 4.5]) over
// a ground plane at y = 0.01, its texture's alpha a checkerboard of 4 × 4 one-metre squares.
// Squares with an even (column + row) are covered.
scene::Scene cardScene(scene::Texture texture, scene::AlphaMode mode, float cutoff) {
    scene::Scene s;
    scene::Mesh ground, card;
    scene::addBox(ground, glm::mat4(1.0f), {12.0f, 0.01f, 12.0f}, glm::vec3(0.7f));
    const glm::mat4 cardFromQuad = glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}) *
                                   glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {0.0f, 1.0f, 0.0f}) *
                                   glm::scale(glm::mat4(1.0f), {4.0f, 4.0f, 1.0f});
    scene::addCard(card, cardFromQuad, {0.0f, 1.0f}, {1.0f, 0.0f}, glm::vec3(0.3f, 0.6f, 0.2f));
    card.material = 0;
    for (scene::Mesh* m : {&ground, &card}) m->computeBounds();
    s.meshes = {ground, card};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    s.textures = {std::move(texture)};
    s.materials = {
        {.name = "checker", .baseColorTexture = 0, .alphaMode = mode, .alphaCutoff = cutoff, .doubleSided = true}};
    return s;
}

scene::Image checkerImage() {
    scene::Image image(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            uint8_t* p = image.pixel(x, y);
            p[0] = p[1] = p[2] = 255;
            p[3] = (x / 16 + y / 16) % 2 == 0 ? 255 : 0;
        }
    return image;
}

scene::Scene checkerCardScene(scene::AlphaMode mode, float cutoff = 0.5f) {
    scene::Texture texture;
    texture.image = checkerImage();
    return cardScene(std::move(texture), mode, cutoff);
}

// `bytes` written whole as dir/name (scene::writeFile), the test failing where it cannot be.
void writeScratch(const std::filesystem::path& dir, const char* name, std::string_view bytes) {
    const core::Status written = scene::writeFile(dir / name, bytes);
    EXPECT_TRUE(written) << written.error();
}

// The same card and ground as a user's OBJ would bring them: the checker as the card's
// material's map_d (an image with alpha), the OBJ's texture coordinates v up, so the image's
// first row (glTF's v = 0, the card's top edge) is v = 1; `leaf` more lines of the card's
// material (a dissolve). Written to `dir`, loaded back.
scene::Scene objCheckerCardScene(const std::filesystem::path& dir, const std::string& leaf = "") {
    std::filesystem::create_directories(dir);
    EXPECT_TRUE(scene::writePng(checkerImage(), dir / "checker.png"));
    writeScratch(dir, "card.mtl",
                 "newmtl ground\nKd 0.7 0.7 0.7\nnewmtl leaf\nKd 0.3 0.6 0.2\nmap_d checker.png\n" + leaf);
    writeScratch(dir, "card.obj",
                 "mtllib card.mtl\n"
                 "o ground\nusemtl ground\n"
                 "v -12 0.01 12\nv 12 0.01 12\nv 12 0.01 -12\nv -12 0.01 -12\nf 1 2 3 4\n"
                 "o card\nusemtl leaf\n" // facing +x: z from +2 (u = 0) to −2
                 "v 0 0.5 2\nv 0 0.5 -2\nv 0 4.5 -2\nv 0 4.5 2\n"
                 "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 5/1 6/2 7/3 8/4\n");
    auto loaded = scene::loadScene(dir / "card.obj");
    EXPECT_TRUE(loaded) << loaded.error();
    return loaded ? std::move(*loaded) : scene::Scene{};
}

// The same card and ground as a glTF whose card is glass (KHR_materials_transmission, an
// opaque material): clear where its transmission texture's red is 255 (the checker's open
// squares), stopping all light where it is 0. Written to `dir`, loaded back.
scene::Scene gltfGlassCardScene(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    scene::Image transmission = checkerImage();
    for (size_t i = 0; i < transmission.rgba.size(); i += 4) {
        transmission.rgba[i] = uint8_t(255 - transmission.rgba[i + 3]); // covered squares let nothing through
        transmission.rgba[i + 3] = 255;
    }
    EXPECT_TRUE(scene::writePng(transmission, dir / "transmission.png"));
    // Ground (y = 0.01, 24 m) then the card (x = 0, z from +2 to −2, y from 0.5 to 4.5), with
    // the card's uvs as cardScene lays them: u from z = +2, v from the top edge down.
    const float positions[] = {-12, 0.01f, 12, 12, 0.01f, 12, 12, 0.01f, -12, -12, 0.01f, -12,
                               0,   0.5f,  2,  0,  0.5f,  -2, 0,  4.5f,  -2,  0,   4.5f,  2};
    const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
    std::string bin;
    bin.append(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
    writeScratch(dir, "card.bin", bin);
    writeScratch(
        dir, "card.gltf",
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0},{"mesh":1}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":3,"material":0}]},)"
        R"({"primitives":[{"attributes":{"POSITION":1,"TEXCOORD_0":2},"indices":3,"material":1}]}],)"
        R"("materials":[{"name":"ground","doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[0.7,0.7,0.7,1]}},)"
        R"({"name":"glass","doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1]},)"
        R"("extensions":{"KHR_materials_transmission":{"transmissionFactor":1,"transmissionTexture":{"index":0}}}}],)"
        R"("textures":[{"source":0}],"images":[{"uri":"transmission.png"}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-12,0.01,-12],"max":[12,0.01,12]},)"
        R"({"bufferView":0,"byteOffset":48,"componentType":5126,"count":4,"type":"VEC3","min":[0,0.5,-2],"max":[0,4.5,2]},)"
        R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},)"
        R"({"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}],)"
        R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":32},)"
        R"({"buffer":0,"byteOffset":128,"byteLength":12}],)"
        R"("buffers":[{"byteLength":140,"uri":"card.bin"}],"extensionsUsed":["KHR_materials_transmission"]})");
    auto loaded = scene::loadScene(dir / "card.gltf");
    EXPECT_TRUE(loaded) << loaded.error();
    return loaded ? std::move(*loaded) : scene::Scene{};
}

// The card as a canopy seen from afar: 200 round leaves of 5 cm (radius 3 texels of 256²)
// covering about a quarter of it, a pattern far finer than a coarse map's texels.
scene::Scene leafyCardScene() {
    scene::Texture texture;
    texture.image = scene::Image(256, 256);
    uint32_t state = 12345u;
    auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8 & 255u; };
    for (int leaf = 0; leaf < 600; ++leaf) {
        const int cx = int(next()), cy = int(next());
        for (int y = cy - 4; y <= cy + 4; ++y)
            for (int x = cx - 4; x <= cx + 4; ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= 9 + 1 && x >= 0 && y >= 0 && x < 256 && y < 256)
                    texture.image.pixel(x, y)[3] = 255;
    }
    return cardScene(std::move(texture), scene::AlphaMode::Mask, 0.5f);
}

// Where the ray from a ground point towards the light (along `wsTowards`) crosses the card's
// plane x = 0: its square's parity and how close it lies to a square's edge (metres), or
// nullopt off the card.
struct CardCrossing {
    bool covered = false;
    double edgeDistance = 0.0;
};
std::optional<CardCrossing> crossing(const core::Vec3& wsGround, const core::Vec3& wsTowards) {
    if (wsGround.x >= 0.0 || wsTowards.x <= 0.0) return std::nullopt;
    const core::Vec3 onCard = wsGround + wsTowards * (-wsGround.x / wsTowards.x);
    const double y = onCard.y, z = onCard.z;
    // The card's texture: u from z = +2 (u = 0) to z = −2, v from the top (y = 4.5, v = 0) down.
    const double u = (2.0 - z) / 4.0, v = (4.5 - y) / 4.0;
    if (u <= 0.0 || u >= 1.0 || v <= 0.0 || v >= 1.0) return std::nullopt;
    const double cu = u * 4.0, cv = v * 4.0; // in squares (= metres)
    const int column = int(cu), row = int(cv);
    const double edge = std::min({cu - column, column + 1 - cu, cv - row, row + 1 - cv});
    return CardCrossing{(column + row) % 2 == 0, edge};
}

struct Agreement {
    int covered = 0, open = 0; // ground pixels behind covered / open squares
    int glAgrees = 0, truthAgrees = 0;
    int glShadowed = 0, truthShadowed = 0;

    void add(const CardCrossing& cross, bool glSaysShadow, bool truthSaysShadow) {
        (cross.covered ? covered : open) += 1;
        glAgrees += glSaysShadow == cross.covered;
        truthAgrees += truthSaysShadow == cross.covered;
        glShadowed += glSaysShadow;
        truthShadowed += truthSaysShadow;
    }
};

core::PerspectiveCamera cardCamera() {
    core::PerspectiveCamera camera;
    camera.wsEye = {-2.5, 9.0, 4.0};
    camera.wsDirection = core::Vec3(-2.5, 0.0, 0.0) - camera.wsEye;
    camera.aspect = 4.0 / 3.0;
    camera.zNear = 1.0;
    camera.zFar = 40.0;
    return camera;
}

gl::RenderSettings cardFrame() {
    gl::RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.fogDensity = 0.0f;
    return settings;
}

class AlphaShadowsTest : public gl::testing::HeadlessGlTest {
protected:
    static Agreement measureCard(const scene::Scene& s, core::Technique technique, int mapSize = 1024,
                                 double edgeMargin = 0.12) {
        auto measurer = measure::Measurer::create(s);
        EXPECT_TRUE(measurer) << measurer.error();
        const core::DirectionalLight sun = core::DirectionalLight::fromDirection({-1.0, -1.0, 0.0}).value();
        auto m = (*measurer)->measure({.camera = cardCamera(),
                                       .light = sun,
                                       .wsSceneBounds = s.wsBounds(),
                                       .technique = technique,
                                       .mapSize = mapSize},
                                      cardFrame());
        EXPECT_TRUE(m) << m.error();
        Agreement a;
        if (!m) return a;
        const eval::TruthBuffers& truth = *m->truth;
        for (size_t i = 0; i < truth.surfaceId.size(); ++i) {
            if (truth.surfaceId[i] != 1 || !truth.facesLight[i] || m->raster.surfaceId[i] != 1) continue; // ground
            const auto cross = crossing(truth.wsPosition[i], -sun.wsDirection);
            if (!cross || cross->edgeDistance < edgeMargin) continue; // a texel and a pixel from every square's edge
            a.add(*cross, m->raster.shadowTerm[i] < 0.5f, !truth.lit[i]);
        }
        return a;
    }

    // A card loaded from a file (ground and card, two meshes) casts the checker, in the truth on
    // every pixel and in the maps up to a few texels of aliasing along the squares' edges.
    static void expectTheCheckerShadow(const scene::Scene& s) {
        ASSERT_EQ(s.meshes.size(), 2u);
        const Agreement a = measureCard(s, core::Technique::Focused);
        const int pixels = a.covered + a.open;
        ASSERT_GT(a.covered, 150);
        ASSERT_GT(a.open, 150);
        EXPECT_EQ(a.truthAgrees, pixels);
        EXPECT_GT(a.glAgrees, 0.97 * pixels);
    }

    // The same under a lamp above and in front of the card (the sun off): a point light's cube
    // or a spot light's map, read from the measurer's per-light classes.
    static Agreement measureCardUnderLamp(const scene::Scene& s, bool spot) {
        auto measurer = measure::Measurer::create(s);
        EXPECT_TRUE(measurer) << measurer.error();
        const core::Vec3 wsLamp(4.0, 8.0, 0.0);
        std::vector<core::PointLight> points;
        std::vector<core::SpotLight> spots;
        if (spot)
            spots.push_back(
                {.wsPosition = wsLamp, .wsDirection = core::Vec3(-2.5, 0, 0) - wsLamp, .coneDegrees = 100.0});
        else
            points.push_back({.wsPosition = wsLamp});
        const core::Aabb bounds = s.wsBounds();
        auto lighting = core::computeLocalLighting({.camera = cardCamera(), .wsSceneBounds = bounds, .mapSize = 1024},
                                                   points, spots);
        EXPECT_TRUE(lighting) << lighting.error();
        EXPECT_TRUE((*measurer)->renderer().setLocalLights(*lighting));
        gl::RenderSettings settings = cardFrame();
        settings.sun = false;
        auto m = (*measurer)->measure({.camera = cardCamera(), .light = {}, .wsSceneBounds = bounds}, settings);
        EXPECT_TRUE(m) << m.error();
        Agreement a;
        if (!m || m->lights.size() != 1) return a;
        const std::vector<eval::PixelClass>& classes = m->lights[0].comparison.classes;
        for (size_t i = 0; i < classes.size(); ++i) {
            using eval::PixelClass;
            const PixelClass c = classes[i];
            if (c == PixelClass::NotEvaluated || c == PixelClass::Excluded || m->truth->surfaceId[i] != 1) continue;
            const auto cross = crossing(m->truth->wsPosition[i], wsLamp - m->truth->wsPosition[i]);
            if (!cross || cross->edgeDistance < 0.12) continue;
            a.add(*cross, c == PixelClass::ShadowCorrect || c == PixelClass::FalseShadow,
                  c == PixelClass::ShadowCorrect || c == PixelClass::FalseLit);
        }
        return a;
    }
};

} // namespace

TEST_F(AlphaShadowsTest, AMaskedCheckerCardCastsACheckerShadowInTheMapsAndInTheTruth) {
    for (const core::Technique technique :
         {core::Technique::Focused, core::Technique::Lispsm, core::Technique::Csm, core::Technique::Virtual}) {
        const Agreement a = measureCard(checkerCardScene(scene::AlphaMode::Mask), technique);
        const int pixels = a.covered + a.open;
        ASSERT_GT(a.covered, 150) << core::techniqueName(technique);
        ASSERT_GT(a.open, 150) << core::techniqueName(technique); // lit squares under the card
        // The truth's rays pass the holes and stop at the squares: exactly the checkerboard.
        EXPECT_EQ(a.truthAgrees, pixels) << core::techniqueName(technique);
        // The maps, up to a few texels of aliasing along the squares' edges.
        EXPECT_GT(a.glAgrees, 0.97 * pixels) << core::techniqueName(technique);
    }
}

TEST_F(AlphaShadowsTest, TheSameCardOpaqueCastsOneSolidShadowAndBlendCastsAsMask) {
    const Agreement opaque = measureCard(checkerCardScene(scene::AlphaMode::Opaque), core::Technique::Focused);
    const int pixels = opaque.covered + opaque.open;
    ASSERT_GT(pixels, 300);
    EXPECT_EQ(opaque.truthShadowed, pixels);
    EXPECT_GT(opaque.glShadowed, 0.99 * pixels);
    // BLEND is cast as MASK at its cutoff (scene/material.h): the checkerboard again.
    const Agreement blend = measureCard(checkerCardScene(scene::AlphaMode::Blend), core::Technique::Focused);
    EXPECT_EQ(blend.truthAgrees, blend.covered + blend.open);
    EXPECT_GT(blend.glAgrees, 0.97 * (blend.covered + blend.open));
    // A cutoff above every alpha the texture holds covers nothing: no shadow at all.
    const Agreement none = measureCard(checkerCardScene(scene::AlphaMode::Mask, 1.01f), core::Technique::Focused);
    ASSERT_GT(none.covered + none.open, 300);
    EXPECT_EQ(none.truthShadowed, 0);
    EXPECT_EQ(none.glShadowed, 0);
}

TEST_F(AlphaShadowsTest, AnObjCardCutByItsMapDCastsTheCheckerShadowToo) {
    // Until OBJ materials read map_d, this card cast its whole square in the maps and the truth.
    const auto dir = shadowkit::test_support::scratchDir() / "alpha_shadows_obj";
    expectTheCheckerShadow(objCheckerCardScene(dir));
    std::filesystem::remove_all(dir);
}

TEST_F(AlphaShadowsTest, AnObjCardsDissolveMultipliesItsMaskAndGlassCastsNothing) {
    // Until the MTL's dissolve was read, a pane written `d 0.1` — glass, as exporters write it —
    // cast its whole square in the maps and in the truth alike.
    const auto dir = shadowkit::test_support::scratchDir() / "alpha_shadows_obj_dissolve";
    for (const char* glass : {"d 0.1\n", "Tr 0.9\n"}) {
        const Agreement none = measureCard(objCheckerCardScene(dir, glass), core::Technique::Focused);
        ASSERT_GT(none.covered + none.open, 300) << glass;
        EXPECT_EQ(none.truthShadowed, 0) << glass;
        EXPECT_EQ(none.glShadowed, 0) << glass;
    }
    // Tinted, stopping more than half: the mask (0 or 1) times 0.8 still cuts the checker.
    expectTheCheckerShadow(objCheckerCardScene(dir, "d 0.8\n"));
    std::filesystem::remove_all(dir);
}

TEST_F(AlphaShadowsTest, AMaterialTheAlphaTestCutsAwayWholeIsDrawnByNoPass) {
    // Clear glass: the checker card at a factor of 0.1, its largest alpha 0.1 under the cutoff 0.5.
    // No fragment of it could pass the alpha test, and no ray may stop on it; it is kept out of
    // every pass on every culling path (GpuScene, GpuCulling) and out of the ray tracer: each pass
    // draws the ground alone, and nothing casts a shadow. Until then every pass drew its two
    // triangles and discarded each of their fragments.
    scene::Scene glass = checkerCardScene(scene::AlphaMode::Mask);
    glass.materials[0].baseColorFactor.a = 0.1f;
    ASSERT_TRUE(scene::coversNothing(glass.materials[0], glass.textures));
    const size_t groundTriangles = glass.meshes[0].triangleCount();
    const core::DirectionalLight sun = core::DirectionalLight::fromDirection({-1.0, -1.0, 0.0}).value();
    const auto setup = core::computeShadowSetup({.camera = cardCamera(),
                                                 .light = sun,
                                                 .wsSceneBounds = glass.wsBounds(),
                                                 .technique = core::Technique::Focused});
    ASSERT_TRUE(setup) << setup.error();
    auto renderer = gl::Renderer::create(glass);
    ASSERT_TRUE(renderer) << renderer.error();
    for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Occlusion, gl::Culling::Gpu}) {
        gl::RenderSettings settings = cardFrame();
        settings.culling = culling;
        for (int frame = 0; frame < 2; ++frame) { // the GPU path's counts come back a frame late
            const auto stats = (*renderer)->render(cardCamera(), sun, *setup, settings);
            ASSERT_TRUE(stats) << stats.error();
            if (frame == 0) continue;
            EXPECT_EQ(stats->shadow.instances, 1u) << int(culling);
            EXPECT_EQ(stats->shadow.triangles, groundTriangles) << int(culling);
            EXPECT_EQ(stats->main.instances, 1u) << int(culling);
            EXPECT_EQ(stats->main.triangles, groundTriangles) << int(culling);
        }
    }
    const Agreement none = measureCard(glass, core::Technique::Focused);
    ASSERT_GT(none.covered + none.open, 300);
    EXPECT_EQ(none.truthShadowed, 0);
    EXPECT_EQ(none.glShadowed, 0);
}

TEST_F(AlphaShadowsTest, AGlassCardLetsTheSunThroughWhereItsTransmissionTextureSays) {
    // Until KHR_materials_transmission was read, this glass cast its whole square in the maps
    // and in the truth alike (every window kept the sun out of its room).
    const auto dir = shadowkit::test_support::scratchDir() / "alpha_shadows_glass";
    expectTheCheckerShadow(gltfGlassCardScene(dir));
    std::filesystem::remove_all(dir);
}

TEST_F(AlphaShadowsTest, ACanopyInACoarseMapKeepsTheCoverageTheTruthSees) {
    // Standard over a 24 m scene at 64 texels: 0.4 m texels, the 4 m card about ten texels
    // wide, so its 256² texture is read around mip level 4 (16² texels). Box-filtered mips would
    // hold alpha near the canopy's mean (~0.25, under the cutoff) there and the shadow would
    // vanish (TextureMipsTest); the coverage-keeping chain keeps the shadowed fraction.
    const scene::Scene canopy = leafyCardScene();
    const Agreement fine = measureCard(canopy, core::Technique::Focused, 2048, 0.05);
    const Agreement coarse = measureCard(canopy, core::Technique::Standard, 64, 0.05);
    const int finePixels = fine.covered + fine.open, coarsePixels = coarse.covered + coarse.open;
    ASSERT_GT(finePixels, 500);
    ASSERT_GT(coarsePixels, 500);
    const double truthShadowed = double(coarse.truthShadowed) / coarsePixels;
    ASSERT_GT(truthShadowed, 0.1); // the leaves' shadow, through the truth's full-resolution card
    ASSERT_LT(truthShadowed, 0.5);
    EXPECT_NEAR(double(fine.glShadowed) / finePixels, truthShadowed, 0.05);     // near: level 0
    EXPECT_NEAR(double(coarse.glShadowed) / coarsePixels, truthShadowed, 0.08); // far: neither thinned nor fattened
}

TEST_F(AlphaShadowsTest, LampsSeeTheCardsHolesInPointCubesAndSpotMaps) {
    for (const bool spot : {false, true}) {
        const Agreement a = measureCardUnderLamp(checkerCardScene(scene::AlphaMode::Mask), spot);
        const int pixels = a.covered + a.open;
        ASSERT_GT(a.covered, 100) << (spot ? "spot" : "point");
        ASSERT_GT(a.open, 100) << (spot ? "spot" : "point");
        EXPECT_EQ(a.truthAgrees, pixels) << (spot ? "spot" : "point");
        EXPECT_GT(a.glAgrees, 0.97 * pixels) << (spot ? "spot" : "point");
    }
}
