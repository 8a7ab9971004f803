// GPU-driven culling (gl/src/gpu_culling.h): its lists are the CPU path's, entry for entry,
// one pass at a time or many at once; its two-phase occlusion never costs a pixel — not on the
// first frame, not after a cut, not after an instance moves; a steady frame uploads no lists and
// dispatches as many passes whatever the forest; a virtual clipmap's pages, culled on the GPU in
// three dispatches whatever their number, draw the CPU path's pixels and count its casters.
// CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "gpu_culling.h"
#include "gpu_scene.h"
#include "program.h"
#include "visibility.h"

#include "shadowkit/gl/read_backs.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/mesh_lod.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <random>
#include <set>

using namespace shadowkit;

namespace {

class GpuCullingTest : public gl::testing::HeadlessGlTest {};

using gl::testing::smallFrame;

core::ShadowSetup lispsmSetup(const scene::ResolvedView& view, const scene::Scene& scene) {
    const core::ShadowSetupInputs in{.camera = view.camera,
                                     .light = view.light,
                                     .wsSceneBounds = scene.wsBounds(),
                                     .technique = core::Technique::Lispsm,
                                     .mapSize = 512};
    auto setup = core::computeShadowSetup(in);
    EXPECT_TRUE(setup) << setup.error();
    return setup ? *setup : core::ShadowSetup{};
}

// What compareWithTheCpuPath drew: instances kept by camera and shadow passes, those drawn
// coarser than level 0, crossing into the next level (LodChoice::fadeBand), and, per batch, how
// many were drawn at its coarsest level.
struct ComparedLists {
    size_t drawnCamera = 0, drawnShadow = 0, coarser = 0, crossing = 0;
    std::vector<size_t> coarsest;
};

// Random camera frusta (levels by pixels) and shadow maps (levels by texels and by the camera's
// pixels), near the scene and far out, culled by both paths: the GPU's lists must equal
// Visibility::collect's entry for entry — the same half-spaces and level rule in double
// precision, compacted in instance order. `coverageScale` and `fadeBand` give each case's
// LodChoice::coverageScale and fadeBand.
template <class CoverageScale, class FadeBand>
ComparedLists compareWithTheCpuPath(const scene::Scene& scene, CoverageScale coverageScale, FadeBand fadeBand) {
    ComparedLists result;
    result.coarsest.assign(scene.batches.size(), 0);
    std::vector<scene::MeshLods> lods;
    for (const scene::Mesh& mesh : scene.meshes) lods.push_back(scene::buildLods(mesh));
    const gl::GpuScene gpuScene(scene, lods);
    gl::Visibility visibility(scene, lods);
    const auto culling = gl::GpuCulling::create(scene, lods, gpuScene);
    EXPECT_TRUE(culling->buildPrograms());
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), between(0.0, 1.0);
    constexpr int kCases = 60;
    culling->beginFrame(kCases);
    for (int c = 0; c < kCases; ++c) {
        core::PerspectiveCamera camera;
        camera.wsEye = core::Vec3(150.0 * unit(random), 2.0 + 80.0 * between(random), 150.0 * unit(random));
        camera.wsDirection = core::Vec3(unit(random), -0.6 * between(random), unit(random));
        camera.fovYDegrees = 30.0 + 60.0 * between(random);
        camera.zFar = 50.0 + 400.0 * between(random);
        const core::DirectionalLight light{
            glm::normalize(core::Vec3(unit(random), -0.3 - between(random), unit(random)))};
        const int pixels = 64 << (c % 5); // pixel bounds from coarse to fine
        const gl::LodProjection cameraProjection{camera.clipFromWorld(), 0.5 * pixels, 0.25 + between(random)};
        gl::PassList cpu, gpu;
        const bool shadow = c % 2 == 1;
        std::vector<visibility::HalfSpace> volume;
        gl::LodChoice lod{cameraProjection, std::nullopt, false, coverageScale(random), fadeBand(random)};
        if (shadow) {
            const core::ShadowSetupInputs in{.camera = camera,
                                             .light = light,
                                             .wsSceneBounds = scene.wsBounds(),
                                             .technique = core::Technique::Focused,
                                             .mapSize = 1024};
            const auto setup = core::computeShadowSetup(in);
            EXPECT_TRUE(setup) << setup.error();
            if (!setup) return result;
            const core::Mat4& clipFromWorld = setup->views[0].clipFromWorld;
            volume = visibility::clipVolume(clipFromWorld, false);
            lod = {
                {clipFromWorld, 0.5 * setup->mapSize, 0.25}, cameraProjection, true, lod.coverageScale, lod.fadeBand};
        } else {
            volume = visibility::clipVolume(camera.clipFromWorld());
        }
        const gl::LodChoice* lodOrNone = c % 7 == 3 ? nullptr : &lod;
        visibility.collect(volume, true, lodOrNone, cpu);
        culling->cull(size_t(c), volume, lodOrNone, gl::GpuCulling::Phase::All, gpu);
        const gl::PassList back = culling->read(gpu);
        EXPECT_EQ(back.count, cpu.count) << "case " << c;
        EXPECT_EQ(back.first, cpu.first) << "case " << c;
        EXPECT_EQ(back.indices, cpu.indices) << "case " << c;
        EXPECT_EQ(back.shadow, cpu.shadow) << "case " << c;
        (shadow ? result.drawnShadow : result.drawnCamera) += cpu.instances();
        for (const uint32_t entry : cpu.indices) result.crossing += (entry & gl::kFadeIncoming) != 0;
        for (size_t slot = 0; slot < cpu.count.size(); ++slot) {
            const size_t batch = slot / gl::kMaxLodLevels, level = slot % gl::kMaxLodLevels;
            result.coarser += level > 0 ? cpu.count[slot] : 0;
            const size_t levels =
                shadow ? lods[scene.batches[batch].mesh].shadow.size() : lods[scene.batches[batch].mesh].camera.size();
            if (levels > 1 && level + 1 == levels) result.coarsest[batch] += cpu.count[slot];
        }
        // What the commands say was drawn is the list's length at each level.
        const gl::DrawStats drawn = culling->submitted(gpu);
        EXPECT_EQ(drawn.instances, cpu.instances()) << "case " << c;
    }
    return result;
}

} // namespace

TEST_F(GpuCullingTest, ListsEqualTheCpuPathsForRandomVolumesAndLevelsOfDetail) {
    const ComparedLists drawn = compareWithTheCpuPath(
        gl::testing::smallForest(700, 300, 16), [](std::mt19937&) { return 1.0; }, [](std::mt19937&) { return 0.0; });
    // The cases are not vacuous: both kinds of pass keep instances, and levels are chosen.
    EXPECT_GT(drawn.drawnCamera, 500u);
    EXPECT_GT(drawn.drawnShadow, 500u);
    EXPECT_GT(drawn.coarser, 100u);
}

// Leafy trees, whose levels keep coverage (card levels, billboard clouds) and are taken further
// out by LodChoice::coverageScale: the GPU's rule reads the levels' flags as the CPU's does.
TEST_F(GpuCullingTest, ListsEqualTheCpuPathsWithLevelsThatKeepCoverage) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    const ComparedLists drawn = compareWithTheCpuPath(
        forest, [](std::mt19937& random) { return std::uniform_real_distribution<double>(1.0, 16.0)(random); },
        [](std::mt19937&) { return 0.0; });
    EXPECT_GT(drawn.drawnCamera + drawn.drawnShadow, 500u);
    EXPECT_EQ(drawn.crossing, 0u);
    // Every leafy batch reaches its coarsest billboard cloud somewhere, the fifth level: its
    // counters are the second word of gpu_cull.comp's scan.
    for (size_t b = 0; b < forest.batches.size(); ++b) {
        const scene::Mesh& mesh = forest.meshes[forest.batches[b].mesh];
        if (mesh.material >= 0) {
            EXPECT_EQ(scene::buildLods(mesh).shadow.size(), gl::kMaxLodLevels) << mesh.name;
            EXPECT_GT(drawn.coarsest[b], 0u) << mesh.name;
        }
    }
}

// With crossings between levels (RenderSettings::lodFade): the GPU marks the same instances as
// crossing, with the same shares, and puts each crossing instance's second entry in the next
// level's list where the CPU does.
TEST_F(GpuCullingTest, ListsEqualTheCpuPathsWhileInstancesCrossLevels) {
    const ComparedLists drawn = compareWithTheCpuPath(
        gl::testing::smallLeafyForest(),
        [](std::mt19937& random) { return std::uniform_real_distribution<double>(1.0, 16.0)(random); },
        [](std::mt19937& random) { return std::uniform_real_distribution<double>(0.05, 0.9)(random); });
    EXPECT_GT(drawn.crossing, 100u);
}

// Many shadow passes culled in one set of dispatches (a frame's virtual pages): each pass's list
// equals the CPU's for its own volume and projection, with crossings between levels, and a
// batch of passes placed after others leaves those others' lists as they were. Through these
// orthographic maps an instance's level follows its scale alone: the ranges of the levels none
// can take are emptied (not drawn), never one the pass fills.
TEST_F(GpuCullingTest, PassesCulledTogetherEqualTheCpuPathsEachWithItsOwnVolumeAndLevels) {
    const scene::Scene forest = gl::testing::smallLeafyForest();
    std::vector<scene::MeshLods> lods;
    for (const scene::Mesh& mesh : forest.meshes) lods.push_back(scene::buildLods(mesh));
    const gl::GpuScene gpuScene(forest, lods);
    gl::Visibility visibility(forest, lods);
    const auto culling = gl::GpuCulling::create(forest, lods, gpuScene);
    ASSERT_TRUE(culling->buildPrograms());
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), between(0.0, 1.0);
    // Orthographic maps of random sizes, places and sun directions, as virtual pages are.
    constexpr size_t kFirst = 3, kPasses = 24;
    std::vector<gl::GpuCulling::PassVolume> passes;
    for (size_t i = 0; i < kPasses; ++i) {
        const core::Vec3 wsTowardsSun = glm::normalize(core::Vec3(unit(random), 0.4 + between(random), unit(random)));
        const core::Vec3 wsCentre(120.0 * unit(random), 0.0, 120.0 * unit(random));
        const double half = 5.0 + 60.0 * between(random);
        const core::Mat4 lightFromWorld =
            glm::lookAt(wsCentre + 200.0 * wsTowardsSun, wsCentre,
                        std::abs(wsTowardsSun.y) > 0.99 ? core::Vec3(1, 0, 0) : core::Vec3(0, 1, 0));
        const core::Mat4 clipFromWorld = glm::orthoRH_ZO(-half, half, -half, half, 1.0, 400.0) * lightFromWorld;
        passes.push_back(
            {visibility::clipVolume(clipFromWorld, false), {clipFromWorld, 64.0 + 64.0 * double(i % 3), 0.5}});
    }
    const gl::LodChoice shared{{}, std::nullopt, true, 4.0, 0.4};
    // Two other passes first, then the batch after them: neither disturbs the other.
    culling->beginFrame(kFirst + kPasses);
    gl::PassList before;
    const std::vector<visibility::HalfSpace> everything =
        visibility::clipVolume(glm::orthoRH_ZO(-200.0, 200.0, -200.0, 200.0, 1.0, 600.0) *
                                   glm::lookAt(core::Vec3(0, 300, 0), core::Vec3(0), core::Vec3(0, 0, -1)),
                               false);
    culling->cull(0, everything, nullptr, gl::GpuCulling::Phase::All, before);
    std::vector<gl::PassList> gpu(kPasses);
    culling->cullPasses(kFirst, passes, &shared, false, gpu);
    size_t kept = 0, crossing = 0, rangesLeft = 0, rangesBefore = 0;
    for (size_t i = 0; i < kPasses; ++i) {
        gl::LodChoice lod = shared;
        lod.pass = passes[i].projection;
        gl::PassList cpu;
        visibility.collect(passes[i].volume, true, &lod, cpu);
        const gl::PassList back = culling->read(gpu[i]);
        EXPECT_EQ(back.count, cpu.count) << "pass " << i;
        EXPECT_EQ(back.indices, cpu.indices) << "pass " << i;
        kept += cpu.instances();
        // The ranges left to draw once those of levels no instance can take are emptied: every
        // range the pass fills among them, and fewer than all.
        gl::PassList drawn = gpu[i];
        visibility.emptyLevelsNoneTakes(drawn, &lod);
        for (size_t slot = 0; slot < cpu.count.size(); ++slot) {
            if (cpu.count[slot] > 0) {
                EXPECT_GT(drawn.count[slot], 0u) << "pass " << i << ", range " << slot;
            }
            rangesLeft += drawn.count[slot] > 0, rangesBefore += gpu[i].count[slot] > 0;
        }
        for (const uint32_t entry : cpu.indices) crossing += (entry & gl::kFadeIncoming) != 0;
    }
    gl::PassList all;
    visibility.collect(everything, true, nullptr, all);
    EXPECT_EQ(culling->read(before).indices, all.indices) << "the pass culled before the batch";
    EXPECT_GT(kept, 200u) << "the passes keep too little to compare";
    EXPECT_GT(crossing, 0u) << "no instance crossing levels";
    EXPECT_LT(4 * rangesLeft, 3 * rangesBefore) << "a quarter of the ranges or more are of levels none takes";
}

TEST_F(GpuCullingTest, TwoPhaseFramesEqualFrustumCulledFramesFromTheFirstAndAfterCuts) {
    // The first frame (nothing visible last frame: everything comes from the late phase), a
    // still frame (everything from the early phase), and a turn to a new view (a cut: what is
    // newly visible comes in the same frame) all equal frustum culling pixel for pixel, while
    // the forest hides some of what the frustum holds.
    const scene::Scene forest = gl::testing::smallForest(600, 200, 32);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    for (const char* name : {"perpendicular", "paper", "perpendicular", "into-sun"}) {
        scene::ResolvedView view = gl::testing::standardView(forest, name);
        view.camera.aspect = 160.0 / 90.0;
        const core::ShadowSetup setup = lispsmSetup(view, forest);
        gl::RenderSettings settings = smallFrame(160, 90, gl::Culling::Frustum);
        const auto frustum = (*renderer)->render(view.camera, view.light, setup, settings);
        ASSERT_TRUE(frustum);
        const scene::Image frustumImage = (*renderer)->readColor();
        const auto frustumBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, setup, settings);
        settings.culling = gl::Culling::Gpu;
        size_t afterCut = 0; // the main pass's instances in the frame after the cut
        for (int frame = 0; frame < 2; ++frame) {
            const auto gpu = (*renderer)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(gpu) << gpu.error();
            afterCut = gpu->main.instances;
            EXPECT_EQ(frustumImage.rgba, (*renderer)->readColor().rgba) << name << ", frame " << frame;
            EXPECT_LE(gpu->main.instances, frustum->main.instances) << name << ", frame " << frame;
            // The sun's maps keep what their volumes hold, as the CPU path does without masks.
            EXPECT_EQ(gpu->shadow.instances, frustum->shadow.instances) << name;
            EXPECT_EQ(gpu->shadow.triangles, frustum->shadow.triangles) << name;
        }
        const auto gpuBuffers = (*renderer)->renderEvalBuffers(view.camera, view.light, setup, settings);
        ASSERT_TRUE(frustumBuffers && gpuBuffers);
        EXPECT_EQ(frustumBuffers->surfaceId, gpuBuffers->surfaceId) << name;
        EXPECT_EQ(frustumBuffers->shadowTerm, gpuBuffers->shadowTerm) << name;
        if (std::string(name) == "perpendicular") {
            // Looking along the ground into the forest: trees hide trees.
            const auto gpu = (*renderer)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(gpu);
            EXPECT_LT(gpu->main.instances, frustum->main.instances) << name;
            // The frame after a cut already draws the still camera's set: what its early phase
            // drew but its pyramid hides has no pixel left for the main pass.
            EXPECT_EQ(gpu->main.instances, afterCut) << name;
            // Receiver masks on the GPU: fewer casters, the same pixels, and no more casters
            // than the CPU's masks keep (those test a coarser pyramid of the same marks).
            settings.receiverMask = true;
            const auto masked = (*renderer)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(masked);
            EXPECT_EQ(frustumImage.rgba, (*renderer)->readColor().rgba) << name << ", receiver masks";
            settings.culling = gl::Culling::Frustum;
            const auto cpuMasked = (*renderer)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(cpuMasked);
            EXPECT_LT(masked->shadow.instances, gpu->shadow.instances) << name;
            EXPECT_LE(masked->shadow.instances, cpuMasked->shadow.instances) << name;
            EXPECT_GT(masked->shadow.instances, 0u) << name;
        }
    }
}

TEST_F(GpuCullingTest, AnInstanceMovedOutFromBehindAWallIsDrawnInTheFrameItAppears) {
    // A cube hidden behind a wall is not visible last frame, so the early phase leaves it out;
    // moved into the open, the late phase finds it against this frame's pyramid: it appears
    // in that very frame, as with frustum culling, with no frame of lag.
    scene::Scene s;
    scene::Mesh ground, wall, cube;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {50, 0.05f, 50}, glm::vec3(0.8f));
    scene::addBox(wall, glm::translate(glm::mat4(1.0f), {0, 4, 0}), {6, 4, 0.5f}, glm::vec3(0.6f));
    scene::addBox(cube, glm::mat4(1.0f), {1, 1, 1}, glm::vec3(0.9f, 0.2f, 0.2f));
    for (scene::Mesh* m : {&ground, &wall, &cube}) m->computeBounds();
    s.meshes = {ground, wall, cube};
    const glm::mat4 hidden = glm::translate(glm::mat4(1.0f), {0, 1, -8});
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}, {2, {hidden}, true}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 3, 20};
    camera.wsDirection = {0, -0.05, -1};
    camera.aspect = 1.0;
    camera.zNear = 0.5;
    camera.zFar = 100.0;
    const core::DirectionalLight sun{glm::normalize(core::Vec3(0.3, -1.0, 0.2))};
    const auto setup = core::computeShadowSetup({.camera = camera,
                                                 .light = sun,
                                                 .wsSceneBounds = (*renderer)->wsSceneBounds(),
                                                 .technique = core::Technique::Focused,
                                                 .mapSize = 1024});
    ASSERT_TRUE(setup) << setup.error();
    auto frame = [&](gl::Culling culling) {
        const auto stats = (*renderer)->render(camera, sun, *setup, smallFrame(128, 128, culling));
        EXPECT_TRUE(stats) << stats.error();
        return std::pair(stats ? stats->main.instances : 0, (*renderer)->readColor().rgba);
    };
    // Frame 0 tests against an empty pyramid (nothing was visible before it): everything in
    // the frustum is drawn and counts as visible. Frame 1 draws that early, and its pyramid
    // hides the cube: the main pass leaves it out from that frame on, though the pre-pass drew
    // it (none of its pixels survived there), and so does frame 2's pre-pass.
    for (int f = 0; f < 4; ++f) {
        const auto [instances, image] = frame(gl::Culling::Gpu);
        EXPECT_EQ(instances, f < 1 ? 3u : 2u) << "frame " << f;
        EXPECT_EQ(image, frame(gl::Culling::Frustum).second) << "frame " << f;
    }
    s.batches[2].worldFromObject[0] = glm::translate(glm::mat4(1.0f), {9, 1, 0});
    ASSERT_TRUE((*renderer)->moveInstances(s, std::vector<uint32_t>{2}));
    const auto [instances, image] = frame(gl::Culling::Gpu);
    EXPECT_EQ(instances, 3u) << "the cube in the open is drawn";
    const auto [frustumInstances, frustumImage] = frame(gl::Culling::Frustum);
    EXPECT_EQ(frustumInstances, 3u);
    EXPECT_EQ(image, frustumImage);
}

TEST_F(GpuCullingTest, EmptyBatchesAndMeshesWithoutTrianglesDrawLikeTheCpuPath) {
    // Batches without instances and meshes without indices get no chunks and no draws; the
    // one instance beside them is culled and drawn as the CPU path does it.
    scene::Scene s;
    scene::Mesh ground, empty, cube;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {20, 0.05f, 20}, glm::vec3(0.8f));
    scene::addBox(cube, glm::mat4(1.0f), {1, 1, 1}, glm::vec3(0.9f));
    for (scene::Mesh* m : {&ground, &cube}) m->computeBounds();
    s.meshes = {ground, empty, cube};
    s.batches = {{1, {glm::mat4(1.0f)}, false}, // a mesh without triangles
                 {2, {}, false},                // a batch without instances
                 {0, {glm::mat4(1.0f)}, false},
                 {2, {glm::translate(glm::mat4(1.0f), {0, 1, 0})}, true}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 4, 12};
    camera.wsDirection = {0, -0.3, -1};
    camera.aspect = 1.0;
    const core::DirectionalLight sun{glm::normalize(core::Vec3(0.4, -1.0, 0.3))};
    const auto setup = core::computeShadowSetup({.camera = camera,
                                                 .light = sun,
                                                 .wsSceneBounds = (*renderer)->wsSceneBounds(),
                                                 .technique = core::Technique::Lispsm,
                                                 .mapSize = 512});
    ASSERT_TRUE(setup) << setup.error();
    const auto frustum = (*renderer)->render(camera, sun, *setup, smallFrame(96, 96, gl::Culling::Frustum));
    ASSERT_TRUE(frustum);
    const std::vector<uint8_t> expected = (*renderer)->readColor().rgba;
    for (int frame = 0; frame < 2; ++frame) {
        const auto gpu = (*renderer)->render(camera, sun, *setup, smallFrame(96, 96, gl::Culling::Gpu));
        ASSERT_TRUE(gpu) << gpu.error();
        EXPECT_EQ((*renderer)->readColor().rgba, expected) << "frame " << frame;
        EXPECT_EQ(gpu->main.instances, frustum->main.instances) << "frame " << frame;
        EXPECT_EQ(gpu->shadow.triangles, frustum->shadow.triangles) << "frame " << frame;
    }
}

TEST_F(GpuCullingTest, AGpuDrivenFrameUploadsNoListsAndDispatchesAsManyPassesWhateverTheForest) {
    // The GPU writes its lists itself: a steady frame uploads its uniforms and blocks alone, the
    // same bytes for 100 trees and for ten times as many, where the CPU path uploads each pass's
    // list, an index per instance drawn (counted as GL was asked, gl::trafficSoFar). Its compute
    // passes are as many for either forest — one dispatch a pass, never one a tree or a chunk —,
    // their work groups growing with the instances (a group a chunk of them).
    std::vector<int64_t> gpuBytes, cpuBytes, gpuDispatches, gpuGroups;
    std::vector<size_t> cpuDrawn;
    for (const int trees : {100, 1000}) {
        const scene::Scene forest = gl::testing::smallForest(trees, 200, 32);
        auto renderer = gl::Renderer::create(forest);
        ASSERT_TRUE(renderer) << renderer.error();
        scene::ResolvedView view = gl::testing::standardView(forest, "aerial");
        view.camera.aspect = 160.0 / 90.0;
        const core::ShadowSetup setup = lispsmSetup(view, forest);
        for (const gl::Culling culling : {gl::Culling::Gpu, gl::Culling::Frustum}) {
            const gl::RenderSettings settings = smallFrame(160, 90, culling);
            ASSERT_TRUE((*renderer)->render(view.camera, view.light, setup, settings)); // the first frame builds
            const gl::Traffic before = gl::trafficSoFar();
            const auto steady = (*renderer)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(steady) << steady.error();
            const gl::Traffic frame = gl::trafficSoFar() - before;
            (culling == gl::Culling::Gpu ? gpuBytes : cpuBytes).push_back(frame.bytesUploaded);
            if (culling == gl::Culling::Gpu)
                gpuDispatches.push_back(frame.dispatches), gpuGroups.push_back(frame.workGroups);
            if (culling == gl::Culling::Frustum) cpuDrawn.push_back(steady->main.instances + steady->shadow.instances);
        }
    }
    EXPECT_EQ(gpuBytes[0], gpuBytes[1]) << "the GPU path's uploads grew with the forest";
    EXPECT_GE(gpuDispatches[0], 3) << "culling, counting and writing the lists: a dispatch each at least";
    EXPECT_EQ(gpuDispatches[0], gpuDispatches[1]) << "the GPU path's dispatches grew with the forest";
    EXPECT_GT(gpuGroups[1], gpuGroups[0]) << "ten times the trees in as many work groups";
    ASSERT_GT(cpuDrawn[1], cpuDrawn[0] + 500);
    EXPECT_GE(cpuBytes[1] - cpuBytes[0], int64_t(sizeof(uint32_t) * (cpuDrawn[1] - cpuDrawn[0])))
        << "the CPU path's lists: an index per instance drawn";
}

TEST_F(GpuCullingTest, VirtualPagesCulledOnTheGpuDrawTheCpuPathsPixelsInThreeDispatchesWhateverTheirNumber) {
    // A virtual clipmap along a moving camera, drawn by a GPU-driven renderer and by a frustum-
    // culled one: every frame the same pixels, the same pages, and the same casters counted in
    // the shadow pass — instances and triangles, the terrain's by the clusters a page draws of it
    // (96² quads: a large mesh, whose clusters the CPU picks per page on both paths), not the
    // whole of it per page. The GPU-driven frame culls on the CPU the pages it has no room for —
    // the first frame's, all of them — and from then on every page's other casters on the GPU,
    // all pages in the same three dispatches: a frame drawing dozens of pages dispatches three
    // more compute passes than the same frame drawing none. Both paths draw pages together: a draw
    // a batch and level for as many pages as the GL has viewports. The leafy forest's pages draw
    // their leaves' opacity layers from the same lists.
    struct Case {
        const char* name;
        scene::Scene forest;
        bool opacity;
    };
    const Case cases[] = {{"forest", gl::testing::smallForest(300, 200, 96), false},
                          {"leafy forest, opacity layers", gl::testing::smallLeafyForest(), true}};
    for (const Case& c : cases) {
        auto gpu = gl::Renderer::create(c.forest);
        auto cpu = gl::Renderer::create(c.forest);
        ASSERT_TRUE(gpu && cpu);
        scene::ResolvedView view = gl::testing::standardView(c.forest, "perpendicular");
        view.camera.aspect = 160.0 / 90.0;
        int culledOnGpu = 0, mostPages = 0;
        size_t evalDrawn = 0;
        for (int frame = 0; frame < 4; ++frame) {
            core::PerspectiveCamera camera = view.camera;
            camera.wsEye += core::Vec3(6.0 * frame, 0.0, -4.0 * frame); // new pages in every frame
            core::ShadowSetupInputs in{.camera = camera, .light = view.light, .wsSceneBounds = c.forest.wsBounds()};
            in.technique = core::Technique::Virtual;
            in.virtualMaps.imageHeight = 90;
            in.virtualMaps.virtualTexels = 4096;
            const auto setup = core::computeShadowSetup(in);
            ASSERT_TRUE(setup) << setup.error();
            gl::RenderSettings settings = smallFrame(160, 90, gl::Culling::Gpu);
            settings.foliageOpacity = c.opacity;
            const gl::Traffic before = gl::trafficSoFar();
            const auto a = (*gpu)->render(camera, view.light, *setup, settings);
            const int64_t dispatches = (gl::trafficSoFar() - before).dispatches;
            settings.culling = gl::Culling::Frustum;
            const auto b = (*cpu)->render(camera, view.light, *setup, settings);
            ASSERT_TRUE(a && b) << (a ? b.error() : a.error());
            ASSERT_TRUE(a->virtualPages && b->virtualPages);
            const std::string at = std::string(c.name) + ", frame " + std::to_string(frame);
            EXPECT_EQ((*gpu)->readColor().rgba, (*cpu)->readColor().rgba) << at;
            const int pages = b->virtualPages->pagesRendered;
            EXPECT_EQ(a->virtualPages->pagesRendered, pages) << at;
            EXPECT_EQ(a->shadow.instances, b->shadow.instances) << at;
            EXPECT_EQ(a->shadow.triangles, b->shadow.triangles) << at;
            EXPECT_EQ(b->virtualPages->pagesCulledOnGpu, 0) << at;
            if (frame == 0) {
                EXPECT_EQ(a->virtualPages->pagesCulledOnGpu, 0) << at << ": no room made yet";
                ASSERT_GT(pages, 8) << at << ": too few pages to compare";
                continue;
            }
            EXPECT_EQ(a->virtualPages->pagesCulledOnGpu, pages) << at << ": fewer pages than the first frame's room";
            culledOnGpu += a->virtualPages->pagesCulledOnGpu;
            if (!c.opacity && gl::vertexStagesReadDrawParameters()) {
                // Drawn together on both paths (VirtualPages::drawPages): for each group of as many
                // pages as the GL has viewports, a draw a batch and level — on the GPU path one for
                // every level a page may take, empty or not; from the CPU's lists only the levels
                // some page holds — the terrain's runs meeting each page among them. The terrain
                // lies under every page: drawn a page at a time it would take a draw a page. Here a
                // group takes nine draws at most (its batches' levels, the terrain's runs) for its
                // eight batches, so a frame of more pages than groups × (batches + 1) draws fewer
                // draws than pages (frame 3, 36 pages in three groups: 27 on the GPU path and 20 on
                // the CPU's; 60 and 152 with the CPU lists drawn a page at a time).
                GLint viewports = 0;
                glGetIntegerv(GL_MAX_VIEWPORTS, &viewports);
                const size_t groups = (size_t(pages) + size_t(viewports) - 1) / size_t(viewports);
                for (const size_t draws : {a->shadow.drawCalls, b->shadow.drawCalls}) {
                    EXPECT_LE(draws, groups * c.forest.batches.size() * gl::kMaxLodLevels)
                        << at << ": " << pages << " pages";
                    if (size_t(pages) > groups * (c.forest.batches.size() + 1)) {
                        EXPECT_LT(draws, size_t(pages)) << at << ": the pages' lists a group at a time";
                    }
                }
                EXPECT_LE(b->shadow.drawCalls, a->shadow.drawCalls) << at << ": the CPU lists' draws, levels held only";
            }
            // The same frame again draws no page: its dispatches are the frame's but the pages'.
            settings.culling = gl::Culling::Gpu;
            const gl::Traffic beforeStill = gl::trafficSoFar();
            const auto still = (*gpu)->render(camera, view.light, *setup, settings);
            ASSERT_TRUE(still && still->virtualPages);
            EXPECT_EQ(still->virtualPages->pagesRendered, 0) << at;
            // Three culling dispatches, and the page table's entries written in place (page_table.h).
            const int tableUpdates = a->virtualPages->tableBytes > 0 ? 1 : 0;
            if (pages > 0) {
                EXPECT_EQ(dispatches, (gl::trafficSoFar() - beforeStill).dispatches + 3 + tableUpdates)
                    << at << ": " << pages << " pages";
            }
            mostPages = std::max(mostPages, pages);
            settings.culling = gl::Culling::Frustum;
            ASSERT_TRUE((*cpu)->render(camera, view.light, *setup, settings));
            // An evaluation's frame, half a step on (new pages again), reads what its lists drew
            // back itself: one wait, not the figures' ring.
            camera.wsEye += core::Vec3(1.5, 0.0, -1.0);
            in.camera = camera;
            const auto evalSetup = core::computeShadowSetup(in);
            ASSERT_TRUE(evalSetup) << evalSetup.error();
            settings.culling = gl::Culling::Gpu;
            ASSERT_TRUE((*gpu)->renderEvalBuffers(camera, view.light, *evalSetup, settings));
            settings.culling = gl::Culling::Frustum;
            ASSERT_TRUE((*cpu)->renderEvalBuffers(camera, view.light, *evalSetup, settings));
            const gl::PassStats gpuEval = (*gpu)->lastShadowPass(), cpuEval = (*cpu)->lastShadowPass();
            evalDrawn += cpuEval.instances;
            EXPECT_EQ(gpuEval.instances, cpuEval.instances) << at << ", eval";
            EXPECT_EQ(gpuEval.triangles, cpuEval.triangles) << at << ", eval";
        }
        EXPECT_GT(culledOnGpu, 0) << c.name << ": no page culled on the GPU after the first frame";
        EXPECT_GE(mostPages, 8) << c.name << ": no frame drew pages enough to tell three dispatches from one a page";
        EXPECT_GT(evalDrawn, 0u) << c.name << ": the evaluations drew no page";
    }
}
