// Culling per pass is invisible by contract: the same pixels with and without it, for every
// technique; and a caster outside the view frustum still casts into it. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"
#include "visibility.h"

#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/mesh_lod.h"
#include "shadowkit/scene/views.h"

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

using namespace shadowkit;

namespace {

class CullingTest : public gl::testing::HeadlessGlTest {};

struct Variant {
    std::string name;
    core::ShadowSetupInputs inputs;
};

std::vector<Variant> everyTechnique(const scene::ResolvedView& view, const core::Aabb& bounds, int imageHeight) {
    std::vector<Variant> variants;
    for (const core::TechniqueInfo& t : core::allTechniques()) {
        core::ShadowSetupInputs in{.camera = view.camera,
                                   .light = view.light,
                                   .wsSceneBounds = bounds,
                                   .technique = t.technique,
                                   .mapSize = 512};
        in.virtualMaps.imageHeight = imageHeight; // the frame's rows: the clipmap's pixel footprint
        variants.push_back({std::string(t.name), in});
    }
    core::ShadowSetupInputs warped = variants.back().inputs;
    warped.technique = core::Technique::Csm;
    warped.cascades.warp = core::CascadeWarp::Lispsm;
    variants.push_back({"csm lispsm", warped});
    warped.cascades.warp = core::CascadeWarp::None;
    warped.cascades.stabilize = true;
    variants.push_back({"csm stabilized", warped});
    return variants;
}

// A standard view shaped for a small frame of width x height pixels.
scene::ResolvedView smallView(const scene::Scene& forest, const char* name, int width, int height) {
    scene::ResolvedView view = gl::testing::standardView(forest, name);
    view.camera.aspect = double(width) / height;
    return view;
}
using gl::testing::smallFrame;

// LiSPSM at 512² over the whole forest: a set-up every culling must draw alike.
core::Result<core::ShadowSetup> lispsmOver(const scene::Scene& forest, const scene::ResolvedView& view) {
    return core::computeShadowSetup({.camera = view.camera,
                                     .light = view.light,
                                     .wsSceneBounds = forest.wsBounds(),
                                     .technique = core::Technique::Lispsm,
                                     .mapSize = 512});
}

// A frame drawn over the camera's depth pre-pass (CHC++, GPU culling, receiver masks) against
// the same frame drawn without culling: the same pixels, but where two triangles lie at the same
// depth — a z-fight, where draw order picks: the first drawn on a cleared depth (GL_LESS), the
// last over the pre-pass's depth (GL_LEQUAL, CameraPasses). A tie shows as another surface or
// another face of the same one (its normal); such ties are few and each is one triangle level
// with another, never a surface missing or one drawn over a nearer one.
void expectSameFrame(const scene::Image& fullImage, const core::RasterBuffers& full, const scene::Image& image,
                     const core::RasterBuffers& buffers, const std::string& what) {
    ASSERT_EQ(full.surfaceId.size(), buffers.surfaceId.size()) << what;
    size_t ties = 0, tiesApart = 0, shadowDiffers = 0, colorDiffers = 0;
    for (size_t i = 0; i < full.surfaceId.size(); ++i) {
        if (full.surfaceId[i] != buffers.surfaceId[i] || full.wsNormal[i] != buffers.wsNormal[i]) {
            ++ties;
            tiesApart += std::abs(full.viewDepth[i] - buffers.viewDepth[i]) > 1e-4f * std::max(full.viewDepth[i], 1.0f);
            continue;
        }
        shadowDiffers += full.shadowTerm[i] != buffers.shadowTerm[i];
        colorDiffers +=
            !std::equal(fullImage.rgba.begin() + 4 * i, fullImage.rgba.begin() + 4 * i + 4, image.rgba.begin() + 4 * i);
    }
    EXPECT_EQ(shadowDiffers, 0u) << what;
    EXPECT_EQ(colorDiffers, 0u) << what;
    EXPECT_EQ(tiesApart, 0u) << what << ": a pixel shows another surface at another depth";
    EXPECT_LE(ties, full.surfaceId.size() / 1000) << what << ": more than one pixel in a thousand tied";
}

// One 512² TSM map of the view over the scene: the levels tests' set-up.
core::Result<core::ShadowSetup> tsmOf(const scene::ResolvedView& view, const scene::Scene& scene) {
    return core::computeShadowSetup({.camera = view.camera,
                                     .light = view.light,
                                     .wsSceneBounds = scene.wsBounds(),
                                     .technique = core::Technique::Tsm,
                                     .mapSize = 512});
}

} // namespace

TEST_F(CullingTest, CulledFramesMatchFullFramesPixelForPixelForEveryTechnique) {
    const scene::Scene forest = gl::testing::smallForest(400, 300, 32);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    EXPECT_EQ((*renderer)->wsSceneBounds().min, forest.wsBounds().min);
    EXPECT_EQ((*renderer)->wsSceneBounds().max, forest.wsBounds().max);
    for (const char* viewName : {"perpendicular", "aerial"}) {
        const scene::ResolvedView view = smallView(forest, viewName, 160, 90);
        for (const Variant& v : everyTechnique(view, forest.wsBounds(), 90)) {
            const auto setup = core::computeShadowSetup(v.inputs);
            ASSERT_TRUE(setup) << v.name << ": " << setup.error();
            gl::RenderSettings settings = smallFrame(160, 90, gl::Culling::Off);
            const auto full = (*renderer)->render(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(full);
            const scene::Image fullImage = (*renderer)->readColor();
            const auto fullBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            settings.culling = gl::Culling::Frustum;
            const auto culled = (*renderer)->render(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(culled);
            const scene::Image culledImage = (*renderer)->readColor();
            const auto culledBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(fullBuffers && culledBuffers);

            // Everything on: occlusion-culled camera pass, casters culled by visible receivers.
            settings.culling = gl::Culling::Occlusion;
            settings.receiverMask = true;
            const auto fewest = (*renderer)->render(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(fewest) << fewest.error();
            const scene::Image fewestImage = (*renderer)->readColor();
            const auto fewestBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(fewestBuffers);

            // GPU-driven: the lists computed by compute passes, the camera's occlusion two-phase,
            // the receiver masks tested there too.
            settings.culling = gl::Culling::Gpu;
            const auto gpu = (*renderer)->render(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(gpu) << gpu.error();
            const scene::Image gpuImage = (*renderer)->readColor();
            const auto gpuBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(gpuBuffers);

            const std::string what = std::string(viewName) + ", " + v.name;
            expectSameFrame(fullImage, *fullBuffers, gpuImage, *gpuBuffers, what + ", gpu");
            EXPECT_LE(gpu->main.instances, culled->main.instances) << what << ", gpu";
            EXPECT_LE(gpu->shadow.instances, culled->shadow.instances) << what << ", gpu with receiver masks";
            expectSameFrame(fullImage, *fullBuffers, fewestImage, *fewestBuffers, what + ", chc + receiver masks");
            EXPECT_LE(fewest->shadow.instances, culled->shadow.instances) << what;
            EXPECT_LE(fewest->main.instances, culled->main.instances) << what;
            EXPECT_EQ(fullImage.rgba, culledImage.rgba) << what;
            EXPECT_EQ(fullBuffers->shadowTerm, culledBuffers->shadowTerm) << what;
            EXPECT_EQ(fullBuffers->surfaceId, culledBuffers->surfaceId) << what;
            EXPECT_EQ(fullBuffers->viewDepth, culledBuffers->viewDepth) << what;
            // ... while drawing less: the camera sees part of the forest, each map part of it.
            EXPECT_LT(culled->main.instances, full->main.instances) << what;
            EXPECT_LE(culled->shadow.instances, full->shadow.instances) << what;
            EXPECT_EQ(full->main.instances, forest.instanceCount()) << what;
        }
    }
}

TEST_F(CullingTest, CasterOutsideTheViewFrustumIsDrawnIntoTheMapAndItsShadowAppears) {
    // A wall 15 m tall stands behind the camera, out of its view; the low sun behind it
    // throws its shadow forward onto the ground the camera looks at.
    scene::Scene s;
    scene::Mesh ground, wall;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, -30}), {40, 0.05f, 60}, glm::vec3(0.8f));
    scene::addBox(wall, glm::mat4(1.0f), {2, 7.5f, 0.5f}, glm::vec3(0.8f));
    ground.computeBounds();
    wall.computeBounds();
    s.meshes = {ground, wall};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 7.5f, 12})}, false}};
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 3, 0};
    cam.wsDirection = {0, -0.35, -1};
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 60;
    const core::DirectionalLight sun =
        core::DirectionalLight::fromDirection({0, -0.5, -1}).value(); // from behind the wall
    // The wall is out of the view frustum.
    const core::Aabb wallBox = core::transformBounds(core::Mat4(s.batches[1].worldFromObject[0]), wall.osBounds);
    bool anyCornerVisible = false;
    for (const core::Vec3& c : wallBox.corners()) {
        const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(c, 1.0);
        anyCornerVisible |= cs.w > 0 && std::abs(cs.x) <= cs.w && std::abs(cs.y) <= cs.w && cs.z >= 0 && cs.z <= cs.w;
    }
    ASSERT_FALSE(anyCornerVisible);

    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.fogDensity = 0.0f;
    // Also with casters culled by visible receivers: the wall is out of view, but the
    // ground it shadows is in view, so the receiver mask must keep it. On the CPU and on the GPU.
    for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu})
        for (const bool receiverMask : {false, true})
            for (core::Technique t :
                 {core::Technique::Focused, core::Technique::Lispsm, core::Technique::Tsm, core::Technique::Csm}) {
                settings.culling = culling;
                settings.receiverMask = receiverMask;
                const auto setup = core::computeShadowSetup(
                    {.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = t, .mapSize = 1024});
                ASSERT_TRUE(setup);
                const auto stats = (*renderer)->render(cam, sun, *setup, settings);
                ASSERT_TRUE(stats);
                EXPECT_EQ(stats->main.instances, 1u)
                    << core::techniqueName(t) << ": the camera pass draws the ground only";
                EXPECT_GE(stats->shadow.instances, 2u * setup->views.size() - (setup->views.size() - 1))
                    << core::techniqueName(t) << ": the wall must be in the map that serves its shadow";
                const scene::Image image = (*renderer)->readColor();
                // The wall's shadow on the ground, 12 m + 15 m / tan(26.6°) ≈ 18 m ahead of it: well in view.
                const auto shadowAt = [&](double z) { return core::Vec3(0, 0, z); };
                auto luminance = [&](const core::Vec3& ws) {
                    const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(ws, 1.0);
                    const int x = static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * image.width);
                    const int y = static_cast<int>((0.5 - cs.y / cs.w * 0.5) * image.height);
                    const uint8_t* p = image.pixel(x, y);
                    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                };
                const double inShadow = luminance(shadowAt(-10)), lit = luminance(core::Vec3(4, 0, -10));
                EXPECT_LT(inShadow, 0.7 * lit) << core::techniqueName(t) << ": shadow " << inShadow << ", lit " << lit;
            }
}

TEST_F(CullingTest, LevelsOfDetailDrawFewerTrianglesForDistantTreesWithinTheirErrorBound) {
    const scene::Scene forest = gl::testing::smallForest(1500, 600, 32);
    const scene::ResolvedView view = smallView(forest, "aerial", 320, 180);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer);
    for (core::Technique t : {core::Technique::Focused, core::Technique::Tsm, core::Technique::Csm}) {
        const auto setup = core::computeShadowSetup({.camera = view.camera,
                                                     .light = view.light,
                                                     .wsSceneBounds = forest.wsBounds(),
                                                     .technique = t,
                                                     .mapSize = 512});
        ASSERT_TRUE(setup);
        gl::RenderSettings settings = smallFrame(320, 180, gl::Culling::Frustum);
        auto frame = [&](bool lod, float bound) {
            settings.lod = lod;
            settings.lodPixelError = settings.lodTexelError = bound;
            auto stats = (*renderer)->render(view.camera, view.light, *setup, settings);
            auto buffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            EXPECT_TRUE(stats && buffers);
            return std::pair{*stats, *buffers};
        };
        const auto [fullStats, full] = frame(false, 0.5f);
        const auto [lodStats, lod] = frame(true, 0.5f);
        (void)lod;
        const auto [strictStats, strict] = frame(true, 1e-4f);
        const std::string name(core::techniqueName(t));
        // Coarser meshes for the distant trees of the aerial view, in both kinds of pass; the
        // same instances either way.
        EXPECT_LT(lodStats.shadow.triangles, fullStats.shadow.triangles) << name;
        EXPECT_LT(lodStats.main.triangles, fullStats.main.triangles) << name;
        EXPECT_EQ(lodStats.shadow.instances, fullStats.shadow.instances) << name;
        EXPECT_EQ(lodStats.main.instances, fullStats.main.instances) << name;
        // (Their effect on correctness is measured against ray-traced truth in
        // tests/eval_integration_test.cpp.) A bound no level meets draws the full meshes:
        // the same frame exactly.
        EXPECT_EQ(strictStats.main.triangles, fullStats.main.triangles) << name;
        EXPECT_EQ(strictStats.shadow.triangles, fullStats.shadow.triangles) << name;
        EXPECT_EQ(strict.shadowTerm, full.shadowTerm) << name;
        EXPECT_EQ(strict.surfaceId, full.surfaceId) << name;
    }
}

// Renderer::levelsDrawn (the report's level map) says which level each pass drew each instance
// at: summed over the instances, those levels' triangles are exactly what the frame's passes
// submitted, on the CPU's lists and on the GPU's (read back), and the leafy trees' far levels
// — their billboard clouds — are among them in both passes. Renderer::workByLevel, what `bench`
// prints of where the triangles went, splits the same counts by level and by material.
TEST_F(CullingTest, LevelsDrawnAccountForEveryTriangleEachPassSubmitted) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    const scene::ResolvedView view = smallView(forest, "aerial", 320, 180);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer);
    // Each global instance's mesh, and each mesh's triangles per level (as the renderer builds them).
    std::vector<uint32_t> meshOf;
    for (const scene::MeshBatch& batch : forest.batches)
        meshOf.insert(meshOf.end(), batch.worldFromObject.size(), batch.mesh);
    std::vector<scene::MeshLods> lods; // as the renderer builds them (Renderer::create)
    for (const scene::Mesh& mesh : forest.meshes)
        lods.push_back(scene::buildLods(mesh, gl::lodOptionsOf(forest, mesh)));
    // Also per level, as Renderer::workByLevel gives it: the same instances' levels counted here.
    auto trianglesOf = [&](const std::vector<uint8_t>& levels, bool shadow, uint8_t& coarsestLeaves,
                           std::vector<gl::LevelWork>& perLevel) {
        size_t triangles = 0;
        perLevel.assign(gl::kMaxLodLevels, {});
        for (size_t i = 0; i < levels.size(); ++i) {
            if (levels[i] == gl::kLevelNotDrawn) continue;
            const auto& chain = shadow ? lods[meshOf[i]].shadow : lods[meshOf[i]].camera;
            EXPECT_LT(levels[i], chain.size()) << i;
            const size_t levelTriangles = chain[levels[i]].indexCount / 3;
            triangles += levelTriangles;
            gl::LevelWork& work = perLevel[levels[i]];
            ++work.instances, work.triangles += levelTriangles;
            if (forest.meshes[meshOf[i]].material >= 0) {
                coarsestLeaves = std::max(coarsestLeaves, levels[i]);
                ++work.alphaTestedInstances, work.alphaTestedTriangles += levelTriangles;
            }
        }
        return triangles;
    };
    auto expectEqualWork = [](const std::vector<gl::LevelWork>& got, const std::vector<gl::LevelWork>& want,
                              const std::string& name) {
        ASSERT_EQ(got.size(), want.size()) << name;
        for (size_t l = 0; l < want.size(); ++l) {
            EXPECT_EQ(got[l].instances, want[l].instances) << name << " level " << l;
            EXPECT_EQ(got[l].triangles, want[l].triangles) << name << " level " << l;
            EXPECT_EQ(got[l].alphaTestedInstances, want[l].alphaTestedInstances) << name << " level " << l;
            EXPECT_EQ(got[l].alphaTestedTriangles, want[l].alphaTestedTriangles) << name << " level " << l;
        }
    };
    const auto setup = tsmOf(view, forest);
    ASSERT_TRUE(setup);
    for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu}) {
        gl::RenderSettings settings = smallFrame(320, 180, culling);
        settings.lodFoliageScale = 32.0f; // clouds within this small forest
        const auto stats = (*renderer)->render(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(stats) << stats.error();
        const gl::LevelsDrawn levels = (*renderer)->levelsDrawn();
        ASSERT_EQ(levels.camera.size(), meshOf.size());
        ASSERT_EQ(levels.sun.size(), meshOf.size());
        uint8_t cameraLeaves = 0, sunLeaves = 0;
        std::vector<gl::LevelWork> cameraWork, sunWork;
        const std::string name(gl::cullingName(culling));
        EXPECT_EQ(trianglesOf(levels.camera, false, cameraLeaves, cameraWork), stats->main.triangles) << name;
        EXPECT_EQ(trianglesOf(levels.sun, true, sunLeaves, sunWork), stats->shadow.triangles)
            << name; // one map: once each
        EXPECT_GE(cameraLeaves, 2) << name << ": the second cloud or coarser in the camera pass";
        EXPECT_GE(sunLeaves, 1) << name << ": a cloud in the shadow pass";
        const gl::WorkByLevel work = (*renderer)->workByLevel();
        expectEqualWork(work.camera, cameraWork, name + ", camera pass");
        expectEqualWork(work.sun, sunWork, name + ", sun pass");
    }
}

// RenderSettings::lodCamera (eval --path --level-pops' hook): the levels every pass draws are those
// its camera chooses, on the CPU's lists and the GPU's, while the frame is drawn from its own. Set
// to the frame's camera it changes nothing; set to a camera ten times as far back along the view,
// no instance is drawn finer than its own camera draws it and some coarser, in the camera pass and
// in the sun's, and the picture shows it (eval::levelPops counts such pixels; tested in libs/eval).
// (The GPU path's occlusion culling may draw another set of hidden instances from one drawing to
// the next; the levels are compared where both drew an instance.)
TEST_F(CullingTest, LevelsChosenByAnotherCameraAreThatCamerasOnEveryCullingPath) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    const scene::ResolvedView view = smallView(forest, "aerial", 320, 180);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer);
    const auto setup = tsmOf(view, forest);
    ASSERT_TRUE(setup);
    core::PerspectiveCamera farther = view.camera;
    farther.wsEye -=
        10.0 * glm::normalize(view.camera.wsDirection) * glm::length(view.camera.wsEye - forest.wsBounds().center());
    farther.zFar *= 20.0;
    // Instances drawn by both, and of them those drawn finer and coarser in `theirs` than in `mine`.
    struct Shift {
        size_t both = 0, finer = 0, coarser = 0;
    };
    auto shift = [](const std::vector<uint8_t>& mine, const std::vector<uint8_t>& theirs) {
        EXPECT_EQ(mine.size(), theirs.size());
        Shift out;
        for (size_t i = 0; i < std::min(mine.size(), theirs.size()); ++i) {
            if (mine[i] == gl::kLevelNotDrawn || theirs[i] == gl::kLevelNotDrawn) continue;
            ++out.both;
            out.finer += theirs[i] < mine[i];
            out.coarser += theirs[i] > mine[i];
        }
        return out;
    };
    auto changedPixels = [](const core::RasterBuffers& a, const core::RasterBuffers& b) {
        size_t changed = 0;
        for (size_t p = 0; p < a.surfaceId.size(); ++p)
            changed += a.surfaceId[p] != b.surfaceId[p] || a.shadowTerm[p] != b.shadowTerm[p];
        return changed;
    };
    for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu}) {
        const std::string name(gl::cullingName(culling));
        gl::RenderSettings settings = smallFrame(320, 180, culling); // the default foliage scale
        auto drawn = [&](std::optional<core::PerspectiveCamera> lodCamera) {
            settings.lodCamera = lodCamera;
            auto buffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            EXPECT_TRUE(buffers) << name << ": " << buffers.error();
            return std::pair{std::move(buffers).value(), (*renderer)->levelsDrawn()};
        };
        const auto [own, ownLevels] = drawn(std::nullopt);
        const auto [same, sameLevels] = drawn(view.camera);
        for (const Shift& s : {shift(ownLevels.camera, sameLevels.camera), shift(ownLevels.sun, sameLevels.sun)}) {
            EXPECT_GT(s.both, 100u) << name;
            EXPECT_EQ(s.finer + s.coarser, 0u) << name << ": the frame's own camera as the levels' camera";
        }
        EXPECT_EQ(changedPixels(own, same), 0u) << name;

        // Measured when written, on both paths: 69 of 240 instances coarser in the camera pass, 33
        // of 295 in the sun's, whose own texel bound still holds most (the camera's is its second).
        const auto [far, farLevels] = drawn(farther);
        for (const auto& [s, pass, atLeast] : {std::tuple{shift(ownLevels.camera, farLevels.camera), "camera", 0.2},
                                               std::tuple{shift(ownLevels.sun, farLevels.sun), "sun", 0.05}}) {
            EXPECT_EQ(s.finer, 0u) << name << ", " << pass << " pass: finer for a farther camera";
            EXPECT_GT(double(s.coarser), atLeast * double(s.both)) << name << ", " << pass << " pass, of " << s.both;
        }
        EXPECT_GT(changedPixels(own, far), own.surfaceId.size() / 100) << name;
    }
}

TEST_F(CullingTest, OcclusionCulledFramesMatchFrustumCulledFramesAfterTheFirst) {
    // CHC++ leaves out only what its queries prove hidden, so a static view looks exactly as
    // it does with frustum culling alone, while drawing fewer instances in a forest.
    const scene::Scene forest = gl::testing::smallForest(600, 200, 32);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    const scene::ResolvedView view = smallView(forest, "perpendicular", 160, 90);
    const auto setup = lispsmOver(forest, view);
    ASSERT_TRUE(setup) << setup.error();
    gl::RenderSettings settings = smallFrame(160, 90, gl::Culling::Frustum);
    const auto frustum = (*renderer)->render(view.camera, view.light, *setup, settings);
    ASSERT_TRUE(frustum);
    const scene::Image frustumImage = (*renderer)->readColor();
    const auto frustumBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
    settings.culling = gl::Culling::Occlusion;
    for (int frame = 0; frame < 3; ++frame) {
        const auto occluded = (*renderer)->render(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(occluded) << occluded.error();
        EXPECT_EQ(frustumImage.rgba, (*renderer)->readColor().rgba) << "frame " << frame;
        EXPECT_LT(occluded->main.instances, frustum->main.instances) << "frame " << frame;
        EXPECT_GT(occluded->occlusion.queriesIssued, 0u);
    }
    const auto occludedBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
    ASSERT_TRUE(frustumBuffers && occludedBuffers);
    EXPECT_EQ(frustumBuffers->surfaceId, occludedBuffers->surfaceId);
    EXPECT_EQ(frustumBuffers->shadowTerm, occludedBuffers->shadowTerm);
}

// Where a frame has a camera depth pre-pass (CHC++, GPU culling, receiver masks) its camera
// passes draw over that depth (CameraPasses): a leafy forest of stacked alpha-tested cards, some
// trees crossing between two levels (dithered), looks as it does without one, up to surfaces
// tied in depth, while its main pass shades each covered pixel once — the samples its depth test
// passed are the covered pixels, where drawn on a cleared depth they are a quarter more or over.
TEST_F(CullingTest, OverTheCameraPrePassEachPixelIsShadedOnceAndTheFrameIsTheSame) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    constexpr int kWidth = 320, kHeight = 180;
    constexpr uint64_t kPixels = uint64_t(kWidth) * kHeight;
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    // ARB_pipeline_statistics_query: Mesa's drivers and NVIDIA's have it.
    const bool countsShading = epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query");
    for (const char* viewName : {"perpendicular", "aerial"}) {
        const scene::ResolvedView view = smallView(forest, viewName, kWidth, kHeight);
        const auto setup = lispsmOver(forest, view);
        ASSERT_TRUE(setup) << setup.error();
        gl::RenderSettings settings = smallFrame(kWidth, kHeight, gl::Culling::Frustum);
        settings.lodFade = 0.5f;
        const auto cleared = (*renderer)->render(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(cleared) << cleared.error();
        const scene::Image clearedImage = (*renderer)->readColor();
        const auto clearedBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(clearedBuffers) << clearedBuffers.error();
        const uint64_t covered =
            uint64_t(std::ranges::count_if(clearedBuffers->surfaceId, [](uint32_t id) { return id != 0; }));
        EXPECT_GT(covered, kPixels / 2) << viewName << ": the forest fills most of the frame";
        EXPECT_GT(cleared->main.samplesPassed, covered * 5 / 4) << viewName << ": the leaves' overdraw";
        EXPECT_EQ(cleared->main.fragmentsShaded > 0, countsShading) << viewName;

        struct PrePassed {
            const char* name;
            gl::Culling culling;
            bool receiverMask;
        };
        for (const PrePassed& p :
             {PrePassed{"frustum + receiver masks", gl::Culling::Frustum, true},
              PrePassed{"chc", gl::Culling::Occlusion, false}, PrePassed{"gpu", gl::Culling::Gpu, true}}) {
            const std::string what = std::string(viewName) + ", " + p.name;
            settings.culling = p.culling;
            settings.receiverMask = p.receiverMask;
            const auto over = (*renderer)->render(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(over) << what << ": " << over.error();
            const scene::Image image = (*renderer)->readColor();
            const auto buffers = (*renderer)->renderEvalBuffers(view.camera, view.light, *setup, settings);
            ASSERT_TRUE(buffers) << what << ": " << buffers.error();
            expectSameFrame(clearedImage, *clearedBuffers, image, *buffers, what);
            // Every sample written was shaded, in both passes, where the driver counts shading.
            if (countsShading) {
                EXPECT_GE(over->main.fragmentsShaded, over->main.samplesPassed) << what;
                EXPECT_GE(over->shadow.fragmentsShaded, over->shadow.samplesPassed) << what;
            }
            // Each covered pixel once; a tie of two triangles in depth passes both (1.3 % more
            // here on `perpendicular`, most of them where a tree crossing between levels draws
            // both at one depth; under 1 % without the crossing).
            EXPECT_GE(over->main.samplesPassed, covered) << what;
            EXPECT_LE(over->main.samplesPassed, covered + covered / 50) << what;
        }
    }
}

TEST(CullingAutoTest, IsGpuOnAGpuAndChcOnASoftwareRasteriser) {
    // GL_RENDERER strings as drivers give them: Mesa's CPU rasterisers and SwiftShader share the
    // CPU's cores with culling's compute passes; every GPU (Mesa's hardware drivers, whose names
    // mention LLVM too, included) does not.
    for (const char* software : {"llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", "SwiftShader Device (Subzero)",
                                 "Mesa X11 swrast", "GDI Generic", "Microsoft Basic Render Driver"}) {
        EXPECT_TRUE(gl::isSoftwareRasteriser(software)) << software;
        EXPECT_EQ(gl::resolveCulling(gl::Culling::Auto, software), gl::Culling::Occlusion) << software;
    }
    for (const char* gpu : {"NVIDIA H200/PCIe/SSE2", "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7)",
                            "Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "Apple M2", ""}) {
        EXPECT_FALSE(gl::isSoftwareRasteriser(gpu)) << gpu;
        EXPECT_EQ(gl::resolveCulling(gl::Culling::Auto, gpu), gl::Culling::Gpu) << gpu;
    }
    // A culling asked for by name is kept on either.
    for (const gl::Culling asked : {gl::Culling::Off, gl::Culling::Frustum, gl::Culling::Occlusion, gl::Culling::Gpu})
        for (const char* renderer : {"llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H200/PCIe/SSE2"})
            EXPECT_EQ(gl::resolveCulling(asked, renderer), asked) << gl::cullingName(asked) << " on " << renderer;
}

TEST_F(CullingTest, AutoDrawsTheCullingItResolvesToForThisDriver) {
    // No pass may see Auto: a frame asking for it is the frame of the culling it resolves to —
    // pixel for pixel, with that culling's own work (CHC++'s queries, or none on the GPU path).
    // Each first frame of a renderer of its own, so CHC++'s history cannot differ.
    const scene::Scene forest = gl::testing::smallForest(300, 200, 32);
    const scene::ResolvedView view = smallView(forest, "perpendicular", 160, 90);
    const auto setup = lispsmOver(forest, view);
    ASSERT_TRUE(setup) << setup.error();
    std::optional<gl::Culling> resolved;
    std::vector<gl::FrameStats> stats;
    std::vector<scene::Image> images;
    for (int frame = 0; frame < 2; ++frame) {
        auto renderer = gl::Renderer::create(forest);
        ASSERT_TRUE(renderer) << renderer.error();
        if (!resolved) resolved = (*renderer)->culling(gl::Culling::Auto);
        const auto drawn = (*renderer)->render(view.camera, view.light, *setup,
                                               smallFrame(160, 90, frame == 0 ? gl::Culling::Auto : *resolved));
        ASSERT_TRUE(drawn) << drawn.error();
        stats.push_back(*drawn);
        images.push_back((*renderer)->readColor());
    }
    EXPECT_EQ(*resolved, gl::resolveCulling(gl::Culling::Auto, context().renderer()));
    EXPECT_EQ(*resolved, gl::isSoftwareRasteriser(context().renderer()) ? gl::Culling::Occlusion : gl::Culling::Gpu);
    EXPECT_EQ(images[0].rgba, images[1].rgba);
    EXPECT_EQ(stats[0].main.instances, stats[1].main.instances);
    EXPECT_EQ(stats[0].shadow.instances, stats[1].shadow.instances);
    EXPECT_EQ(stats[0].occlusion.nodesVisited > 0, *resolved == gl::Culling::Occlusion);
}
