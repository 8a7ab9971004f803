// A GPU-culled list's draws (gl/src/gpu_scene.h, GpuScene::draw): where vertex stages read each
// indirect command's base instance and the draw's index (program.h), a batch's levels that draw
// alike are one multi-draw, in every pass; without them, one draw a level. Either way the pixels,
// shadow terms and casters are the CPU path's. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "program.h"
#include "visibility.h"

#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_lod.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

using namespace shadowkit;

namespace {

class BatchedDrawsTest : public gl::testing::HeadlessGlTest {};

using gl::testing::smallFrame;

core::ShadowSetup lispsmMapFor(const scene::ResolvedView& view, const scene::Scene& scene) {
    auto setup = core::computeShadowSetup({.camera = view.camera,
                                           .light = view.light,
                                           .wsSceneBounds = scene.wsBounds(),
                                           .technique = core::Technique::Lispsm,
                                           .mapSize = 512});
    EXPECT_TRUE(setup) << setup.error();
    return setup ? *setup : core::ShadowSetup{};
}

TEST_F(BatchedDrawsTest, ABatchsLevelsAreOneDrawWhereVertexStagesReadTheBaseInstanceAndTheFallbackDrawsTheSame) {
    // A GPU-culled list's commands lie a batch's levels one after the other, each carrying where
    // its entries start: where vertex stages read that base instance and the draw's index
    // (program.h) one multi-draw takes a batch's levels that draw alike, the camera passes' each
    // with its own level's lookup offset; else each level is a draw (a driver without
    // GL_ARB_shader_draw_parameters). Both draw the CPU path's pixels, shadow terms and casters.
    // The simple forest's levels all draw alike: one draw a batch. The leafy forest's billboard
    // clouds bind textures of their own, so its leaves' levels split there.
    if (!gl::vertexStagesReadDrawParameters()) GTEST_SKIP() << "this GL has no GL_ARB_shader_draw_parameters";
    struct Case {
        const char* name;
        scene::Scene forest;
        bool levelsAlike;
    } cases[] = {{"simple forest", gl::testing::smallForest(600, 200, 32), true},
                 {"leafy forest", gl::testing::smallLeafyForest(), false}};
    for (const Case& c : cases) {
        // One draw a batch and level: the fallback's count, from the levels the renderer builds.
        size_t batches = 0, shadowLevels = 0, cameraLevels = 0;
        for (const scene::MeshBatch& batch : c.forest.batches) {
            const scene::Mesh& mesh = c.forest.meshes[batch.mesh];
            if (batch.worldFromObject.empty() || mesh.indices.empty()) continue;
            ++batches;
            const scene::MeshLods lods = scene::buildLods(mesh, gl::lodOptionsOf(c.forest, mesh));
            shadowLevels += lods.shadow.size(), cameraLevels += lods.camera.size();
        }
        ASSERT_GT(shadowLevels, batches) << c.name << ": no batch with levels to draw together";
        ASSERT_GT(cameraLevels, batches) << c.name;
        scene::ResolvedView view = gl::testing::standardView(c.forest, "aerial");
        view.camera.aspect = 160.0 / 90.0;
        const core::ShadowSetup setup = lispsmMapFor(view, c.forest);
        std::vector<uint8_t> expected;
        std::optional<core::RasterBuffers> expectedBuffers;
        gl::FrameStats cpu;
        for (const bool withBaseInstance : {true, false}) {
            std::optional<gl::WithoutDrawParameters> without;
            if (!withBaseInstance) without.emplace(); // programs built and the scene made without it
            auto renderer = gl::Renderer::create(c.forest);
            ASSERT_TRUE(renderer) << renderer.error();
            gl::RenderSettings settings = smallFrame(160, 90, gl::Culling::Frustum);
            if (expected.empty()) {
                const auto frustum = (*renderer)->render(view.camera, view.light, setup, settings);
                ASSERT_TRUE(frustum) << frustum.error();
                expected = (*renderer)->readColor().rgba;
                cpu = *frustum;
                auto buffers = (*renderer)->renderEvalBuffers(view.camera, view.light, setup, settings);
                ASSERT_TRUE(buffers) << buffers.error();
                expectedBuffers = std::move(buffers).value();
            }
            settings.culling = gl::Culling::Gpu;
            for (int frame = 0; frame < 2; ++frame) {
                const auto gpu = (*renderer)->render(view.camera, view.light, setup, settings);
                ASSERT_TRUE(gpu) << gpu.error();
                const std::string what = std::string(c.name) + (withBaseInstance ? "" : ", one draw a level") +
                                         ", frame " + std::to_string(frame);
                EXPECT_TRUE((*renderer)->readColor().rgba == expected) << what << ": pixels differ";
                EXPECT_EQ(gpu->shadow.instances, cpu.shadow.instances) << what;
                EXPECT_EQ(gpu->shadow.triangles, cpu.shadow.triangles) << what;
                for (const auto& [pass, drawn, levels] : {std::tuple{"shadow", gpu->shadow.drawCalls, shadowLevels},
                                                          std::tuple{"camera", gpu->main.drawCalls, cameraLevels}}) {
                    if (!withBaseInstance)
                        EXPECT_EQ(drawn, levels) << what << ", " << pass;
                    else if (c.levelsAlike)
                        EXPECT_EQ(drawn, batches) << what << ", " << pass;
                    else {
                        EXPECT_GE(drawn, batches) << what << ", " << pass;
                        EXPECT_LT(drawn, levels) << what << ", " << pass;
                    }
                }
            }
            // Each simplified receiver's lookup moved by its own level's error, read per draw.
            const auto buffers = (*renderer)->renderEvalBuffers(view.camera, view.light, setup, settings);
            ASSERT_TRUE(buffers) << buffers.error();
            EXPECT_TRUE(buffers->surfaceId == expectedBuffers->surfaceId) << c.name;
            EXPECT_TRUE(buffers->shadowTerm == expectedBuffers->shadowTerm) << c.name << ": shadow terms differ";
        }
    }
}

TEST_F(BatchedDrawsTest, VirtualPagesDrawnTogetherCastWhatPagesDrawnOneAtATimeCast) {
    // Where vertex stages read the draw parameters and pick their viewport, a frame's virtual
    // pages are drawn up to GL_MAX_VIEWPORTS at a time, each draw's page from its index or a table
    // (VirtualPages::drawPages), on the CPU path as on the GPU-driven one; without, a page at a
    // time by the plain depth programs, each page's matrix in its uniform block. Along a moving
    // camera, on both paths, the two draw the same shadows and casters — the first frame capped
    // at a group of pages and one more, which is drawn alone. The ground is a large
    // mesh (96² quads), drawn by its clusters meeting each page. The two programs compute a page's
    // matrix product apart and may round a sample apart (a pixel here and there, measured when
    // written: none); a page's casters drawn into another page's slot would move shadows over
    // thousands of pixels.
    if (!gl::vertexStagesReadDrawParameters()) GTEST_SKIP() << "this GL has no GL_ARB_shader_draw_parameters";
    const scene::Scene forest = gl::testing::smallForest(300, 200, 96);
    scene::ResolvedView view = gl::testing::standardView(forest, "perpendicular");
    view.camera.aspect = 160.0 / 90.0;
    for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu}) {
        auto together = gl::Renderer::create(forest);
        std::optional<gl::WithoutDrawParameters> without(std::in_place); // programs built without them
        auto alone = gl::Renderer::create(forest);
        without.reset();
        ASSERT_TRUE(together && alone);
        for (int frame = 0; frame < 3; ++frame) {
            core::PerspectiveCamera camera = view.camera;
            camera.wsEye += core::Vec3(6.0 * frame, 0.0, -4.0 * frame); // new pages in every frame
            core::ShadowSetupInputs in{.camera = camera, .light = view.light, .wsSceneBounds = forest.wsBounds()};
            in.technique = core::Technique::Virtual;
            in.virtualMaps.imageHeight = 90;
            in.virtualMaps.virtualTexels = 4096;
            const auto setup = core::computeShadowSetup(in);
            ASSERT_TRUE(setup) << setup.error();
            gl::RenderSettings settings = smallFrame(160, 90, culling);
            // The first frame capped at a group and one page: the last group one page alone.
            GLint viewports = 0;
            glGetIntegerv(GL_MAX_VIEWPORTS, &viewports);
            if (frame == 0) settings.virtualPageBudget = viewports + 1;
            const auto a = (*together)->render(camera, view.light, *setup, settings);
            const std::vector<uint8_t> pixels = (*together)->readColor().rgba;
            std::optional<gl::WithoutDrawParameters> guard(std::in_place); // draws as it was built
            const auto b = (*alone)->render(camera, view.light, *setup, settings);
            const std::vector<uint8_t> expected = (*alone)->readColor().rgba;
            guard.reset();
            ASSERT_TRUE(a && b) << (a ? b.error() : a.error());
            const std::string at =
                std::string(culling == gl::Culling::Gpu ? "gpu" : "frustum") + ", frame " + std::to_string(frame);
            ASSERT_GT(a->virtualPages->pagesRendered, 2) << at << ": too few pages to draw together";
            if (frame == 0) {
                ASSERT_EQ(a->virtualPages->pagesRendered, viewports + 1) << at << ": the budget's pages";
            }
            EXPECT_EQ(a->virtualPages->pagesRendered, b->virtualPages->pagesRendered) << at;
            EXPECT_EQ(a->shadow.instances, b->shadow.instances) << at;
            EXPECT_EQ(a->shadow.triangles, b->shadow.triangles) << at;
            EXPECT_LT(a->shadow.drawCalls, b->shadow.drawCalls) << at << ": a page at a time";
            ASSERT_EQ(pixels.size(), expected.size());
            size_t differing = 0;
            for (size_t i = 0; i < pixels.size(); i += 4)
                differing += std::equal(pixels.begin() + std::ptrdiff_t(i), pixels.begin() + std::ptrdiff_t(i + 4),
                                        expected.begin() + std::ptrdiff_t(i))
                                 ? 0
                                 : 1;
            EXPECT_LE(differing, 4u) << at << ": pixels that differ of " << pixels.size() / 4;
        }
    }
}

} // namespace

namespace {

// The shadow maps (greys, layers side by side) and the frame of one render.
struct CascadeFrame {
    gl::FrameStats stats;
    std::vector<uint8_t> pixels, maps;
};

// The texels (of 4 bytes) in which two images differ.
size_t texelsApart(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t apart = 0;
    for (size_t i = 0; i + 4 <= std::min(a.size(), b.size()); i += 4)
        apart +=
            std::equal(a.begin() + std::ptrdiff_t(i), a.begin() + std::ptrdiff_t(i + 4), b.begin() + std::ptrdiff_t(i))
                ? 0
                : 1;
    return apart;
}

} // namespace

TEST_F(BatchedDrawsTest, CascadesDrawnTogetherCastWhatCascadesDrawnOneAtATimeCast) {
    // Where vertex stages read the draw parameters and pick their layer, a set-up's fixed maps
    // (four cascades here) are drawn together, each batch's level for all of them in one
    // multi-draw, each draw's map from its index (GPU-culled lists) or a table (the CPU's), into
    // a layered framebuffer (SunPass::drawMapsTogether); without, a map at a time, each
    // attached and cleared alone. On both culling paths, for uniform and warped splits, for
    // opaque casters and alpha-tested leaves (the material programs), the two write the same
    // maps and draw the same frame with the same instances. A cascade's casters drawn into
    // another's layer would move its depths over thousands of texels. The CPU lists draw the
    // ground (a large mesh, 96² quads) by its clusters meeting each cascade, where a map at a
    // time drew it whole in each: fewer triangles, the same texels.
    if (!gl::vertexStagesReadDrawParameters()) GTEST_SKIP() << "this GL has no GL_ARB_shader_draw_parameters";
    const scene::Scene blobs = gl::testing::smallForest(300, 200, 96);
    const scene::Scene leafy = gl::testing::smallLeafyForest();
    for (const scene::Scene* forest : {&blobs, &leafy})
        for (const core::CascadeWarp warp : {core::CascadeWarp::None, core::CascadeWarp::Lispsm})
            for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu}) {
                const std::string at = std::string(forest == &leafy ? "leafy" : "blobs") +
                                       (warp == core::CascadeWarp::None ? ", uniform" : ", lispsm") +
                                       (culling == gl::Culling::Gpu ? ", gpu" : ", frustum");
                scene::ResolvedView view = gl::testing::standardView(*forest, "perpendicular");
                view.camera.aspect = 160.0 / 90.0;
                core::ShadowSetupInputs in{.camera = view.camera,
                                           .light = view.light,
                                           .wsSceneBounds = forest->wsBounds(),
                                           .technique = core::Technique::Csm,
                                           .mapSize = 512};
                in.cascades.warp = warp;
                const auto setup = core::computeShadowSetup(in);
                ASSERT_TRUE(setup) << at << ": " << setup.error();
                ASSERT_EQ(setup->views.size(), 4u) << at;
                ASSERT_EQ(setup->depthLayout, core::DepthLayout::Hyperbolic) << at;
                const gl::RenderSettings settings = smallFrame(160, 90, culling);
                auto together = gl::Renderer::create(*forest);
                std::optional<gl::WithoutDrawParameters> without(std::in_place); // programs built without them
                auto alone = gl::Renderer::create(*forest);
                without.reset();
                ASSERT_TRUE(together && alone) << at;
                auto frameOf = [&](gl::Renderer& renderer) {
                    const auto stats = renderer.render(view.camera, view.light, *setup, settings);
                    EXPECT_TRUE(stats) << at << ": " << (stats ? "" : stats.error());
                    return CascadeFrame{stats ? *stats : gl::FrameStats{}, renderer.readColor().rgba,
                                        renderer.readShadowMap().rgba};
                };
                const CascadeFrame a = frameOf(**together);
                std::optional<gl::WithoutDrawParameters> guard(std::in_place); // draws as it was built
                const CascadeFrame b = frameOf(**alone);
                guard.reset();
                EXPECT_EQ(a.stats.shadow.instances, b.stats.shadow.instances) << at;
                EXPECT_LE(a.stats.shadow.triangles, b.stats.shadow.triangles) << at;
                EXPECT_LT(a.stats.shadow.drawCalls, b.stats.shadow.drawCalls) << at << ": a map at a time";
                ASSERT_EQ(a.maps.size(), b.maps.size()) << at;
                ASSERT_EQ(a.pixels.size(), b.pixels.size()) << at;
                // The two programs compute a map's matrix product apart and may round a sample
                // apart (measured when written: none).
                EXPECT_LE(texelsApart(a.maps, b.maps), 16u) << at << ": map texels apart of " << a.maps.size() / 4;
                EXPECT_LE(texelsApart(a.pixels, b.pixels), 4u) << at << ": pixels apart of " << a.pixels.size() / 4;
            }
}

TEST_F(BatchedDrawsTest, CpuListsDrawTheTerrainByTheClustersMeetingEachMapAndTheCamera) {
    // A large mesh — the ground, 96² quads, in triangle clusters — is drawn by the clusters
    // meeting each pass's volume wherever the CPU lists it: in each map (one map, or cascades
    // drawn together) and in the camera passes, on both paths — the GPU-driven path leaves the
    // clustered meshes to the CPU as pages do. Over views that see part of the ground: fewer
    // triangles than the levels drawn hold (which count the ground whole), the same shadow
    // instances and triangles on both paths, the same maps texel for texel and the same pixels
    // (a cluster left out lies wholly outside its pass's volume).
    if (!gl::vertexStagesReadDrawParameters()) GTEST_SKIP() << "this GL has no GL_ARB_shader_draw_parameters";
    const scene::Scene forest = gl::testing::smallForest(300, 200, 96);
    auto trianglesOf = [](const std::vector<gl::LevelWork>& levels) {
        size_t sum = 0;
        for (const gl::LevelWork& level : levels) sum += level.triangles;
        return sum;
    };
    for (const core::Technique technique : {core::Technique::Tsm, core::Technique::Csm}) {
        for (const char* name : {"paper", "perpendicular"}) {
            const std::string at = std::string(core::techniqueName(technique)) + ", " + name;
            scene::ResolvedView view = gl::testing::standardView(forest, name);
            view.camera.aspect = 160.0 / 90.0;
            const auto setup = core::computeShadowSetup({.camera = view.camera,
                                                         .light = view.light,
                                                         .wsSceneBounds = forest.wsBounds(),
                                                         .technique = technique,
                                                         .mapSize = 512});
            ASSERT_TRUE(setup) << at << ": " << setup.error();
            auto renderer = gl::Renderer::create(forest);
            ASSERT_TRUE(renderer) << renderer.error();
            const auto cpu =
                (*renderer)->render(view.camera, view.light, *setup, smallFrame(160, 90, gl::Culling::Frustum));
            ASSERT_TRUE(cpu) << at << ": " << cpu.error();
            const gl::WorkByLevel cpuWork = (*renderer)->workByLevel();
            EXPECT_LT(cpu->shadow.triangles, trianglesOf(cpuWork.sun)) << at << ": the ground drawn whole in the maps";
            EXPECT_LT(cpu->main.triangles, trianglesOf(cpuWork.camera))
                << at << ": the ground drawn whole by the camera";
            const std::vector<uint8_t> expected = (*renderer)->readColor().rgba;
            const std::vector<uint8_t> expectedMaps = (*renderer)->readShadowMap().rgba;
            const auto gpu =
                (*renderer)->render(view.camera, view.light, *setup, smallFrame(160, 90, gl::Culling::Gpu));
            ASSERT_TRUE(gpu) << at << ": " << gpu.error();
            const gl::WorkByLevel gpuWork = (*renderer)->workByLevel();
            EXPECT_EQ(cpu->shadow.instances, gpu->shadow.instances) << at;
            EXPECT_EQ(cpu->shadow.triangles, gpu->shadow.triangles) << at;
            EXPECT_LT(gpu->shadow.triangles, trianglesOf(gpuWork.sun)) << at << ": the GPU path's maps";
            // The GPU path's occlusion test (its pyramid holds the ground) may leave out more.
            EXPECT_LE(gpu->main.instances, cpu->main.instances) << at;
            EXPECT_LT(gpu->main.triangles, trianglesOf(gpuWork.camera)) << at << ": the GPU path's camera pass";
            // The maps hold the same ground, texel for texel: the frame alone would not see a
            // part of it missing where nothing else shades the ground (a mutation that left every
            // cluster out passed the pixels and failed here).
            EXPECT_EQ(texelsApart((*renderer)->readShadowMap().rgba, expectedMaps), 0u) << at << ": map texels";
            // The two paths' draws may round a sample apart: one pixel on `paper` for TSM whether
            // the CPU path drew the ground by clusters or whole (measured when written).
            EXPECT_LE(texelsApart((*renderer)->readColor().rgba, expected), 2u) << at;
            // Culling off draws every cluster: each pass's triangles are its levels' whole.
            const auto off =
                (*renderer)->render(view.camera, view.light, *setup, smallFrame(160, 90, gl::Culling::Off));
            ASSERT_TRUE(off) << at << ": " << off.error();
            const gl::WorkByLevel work = (*renderer)->workByLevel();
            EXPECT_EQ(off->shadow.triangles, trianglesOf(work.sun)) << at << ": culling off";
            EXPECT_EQ(off->main.triangles, trianglesOf(work.camera)) << at << ": culling off";
        }
    }
}
