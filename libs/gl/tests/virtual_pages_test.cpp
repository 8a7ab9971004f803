// Virtual shadow maps on the GPU (CTest label `gl`): a frame drawn from cached pages looks up
// exactly what a frame with every page fresh looks up; a mover redraws only the pages under it
// and its shadow moves; a pool too small for the view falls back to coarser levels, says so,
// and still shadows where the caster is; a page budget caps the pages drawn a frame, shows the
// old sun's pages while a new sun's are drawn, and converges on what fresh pages give; requests
// read late wait only when nothing that applies is on its way, and converge on what waiting
// frames show; a still frame uploads no page table and a moved one only the entries that changed;
// a large mesh drawn by the clusters meeting each page casts what it casts drawn whole.
#include "headless_gl_test.h"

#include "gpu_scene.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/read_backs.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class VirtualPagesTest : public gl::testing::HeadlessGlTest {};

// A plane, a floating box that may move (dynamic batch) and a post, under a low sun.
scene::Scene boxesOverPlane() {
    scene::Scene s;
    scene::Mesh ground, box;
    ground.name = "ground";
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {30, 0.05f, 30}, glm::vec3(0.8f));
    box.name = "box";
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1}, glm::vec3(0.8f));
    ground.computeBounds();
    box.computeBounds();
    s.meshes = {ground, box};
    s.batches = {{0, {glm::mat4(1.0f)}, false},
                 {1, {glm::translate(glm::mat4(1.0f), {-4, 1.0f, -6})}, false},
                 {1, {glm::translate(glm::mat4(1.0f), {0, 2.5f, 0})}, true}};
    return s;
}

core::PerspectiveCamera camera(double x) {
    core::PerspectiveCamera cam;
    cam.wsEye = {x, 6, 14};
    cam.wsDirection = core::Vec3(0, 0, 0) - core::Vec3(0, 6, 14);
    cam.fovYDegrees = 50;
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 80;
    return cam;
}

const core::DirectionalLight kSun{glm::normalize(core::Vec3(0.3, -1.0, 0.2))};

core::ShadowSetup virtualSetup(const scene::Scene& s, const core::PerspectiveCamera& cam, int imageHeight,
                               const core::DirectionalLight& sun = kSun) {
    core::ShadowSetupInputs in{.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds()};
    in.technique = core::Technique::Virtual;
    in.virtualMaps.imageHeight = imageHeight;
    in.virtualMaps.virtualTexels = 4096; // 32 × 32 pages: small windows, many pages at 128 px
    return core::computeShadowSetup(in).value();
}

gl::RenderSettings smallFrame() {
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.fogDensity = 0.0f;
    return settings;
}

// The shadow term where the camera sees world point `ws`.
float shadowAt(const core::RasterBuffers& b, const core::PerspectiveCamera& cam, const core::Vec3& ws) {
    const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(ws, 1.0);
    const int x = static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * b.width);
    const int y = static_cast<int>((0.5 - cs.y / cs.w * 0.5) * b.height); // top row first
    return b.shadowTerm[size_t(y) * b.width + x];
}

// Where the sun's ray through `ws` meets the ground (y = 0).
core::Vec3 groundUnder(const core::Vec3& ws) { return ws + kSun.wsDirection * (ws.y / -kSun.wsDirection.y); }

} // namespace

TEST_F(VirtualPagesTest, FramesFromCachedPagesLookUpExactlyWhatFreshPagesGive) {
    const scene::Scene s = boxesOverPlane();
    auto cached = gl::Renderer::create(s);
    ASSERT_TRUE(cached) << cached.error();
    // Hardware PCF, and a Poisson disk across a blend band (two levels read near each boundary).
    for (const auto& [filter, band] :
         {std::pair{core::ShadowFilter::Pcf2, 0.0f}, {core::ShadowFilter::Poisson, 0.3f}}) {
        gl::RenderSettings settings = smallFrame();
        settings.filter.kind = filter;
        settings.virtualBlendBand = band;
        int reused = 0;
        for (int frame = 0; frame < 6; ++frame) {
            const core::PerspectiveCamera cam = camera(0.37 * frame); // the sun held, the camera moving
            const core::ShadowSetup setup = virtualSetup(s, cam, settings.height);
            auto fresh = gl::Renderer::create(s);
            ASSERT_TRUE(fresh);
            const auto stats = (*cached)->render(cam, kSun, setup, settings);
            ASSERT_TRUE(stats && stats->virtualPages) << (stats ? "no page stats" : stats.error());
            reused += stats->virtualPages->pagesRequested - stats->virtualPages->pagesRendered;
            const auto a = (*cached)->renderEvalBuffers(cam, kSun, setup, settings);
            const auto b = (*fresh)->renderEvalBuffers(cam, kSun, setup, settings);
            ASSERT_TRUE(a && b);
            ASSERT_EQ(a->shadowTerm.size(), b->shadowTerm.size());
            // Exactly equal, but for the hardware 2 × 2 filter's weights: GL leaves their precision
            // to the driver, and a kept page lies in another atlas slot than a fresh one, so its
            // texel coordinates round to other fixed-point fractions (one pixel in 16,384 on an
            // NVIDIA H100, by less than this; llvmpipe gives equal terms). A wrong page is off by
            // far more: a lit receiver reads shadow, or a shadowed one light.
            const float tolerance = filter == core::ShadowFilter::Pcf2 ? 1.0f / 64.0f : 0.0f;
            int differ = 0, shadowed = 0;
            for (size_t i = 0; i < a->shadowTerm.size(); ++i) {
                differ += std::abs(a->shadowTerm[i] - b->shadowTerm[i]) > tolerance;
                shadowed += b->shadowTerm[i] < 0.5f;
            }
            EXPECT_EQ(differ, 0) << "frame " << frame << ", filter " << int(filter);
            EXPECT_GT(shadowed, 100) << "frame " << frame; // the boxes' shadows are in view
        }
        EXPECT_GT(reused, 0) << "no page was kept across frames";
    }
}

TEST_F(VirtualPagesTest, AStillFrameUploadsNoPageTableAndAMovedOneOnlyTheEntriesThatChanged) {
    // The page table (pages² entries of 4 bytes a level) went up whole in every frame; now a still
    // frame uploads none of it, and a moved one the entries that changed (eight bytes each) —
    // fewer than a level's, the table being toroidal: a window that moves keeps its other pages'
    // entries where they were. Counted as GL was asked to upload (gl::trafficSoFar); the moved
    // frames still equal fresh ones (FramesFromCachedPagesLookUpExactlyWhatFreshPagesGive).
    const scene::Scene s = boxesOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    gl::RenderSettings settings = smallFrame();
    settings.filter.kind = core::ShadowFilter::Poisson; // exact terms in any atlas slot (see above)
    const auto uploaded = [&](double x) {
        const core::PerspectiveCamera cam = camera(x);
        const core::ShadowSetup setup = virtualSetup(s, cam, settings.height);
        const gl::Traffic before = gl::trafficSoFar();
        EXPECT_TRUE((*renderer)->render(cam, kSun, setup, settings));
        return (gl::trafficSoFar() - before).bytesUploaded;
    };
    const core::ShadowSetup setup = virtualSetup(s, camera(0.0), settings.height);
    const int64_t pages = setup.clipmap->pagesPerSide(), levels = int64_t(setup.views.size());
    const int64_t level = pages * pages * int64_t(sizeof(uint32_t)), table = level * levels;
    ASSERT_GT(levels, 2);
    EXPECT_GE(uploaded(0.0), table) << "the first frame's table";
    // Beside the table a frame uploads its lists and uniforms, a few KiB here.
    int64_t still = 0;
    for (int frame = 0; frame < 2; ++frame) {
        still = uploaded(0.0);
        EXPECT_LT(still, table) << "a still frame";
    }
    // A step of the camera shifts the finest levels' windows: the pages that came and went, in
    // place, less than one level's entries (as the table was addressed before, every level whose
    // window moved went up whole: a level or more).
    const int64_t moved = uploaded(3.0) - still;
    EXPECT_GT(moved, 0) << "the step changed no entry: the check is empty";
    EXPECT_LT(moved, level);
    // And each moved frame, its table written in place, looks up exactly what a fresh renderer's
    // whole table gives — the step above, then longer ones.
    for (const double x : {3.0, 6.0, -5.0, 2.0}) {
        const core::PerspectiveCamera cam = camera(x);
        const core::ShadowSetup movedSetup = virtualSetup(s, cam, settings.height);
        auto fresh = gl::Renderer::create(s);
        ASSERT_TRUE(fresh);
        const auto a = (*renderer)->renderEvalBuffers(cam, kSun, movedSetup, settings);
        const auto b = (*fresh)->renderEvalBuffers(cam, kSun, movedSetup, settings);
        ASSERT_TRUE(a && b);
        ASSERT_EQ(a->shadowTerm.size(), b->shadowTerm.size());
        // The same terms, from the same levels (a page missing from the table is served by a
        // coarser level, whose texel coordinates are half as large).
        int differ = 0, otherLevel = 0, shadowed = 0;
        for (size_t i = 0; i < a->shadowTerm.size(); ++i) {
            differ += a->shadowTerm[i] != b->shadowTerm[i];
            otherLevel += a->tsTexel[i] != b->tsTexel[i];
            shadowed += b->shadowTerm[i] < 0.5f;
        }
        EXPECT_EQ(differ, 0) << "camera at x = " << x;
        EXPECT_EQ(otherLevel, 0) << "camera at x = " << x;
        EXPECT_GT(shadowed, 100) << "camera at x = " << x << ": the boxes' shadows are in view";
    }
}

TEST_F(VirtualPagesTest, AMoverRedrawsOnlyThePagesUnderItAndItsShadowMoves) {
    scene::Scene s = boxesOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const gl::RenderSettings settings = smallFrame();
    const core::PerspectiveCamera cam = camera(0.0);
    const core::ShadowSetup setup = virtualSetup(s, cam, settings.height);
    ASSERT_TRUE((*renderer)->render(cam, kSun, setup, settings));
    const auto still = (*renderer)->render(cam, kSun, setup, settings);
    ASSERT_TRUE(still);
    EXPECT_EQ(still->virtualPages->pagesRendered, 0); // nothing moved: every page cached

    // The floating box (global instance 2) moves 3 m along x.
    s.batches[2].worldFromObject[0] = glm::translate(glm::mat4(1.0f), {3, 2.5f, 0});
    const uint32_t mover = 2;
    ASSERT_TRUE((*renderer)->moveInstances(s, {&mover, 1}));
    const auto moved = (*renderer)->render(cam, kSun, setup, settings);
    ASSERT_TRUE(moved);
    EXPECT_GT(moved->virtualPages->pagesRendered, 0);
    EXPECT_LT(moved->virtualPages->pagesRendered, moved->virtualPages->pagesRequested);

    const auto buffers = (*renderer)->renderEvalBuffers(cam, kSun, setup, settings);
    ASSERT_TRUE(buffers);
    EXPECT_LT(shadowAt(*buffers, cam, groundUnder({3, 2.5, 0})), 0.5f) << "no shadow under the box's new place";
    EXPECT_GT(shadowAt(*buffers, cam, groundUnder({0, 2.5, 0})), 0.5f) << "the old shadow stayed";
    // And the moved frame equals a fresh renderer's.
    auto fresh = gl::Renderer::create(s);
    ASSERT_TRUE(fresh);
    const auto reference = (*fresh)->renderEvalBuffers(cam, kSun, setup, settings);
    ASSERT_TRUE(reference);
    EXPECT_EQ(buffers->shadowTerm, reference->shadowTerm);
}

TEST_F(VirtualPagesTest, ATinyPoolFallsBackToCoarserLevelsSaysSoAndNeverShowsAnotherPagesDepth) {
    const scene::Scene s = boxesOverPlane();
    gl::RenderSettings settings = smallFrame();
    const core::PerspectiveCamera cam = camera(0.0);
    const core::ShadowSetup setup = virtualSetup(s, cam, settings.height);
    auto full = gl::Renderer::create(s);
    ASSERT_TRUE(full);
    const auto reference = (*full)->renderEvalBuffers(cam, kSun, setup, settings);
    ASSERT_TRUE(reference);
    for (const int pool : {6, 24}) {
        auto renderer = gl::Renderer::create(s);
        ASSERT_TRUE(renderer);
        settings.virtualPoolPages = pool;
        const auto stats = (*renderer)->render(cam, kSun, setup, settings);
        ASSERT_TRUE(stats);
        EXPECT_EQ(stats->virtualPages->poolPages, pool);
        EXPECT_GT(stats->virtualPages->pagesFellBack, 0);
        EXPECT_LE(stats->virtualPages->pagesResident, pool);
        // Coarser or absent pages blur or lose shadow; a wrong page would put shadow on ground
        // that every full frame has lit. At most a pixel row's worth of edge pixels differ so.
        const auto buffers = (*renderer)->renderEvalBuffers(cam, kSun, setup, settings);
        ASSERT_TRUE(buffers);
        int falseShadow = 0;
        for (size_t i = 0; i < buffers->shadowTerm.size(); ++i)
            falseShadow += buffers->shadowTerm[i] < 0.5f && reference->shadowTerm[i] > 0.99f;
        EXPECT_LT(falseShadow, settings.width) << "pool of " << pool;
        // Every receiver also asked for its page of the coarsest level, which is allocated
        // first: with room for those (24 here; 6 is fewer than the view's coarsest pages) the box
        // still shadows the ground under it, coarsely.
        if (pool >= 24) {
            EXPECT_LT(shadowAt(*buffers, cam, groundUnder({0, 2.5, 0})), 0.5f) << "pool of " << pool;
        }
        // The viewer's page-table picture: the pages served coarser in white, at most the pool's
        // pages in their levels' tints.
        const scene::Image table = (*renderer)->readVirtualPageTable();
        int white = 0, tinted = 0;
        for (size_t i = 0; i < table.rgba.size(); i += 4) {
            const uint8_t* p = &table.rgba[i];
            white += p[0] == 255 && p[1] == 255 && p[2] == 255;
            tinted += p[3] == 255 && std::max({p[0], p[1], p[2]}) > 60 && !(p[0] == 255 && p[1] == 255 && p[2] == 255);
        }
        EXPECT_GT(white, 0) << "pool of " << pool;
        EXPECT_GT(tinted, 0) << "pool of " << pool;
        EXPECT_LE(tinted, pool) << "pool of " << pool;
    }
    settings.virtualPoolPages = -1;
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    EXPECT_EQ((*renderer)->render(cam, kSun, setup, settings).errorInfo().field, "virtual.pool_pages");
    settings.virtualPoolPages = 0;
    settings.virtualBlendBand = 1.0f;
    EXPECT_EQ((*renderer)->render(cam, kSun, setup, settings).errorInfo().field, "virtual.blend_band");
}

TEST_F(VirtualPagesTest, APageBudgetCapsEachFrameKeepsTheOldSunsPagesShownAndConvergesOnFreshPages) {
    const scene::Scene s = boxesOverPlane();
    const core::PerspectiveCamera cam = camera(0.0);
    gl::RenderSettings settings = smallFrame();
    settings.virtualPageBudget = 3;
    const core::DirectionalLight sunA = kSun, sunB{glm::normalize(core::Vec3(0.38, -1.0, 0.12))};
    const auto setupFor = [&](const core::DirectionalLight& sun) {
        core::ShadowSetupInputs in{.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds()};
        in.technique = core::Technique::Virtual;
        in.virtualMaps.imageHeight = settings.height;
        // Small windows of small pages (32² of 32 texels): several levels hold this small scene.
        in.virtualMaps.virtualTexels = 1024;
        in.virtualMaps.pageTexels = 32;
        in.visibleDepth = core::Vec2(6.0, 45.0); // levels for the receivers in view, not the near plane
        return core::computeShadowSetup(in).value();
    };
    const auto freshTerm = [&](const core::DirectionalLight& sun) {
        auto fresh = gl::Renderer::create(s);
        gl::RenderSettings unlimited = settings;
        unlimited.virtualPageBudget = 0;
        return (*fresh)->renderEvalBuffers(cam, sun, setupFor(sun), unlimited).value().shadowTerm;
    };
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    // Frames until nothing is left to draw; none draws more than the budget.
    const auto settle = [&](const core::DirectionalLight& sun, int& frames, int& behindFrames) {
        for (frames = 1; frames < 200; ++frames) {
            const auto stats = (*renderer)->render(cam, sun, setupFor(sun), settings);
            EXPECT_TRUE(stats && stats->virtualPages);
            if (!stats || !stats->virtualPages) return;
            const gl::VirtualPageStats& v = *stats->virtualPages;
            EXPECT_LE(v.pagesRendered, settings.virtualPageBudget);
            behindFrames += v.levelsBehind > 0;
            if (v.pagesRendered == 0 && v.pagesDeferred == 0 && v.levelsBehind == 0) return;
        }
    };
    int frames = 0, behind = 0;
    settle(sunA, frames, behind);
    EXPECT_GT(frames, 2) << "the first frame's pages fit the budget: the test checks nothing";
    EXPECT_EQ(behind, 0);
    const auto termA = freshTerm(sunA);
    EXPECT_EQ((*renderer)->renderEvalBuffers(cam, sunA, setupFor(sunA), settings)->shadowTerm, termA);

    // The sun moves: until the back generation's finest level is drawn, every frame is still
    // looked up in sun A's pages, and only those (the lookup reads the shadow maps alone; the
    // light's direction only shades), while sun B's are drawn beside them.
    const int levels = static_cast<int>(setupFor(sunB).views.size());
    int allBehind = 0;
    for (int frame = 0; frame < 50; ++frame) {
        const auto term = (*renderer)->renderEvalBuffers(cam, sunB, setupFor(sunB), settings);
        ASSERT_TRUE(term);
        const auto stats = (*renderer)->lastVirtualPages();
        ASSERT_TRUE(stats);
        if (stats->levelsBehind < levels) break;
        EXPECT_EQ(term->shadowTerm, termA) << "frame " << frame << " after the sun moved";
        ++allBehind;
    }
    EXPECT_GE(allBehind, 2) << "the finest level was drawn at once: the test checks little";
    // Then sun B's pages replace them level by level within the budget, and the frame ends equal
    // to one drawn fresh for sun B.
    behind = 0;
    settle(sunB, frames, behind);
    EXPECT_GT(behind, 1);
    const auto termB = freshTerm(sunB);
    EXPECT_NE(termA, termB);
    EXPECT_EQ((*renderer)->renderEvalBuffers(cam, sunB, setupFor(sunB), settings)->shadowTerm, termB);

    // A budget that holds every page draws what no budget does, frame for frame, the sun moving.
    auto large = gl::Renderer::create(s), unlimited = gl::Renderer::create(s);
    ASSERT_TRUE(large && unlimited);
    gl::RenderSettings none = settings;
    none.virtualPageBudget = 0;
    settings.virtualPageBudget = 100000;
    for (const core::DirectionalLight& sun : {sunA, sunA, sunB, sunB, sunA}) {
        const auto a = (*large)->renderEvalBuffers(cam, sun, setupFor(sun), settings);
        const auto b = (*unlimited)->renderEvalBuffers(cam, sun, setupFor(sun), none);
        ASSERT_TRUE(a && b);
        EXPECT_EQ(a->shadowTerm, b->shadowTerm);
        EXPECT_EQ((*large)->lastVirtualPages()->lagFrames, 0);
        EXPECT_EQ((*large)->lastVirtualPages()->pagesRendered, (*unlimited)->lastVirtualPages()->pagesRendered);
    }

    settings.virtualPageBudget = -1;
    EXPECT_EQ((*renderer)->render(cam, sunB, setupFor(sunB), settings).errorInfo().field, "virtual.page_budget");
}

TEST_F(VirtualPagesTest, MovingThePageBordersChangesNoShadowForAnyFilter) {
    // The page grid shifted by 1/8 m along both light-space axes: a whole number of texels at
    // every level here (texels of 2^-9 .. 2^-5 m), so the texel lattices stay put, but every
    // page border moves. A lookup that read across a border without its guard band would now
    // differ along the old or the new borders.
    const scene::Scene s = boxesOverPlane();
    const core::PerspectiveCamera cam = camera(0.0);
    gl::RenderSettings settings = smallFrame();
    settings.width = settings.height = 192;
    core::ShadowSetupInputs in{.camera = cam, .light = kSun, .wsSceneBounds = s.wsBounds()};
    in.technique = core::Technique::Virtual;
    in.virtualMaps.imageHeight = settings.height;
    in.virtualMaps.virtualTexels = 4096;
    in.virtualMaps.firstLevel = -9;
    const core::ShadowSetup a = core::computeShadowSetup(in).value();
    ASSERT_LE(a.views.size(), 5u); // 1/8 m is a whole number of texels up to 2^-5 m
    const core::Mat4& r = a.clipmap->lightFromWorldRotation;
    const core::Vec3 lightX(r[0][0], r[1][0], r[2][0]), lightY(r[0][1], r[1][1], r[2][1]); // rows of R
    in.wsGridOrigin = 0.125 * (lightX + lightY);
    const core::ShadowSetup b = core::computeShadowSetup(in).value();
    ASSERT_EQ(a.views.size(), b.views.size());
    // PCSS too, under a 3° sun: its blocker search and filter read across borders as the wide
    // kernels do (its kernels here are a few texels: the boxes are low).
    settings.sunAngleDegrees = 3.0;
    for (const core::FilterSettings& filter : {core::FilterSettings{core::ShadowFilter::Hard, 1, 2.0f},
                                               {core::ShadowFilter::Pcf2, 1, 2.0f},
                                               {core::ShadowFilter::PcfGrid, 3, 2.0f},
                                               {core::ShadowFilter::Poisson, 16, 2.0f},
                                               core::parseFilter("pcss").value()}) {
        settings.filter = filter;
        const core::ShadowFilter kind = filter.kind;
        auto ra = gl::Renderer::create(s), rb = gl::Renderer::create(s);
        ASSERT_TRUE(ra && rb);
        const auto ba = (*ra)->renderEvalBuffers(cam, kSun, a, settings);
        const auto bb = (*rb)->renderEvalBuffers(cam, kSun, b, settings);
        ASSERT_TRUE(ba && bb);
        int differ = 0, shadowed = 0;
        for (size_t i = 0; i < ba->shadowTerm.size(); ++i) {
            differ += std::abs(ba->shadowTerm[i] - bb->shadowTerm[i]) > 0.02f;
            shadowed += ba->shadowTerm[i] < 0.5f;
        }
        EXPECT_GT(shadowed, 200);
        EXPECT_LE(differ, 2) << "filter " << int(kind) << ": " << differ << " pixels changed with the page borders";
    }
}

TEST_F(VirtualPagesTest, RequestsReadLateWaitOnlyWhenNothingAppliesAndConvergeOnWhatWaitingFramesShow) {
    // Two renderers draw the same frames: the camera walks 0.9 m a frame, then stands. One waits
    // for each frame's page requests; the other reads them late. The late one waits (a counted
    // read-back) only in the first frame and after the sun moves — never while the sun holds —,
    // and two frames after the camera stands it looks up what the waiting one does.
    const scene::Scene s = boxesOverPlane();
    auto waiting = gl::Renderer::create(s), late = gl::Renderer::create(s);
    ASSERT_TRUE(waiting && late);
    (*waiting)->readGpuFiguresLate(true);
    (*late)->readGpuFiguresLate(true); // so that nothing but the page requests could wait
    gl::RenderSettings settings = smallFrame();
    settings.culling = gl::Culling::Frustum;
    gl::RenderSettings lateSettings = settings;
    lateSettings.virtualRequestsLate = true;
    const core::DirectionalLight sunB{glm::normalize(core::Vec3(0.38, -1.0, 0.12))};
    constexpr int kWalk = 6, kStand = 3;
    int lateMarks = 0;
    for (const core::DirectionalLight& sun : {kSun, sunB}) {
        for (int frame = 0; frame < kWalk + kStand; ++frame) {
            const core::PerspectiveCamera cam = camera(0.9 * std::min(frame, kWalk));
            const core::ShadowSetup setup = virtualSetup(s, cam, settings.height, sun);
            ASSERT_TRUE((*waiting)->render(cam, sun, setup, settings));
            const int64_t before = gl::readBacksMade();
            const auto stats = (*late)->render(cam, sun, setup, lateSettings);
            ASSERT_TRUE(stats && stats->virtualPages) << (stats ? "no page stats" : stats.error());
            EXPECT_EQ(gl::readBacksMade() - before, frame == 0 ? 1 : 0)
                << "frame " << frame << (sun.wsDirection == kSun.wsDirection ? "" : " after the sun moved");
            lateMarks += stats->virtualPages->marksAge > 0;
        }
        const core::PerspectiveCamera cam = camera(0.9 * kWalk);
        const core::ShadowSetup setup = virtualSetup(s, cam, settings.height, sun);
        const auto a = (*late)->renderEvalBuffers(cam, sun, setup, lateSettings);
        const auto b = (*waiting)->renderEvalBuffers(cam, sun, setup, settings);
        ASSERT_TRUE(a && b);
        int shadowed = 0;
        for (const float t : b->shadowTerm) shadowed += t < 0.5f;
        EXPECT_GT(shadowed, 100); // the boxes' shadows are in view
        EXPECT_EQ(a->shadowTerm, b->shadowTerm);
    }
    EXPECT_GE(lateMarks, kWalk) << "the earlier frames' marks never arrived in time: the test checks little";
}

TEST_F(VirtualPagesTest, ALargeMeshDrawnByTheClustersMeetingEachPageCastsWhatItCastsDrawnWhole) {
    // A ground of 2 × 128² triangles (GpuScene::kClusterMinTriangles or more: a page draws the
    // clusters of it that meet the page, each instance's runs of them in one multi-draw) against
    // the same triangles as four meshes too small to cluster (each drawn whole where it meets a
    // page). Hills shade the ground, boxes stand on it; without levels of detail the two scenes
    // hold the same triangles at the same places, so every pixel and shadow term must agree,
    // while the clustered ground sends fewer triangles to the pages.
    constexpr int kQuads = 128;
    constexpr float kSide = 40.0f;
    auto heightAt = [](float x, float z) { return 3.0f * std::sin(0.35f * x) * std::cos(0.3f * z); };
    scene::Mesh whole;
    whole.name = "ground";
    for (int j = 0; j <= kQuads; ++j)
        for (int i = 0; i <= kQuads; ++i) {
            const float x = kSide * (float(i) / kQuads - 0.5f), z = kSide * (float(j) / kQuads - 0.5f);
            whole.vertices.push_back({{x, heightAt(x, z), z}, {0, 1, 0}, glm::vec3(0.7f)});
        }
    for (int j = 0; j < kQuads; ++j)
        for (int i = 0; i < kQuads; ++i) {
            const uint32_t a = uint32_t(j * (kQuads + 1) + i), b = a + 1, c = a + kQuads + 1, d = c + 1;
            whole.indices.insert(whole.indices.end(), {a, c, b, b, c, d});
        }
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), {0.8f, 1.5f, 0.8f}, glm::vec3(0.8f));
    box.computeBounds();
    const std::vector<glm::mat4> boxes = {glm::translate(glm::mat4(1.0f), {-5, 2.5f, -3}),
                                          glm::translate(glm::mat4(1.0f), {4, 2.5f, 2})};
    scene::Scene clustered;
    whole.computeBounds();
    clustered.meshes = {whole, box};
    clustered.batches = {{0, {glm::mat4(1.0f)}, false}, {1, boxes, false}};
    scene::Scene quarters;
    for (int q = 0; q < 4; ++q) {
        scene::Mesh part;
        part.name = "ground quarter";
        part.vertices = whole.vertices;
        for (size_t t = 0; t < whole.indices.size(); t += 3) {
            const glm::vec3& p = whole.vertices[whole.indices[t]].position;
            if ((p.x < 0.0f ? 0 : 1) + (p.z < 0.0f ? 0 : 2) == q)
                part.indices.insert(part.indices.end(), whole.indices.begin() + long(t),
                                    whole.indices.begin() + long(t) + 3);
        }
        ASSERT_LT(part.triangleCount(), gl::GpuScene::kClusterMinTriangles) << "a quarter would be clustered too";
        part.computeBounds();
        quarters.meshes.push_back(std::move(part));
        quarters.batches.push_back({uint32_t(q), {glm::mat4(1.0f)}, false});
    }
    ASSERT_GE(whole.triangleCount(), gl::GpuScene::kClusterMinTriangles);
    quarters.meshes.push_back(box);
    quarters.batches.push_back({4, boxes, false});

    const core::DirectionalLight lowSun{glm::normalize(core::Vec3(0.9, -0.25, 0.3))};
    // Each scene on the CPU path and GPU-driven, a second frame a step on drawing new pages: on the
    // GPU path all of them culled on the GPU and drawn together (VirtualPages::drawPages), the
    // clustered ground's runs page by page.
    struct Frame {
        std::vector<uint8_t> pixels;
        std::vector<float> shadow;
        size_t triangles = 0;
    } frames[2][2][2]; // [scene][gpu][the second or third frame]
    const scene::Scene* scenes[2] = {&clustered, &quarters};
    const char* names[2] = {"clustered", "quarters"};
    for (int k = 0; k < 2; ++k)
        for (const gl::Culling culling : {gl::Culling::Frustum, gl::Culling::Gpu}) {
            const bool gpu = culling == gl::Culling::Gpu;
            gl::RenderSettings settings = smallFrame();
            settings.lod = false;
            settings.culling = culling;
            auto renderer = gl::Renderer::create(*scenes[k]);
            ASSERT_TRUE(renderer) << renderer.error();
            // The sun (at most 10 pages: the GPU path makes room for 10 pages on the GPU), another
            // sun (all its pages anew: 10 culled on the GPU and drawn together, the rest on the CPU
            // one at a time), the sun again (the room grown to the last frame's pages).
            const core::PerspectiveCamera cam = camera(2.0);
            const core::DirectionalLight otherSun{glm::normalize(core::Vec3(0.7, -0.35, 0.5))};
            const core::DirectionalLight* suns[] = {&lowSun, &otherSun, &lowSun};
            for (int i = 0; i < 3; ++i) {
                const std::string what =
                    std::string(names[k]) + (gpu ? ", gpu" : ", cpu") + ", frame " + std::to_string(i);
                settings.virtualPageBudget = i == 0 ? 10 : 0;
                const core::ShadowSetup setup = virtualSetup(*scenes[k], cam, settings.height, *suns[i]);
                const auto frame = (*renderer)->render(cam, *suns[i], setup, settings);
                ASSERT_TRUE(frame) << what << ": " << frame.error();
                ASSERT_TRUE(frame->virtualPages && frame->virtualPages->pagesRendered > 1) << what;
                if (i == 0) continue;
                const int pages = frame->virtualPages->pagesRendered, onGpu = frame->virtualPages->pagesCulledOnGpu;
                if (gpu && i == 1) {
                    EXPECT_EQ(onGpu, 10) << what;
                    EXPECT_GT(pages, onGpu) << what << ": no page culled on the CPU beside them";
                }
                if (gpu && i == 2) {
                    EXPECT_GT(onGpu, 1) << what;
                }
                Frame& f = frames[k][gpu][i - 1];
                f.pixels = (*renderer)->readColor().rgba;
                f.triangles = frame->shadow.triangles;
                const auto buffers = (*renderer)->renderEvalBuffers(cam, *suns[i], setup, settings);
                ASSERT_TRUE(buffers) << buffers.error();
                f.shadow = buffers->shadowTerm;
            }
        }
    for (int k = 0; k < 2; ++k)
        for (int gpu = 0; gpu < 2; ++gpu)
            for (int i = 0; i < 2; ++i) {
                const std::string what =
                    std::string(names[k]) + (gpu ? ", gpu" : ", cpu") + ", frame " + std::to_string(i + 1);
                const Frame &f = frames[k][gpu][i], &expected = frames[1][0][i];
                EXPECT_TRUE(f.pixels == expected.pixels) << what << ": the frame differs";
                EXPECT_TRUE(f.shadow == expected.shadow) << what << ": the shadow terms differ";
                EXPECT_EQ(f.triangles, frames[k][0][i].triangles) << what;
            }
    const std::vector<float>& shadow = frames[1][0][1].shadow;
    EXPECT_GT(std::count(shadow.begin(), shadow.end(), 0.0f), 100) << "no shadow to compare";
    const size_t triangles[2] = {frames[0][0][1].triangles, frames[1][0][1].triangles};
    EXPECT_LT(triangles[0], triangles[1]) << "the pages drew the clustered ground whole";
}
