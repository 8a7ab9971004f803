// The GPU's figures read late (gl/src/gpu_figures.h, Renderer::readGpuFiguresLate): a steady
// frame waits for nothing — every GPU-to-CPU read and query wait is counted — and the figures
// that come back frames later are the ones a frame that waits for its own reads. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/read_backs.h"
#include "shadowkit/gl/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

using namespace shadowkit;

namespace {

class GpuFiguresTest : public gl::testing::HeadlessGlTest {
protected:
    const scene::Scene forest = gl::testing::smallForest(300, 160, 16);

    // The view turned a little more each frame: no cache of the last frame serves it whole.
    scene::ResolvedView frameView(int frame) const {
        scene::ResolvedView view = gl::testing::standardView(forest, "perpendicular");
        view.camera.aspect = 96.0 / 54.0;
        const double turn = 0.02 * frame;
        const core::Vec3 d = view.camera.wsDirection;
        view.camera.wsDirection = {d.x * std::cos(turn) - d.z * std::sin(turn), d.y,
                                   d.x * std::sin(turn) + d.z * std::cos(turn)};
        return view;
    }
    core::ShadowSetup setupOf(const scene::ResolvedView& view, core::Technique technique) const {
        auto setup = core::computeShadowSetup({.camera = view.camera,
                                               .light = view.light,
                                               .wsSceneBounds = forest.wsBounds(),
                                               .technique = technique,
                                               .mapSize = 256});
        EXPECT_TRUE(setup) << setup.error();
        return setup ? *setup : core::ShadowSetup{};
    }
};

using gl::testing::smallFrame;

} // namespace

TEST_F(GpuFiguresTest, SteadyFramesWaitForNothingOnTheGpuPath) {
    // Every technique's frames culled on the GPU (the default on a GPU) and by the frustum: after
    // the first, a frame reads nothing back and waits on no query. The virtual maps read their
    // page requests late too (RenderSettings::virtualRequestsLate); waiting for them costs one
    // read-back a frame.
    for (const core::Technique technique :
         {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Csm, core::Technique::Psm,
          core::Technique::Focused, core::Technique::Standard, core::Technique::Virtual})
        for (const gl::Culling culling : {gl::Culling::Gpu, gl::Culling::Frustum}) {
            auto renderer = gl::Renderer::create(forest);
            ASSERT_TRUE(renderer) << renderer.error();
            (*renderer)->readGpuFiguresLate(true);
            const std::string name =
                std::string(core::techniqueName(technique)) + ", " + std::string(gl::cullingName(culling));
            for (const bool lateRequests : {true, false}) {
                gl::RenderSettings settings = smallFrame(96, 54, culling);
                settings.virtualRequestsLate = lateRequests;
                for (int frame = 0; frame < 5; ++frame) {
                    const scene::ResolvedView view = frameView(frame);
                    const int64_t before = gl::readBacksMade();
                    auto stats = (*renderer)->render(view.camera, view.light, setupOf(view, technique), settings);
                    ASSERT_TRUE(stats) << name << ": " << stats.error();
                    EXPECT_TRUE(stats->gpuFiguresLate);
                    if (frame == 0) continue; // the first frame builds what later ones reuse
                    const int64_t expected = technique == core::Technique::Virtual && !lateRequests ? 1 : 0;
                    EXPECT_EQ(gl::readBacksMade() - before, expected)
                        << name << ", frame " << frame << (lateRequests ? ", page requests late" : "");
                }
            }
            EXPECT_FALSE((*renderer)->finishGpuFigures().empty()) << name;
        }
}

TEST_F(GpuFiguresTest, LateFiguresAreWhatAFrameThatWaitsReads) {
    // The same frames drawn by two renderers, one waiting for each frame's figures and one
    // reading them late: every frame's figures come back once, in order, and its samples and
    // GPU-culled counts equal the waiting renderer's (times differ; they are times).
    for (const gl::Culling culling : {gl::Culling::Gpu, gl::Culling::Frustum}) {
        auto waiting = gl::Renderer::create(forest);
        auto late = gl::Renderer::create(forest);
        ASSERT_TRUE(waiting && late);
        (*late)->readGpuFiguresLate(true);
        std::map<int64_t, gl::FrameStats> waited;
        std::vector<gl::GpuFigures> arrived;
        const int frames = 6;
        for (int frame = 0; frame < frames; ++frame) {
            const scene::ResolvedView view = frameView(frame);
            const core::ShadowSetup setup = setupOf(view, core::Technique::Tsm);
            const gl::RenderSettings settings = smallFrame(96, 54, culling);
            auto now = (*waiting)->render(view.camera, view.light, setup, settings);
            auto later = (*late)->render(view.camera, view.light, setup, settings);
            ASSERT_TRUE(now && later);
            EXPECT_FALSE(now->gpuFiguresLate);
            EXPECT_TRUE(now->gpuFigures.empty());
            waited[later->frame] = *now;
            for (const gl::GpuFigures& f : later->gpuFigures) {
                EXPECT_LT(f.frame, later->frame) << "figures come from earlier frames";
                arrived.push_back(f);
            }
        }
        for (const gl::GpuFigures& f : (*late)->finishGpuFigures()) arrived.push_back(f);
        EXPECT_TRUE((*late)->finishGpuFigures().empty()) << "each frame's figures come back once";
        ASSERT_EQ(arrived.size(), size_t(frames)) << gl::cullingName(culling);
        for (size_t i = 0; i < arrived.size(); ++i) {
            const gl::GpuFigures& f = arrived[i];
            EXPECT_EQ(f.frame, waited.begin()->first + int64_t(i)) << "in frame order";
            const gl::FrameStats& w = waited.at(f.frame);
            EXPECT_GT(f.samplesPassed, 0u);
            EXPECT_EQ(f.samplesPassed, w.shadow.samplesPassed) << "frame " << f.frame;
            EXPECT_EQ(f.mapTexels, w.shadow.mapTexels);
            gl::FrameStats filled;
            f.fill(filled);
            if (culling == gl::Culling::Gpu) {
                ASSERT_TRUE(f.shadowInstances && f.mainInstances);
                EXPECT_GT(*f.mainInstances, 0u);
                EXPECT_EQ(filled.shadow.instances, w.shadow.instances) << "frame " << f.frame;
                EXPECT_EQ(filled.shadow.triangles, w.shadow.triangles) << "frame " << f.frame;
                EXPECT_EQ(filled.main.instances, w.main.instances) << "frame " << f.frame;
                EXPECT_EQ(filled.main.triangles, w.main.triangles) << "frame " << f.frame;
            } else {
                EXPECT_FALSE(f.shadowInstances) << "the CPU path's counts are the frame's own";
            }
            EXPECT_GT(f.shadowMilliseconds, 0.0);
            EXPECT_GT(f.mainMilliseconds, 0.0);
        }
    }
}

TEST_F(GpuFiguresTest, AFrameThatWaitsMakesOneSynchronisationForAllItsFigures) {
    // Times, samples and (GPU culling) what the lists drew: gathered on the GPU, read after one
    // wait — not one per query, as each pass's timer used to.
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer);
    for (int frame = 0; frame < 3; ++frame) {
        const scene::ResolvedView view = frameView(frame);
        const int64_t before = gl::readBacksMade();
        auto stats = (*renderer)->render(view.camera, view.light, setupOf(view, core::Technique::Tsm),
                                         smallFrame(96, 54, gl::Culling::Gpu));
        ASSERT_TRUE(stats);
        if (frame > 0) {
            EXPECT_EQ(gl::readBacksMade() - before, 1);
        }
        EXPECT_GT(stats->shadow.samplesPassed, 0u);
        EXPECT_GT(stats->main.instances, 0u);
    }
}
