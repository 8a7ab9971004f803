// Flicker against truth between two frames of a ground plane with a shadow edge, at the same
// world points: zero for identical frames and for a camera that moves over a still edge; the
// whole band an edge jumps over when the map slides; a moving truth reported apart; points
// not seen before, hidden by a mover, or on a surface that changed its shape, not compared.
#include "shadowkit/eval/temporal.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit;

namespace {

core::PerspectiveCamera overGround(double x) {
    core::PerspectiveCamera cam;
    cam.wsEye = {x, 10.0, 20.0};
    cam.wsDirection = glm::normalize(core::Vec3(0.0, -10.0, -20.0));
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 200.0;
    return cam;
}

constexpr int kSize = 128;

// A frame of the ground y = 0: rendered shadow where x < renderedEdge, true shadow where
// x < truthEdge (world metres), and the same pixels under the previous frame's edges.
struct GroundFrame {
    eval::ShadowStates states;
    eval::PreviousShadowsHere before;
};

GroundFrame ground(const core::PerspectiveCamera& cam, double renderedEdge, double truthEdge, double renderedEdgeBefore,
                   double truthEdgeBefore) {
    eval::TruthBuffers truth;
    truth.width = truth.height = kSize;
    eval::Comparison comparison;
    GroundFrame f;
    core::RasterBuffers& raster = f.before.raster;
    raster.width = raster.height = kSize;
    const size_t n = size_t(kSize) * size_t(kSize);
    truth.surfaceId.assign(n, 0);
    truth.viewDepth.assign(n, 0.0f);
    truth.wsPosition.assign(n, core::Vec3(0.0));
    comparison.classes.assign(n, eval::PixelClass::NotEvaluated);
    raster.shadowTerm.assign(n, 1.0f);
    raster.surfaceId.assign(n, 0);
    raster.viewDepth.assign(n, 0.0f);
    f.before.truthLit.assign(n, 0);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const core::Vec3 d = eval::primaryRayDirection(cam, kSize, kSize, x, y); // t is the view depth
            if (!(d.y < 0.0)) continue;
            const double t = -cam.wsEye.y / d.y;
            const core::Vec3 p = cam.wsEye + t * d;
            const size_t i = size_t(y) * size_t(kSize) + size_t(x);
            truth.surfaceId[i] = raster.surfaceId[i] = 1;
            truth.viewDepth[i] = raster.viewDepth[i] = static_cast<float>(t);
            truth.wsPosition[i] = p;
            const bool renderedLit = p.x >= renderedEdge, truthLit = p.x >= truthEdge;
            comparison.classes[i] = renderedLit
                                        ? (truthLit ? eval::PixelClass::LitCorrect : eval::PixelClass::FalseLit)
                                        : (truthLit ? eval::PixelClass::FalseShadow : eval::PixelClass::ShadowCorrect);
            raster.shadowTerm[i] = p.x >= renderedEdgeBefore ? 1.0f : 0.0f;
            f.before.truthLit[i] = p.x >= truthEdgeBefore;
        }
    f.states = eval::shadowStates(cam, truth, comparison);
    return f;
}

int64_t pixelsBetween(const eval::ShadowStates& s, double from, double to) {
    int64_t n = 0;
    for (size_t i = 0; i < s.state.size(); ++i)
        if (s.state[i] && s.wsPosition[i].x >= from && s.wsPosition[i].x < to) ++n;
    return n;
}

} // namespace

TEST(Temporal, IdenticalFramesHaveNoFlicker) {
    const GroundFrame a = ground(overGround(0.0), 0.3, 0.0, 0.3, 0.0);
    const eval::TemporalFigures f = eval::compareFrames(a.states, a.states, a.before);
    EXPECT_GT(f.comparedPx, kSize * kSize / 3);
    EXPECT_EQ(f.flickerPct, 0.0);
    EXPECT_EQ(f.truthChangePct, 0.0);
}

TEST(Temporal, ACameraMovingOverAStillEdgeHasNoFlicker) {
    // The edge stays put in the world (0.3 m off the truth, as aliasing leaves it); the
    // camera slides 0.17 m sideways, a fraction of a pixel for most points.
    const GroundFrame a = ground(overGround(0.0), 0.3, 0.0, 0.3, 0.0);
    const GroundFrame b = ground(overGround(0.17), 0.3, 0.0, 0.3, 0.0);
    const eval::TemporalFigures f = eval::compareFrames(a.states, b.states, b.before);
    EXPECT_GT(f.comparedPx, kSize * kSize / 3);
    EXPECT_EQ(f.flickerPct, 0.0);
    EXPECT_EQ(f.truthChangePct, 0.0);
}

TEST(Temporal, AnEdgeThatJumpsFlickersOverExactlyTheBandItCrosses) {
    // The rendered edge jumps 1 m (a texel grid sliding) while the truth stays.
    const core::PerspectiveCamera cam = overGround(0.0);
    const GroundFrame a = ground(cam, 0.0, 0.0, 0.0, 0.0), b = ground(cam, 1.0, 0.0, 0.0, 0.0);
    const eval::TemporalFigures f = eval::compareFrames(a.states, b.states, b.before);
    const int64_t band = pixelsBetween(b.states, 0.0, 1.0);
    ASSERT_GT(band, 100);
    EXPECT_NEAR(f.flickerPct, 100.0 * double(band) / double(f.comparedPx), 1e-9);
    EXPECT_EQ(f.truthChangePct, 0.0);
}

TEST(Temporal, ATruthThatMovesIsReportedApartNotAsFlicker) {
    // The sun moved: truth and rendered edges both moved 1 m.
    const core::PerspectiveCamera cam = overGround(0.0);
    const GroundFrame a = ground(cam, 0.0, 0.0, 0.0, 0.0), b = ground(cam, 1.0, 1.0, 0.0, 0.0);
    const eval::TemporalFigures f = eval::compareFrames(a.states, b.states, b.before);
    EXPECT_EQ(f.flickerPct, 0.0);
    EXPECT_NEAR(f.truthChangePct, 100.0 * double(pixelsBetween(b.states, 0.0, 1.0)) / double(f.comparedPx), 1e-9);
}

TEST(Temporal, PointsNotSeenBeforeOrHiddenByAMoverAreNotCompared) {
    const core::PerspectiveCamera cam = overGround(0.0);
    GroundFrame a = ground(cam, 0.0, 0.0, 0.0, 0.0);
    GroundFrame b = ground(cam, 1.0, 0.0, 0.0, 0.0);
    // Another surface was in view there last frame (a caster in front).
    eval::ShadowStates hidden = a.states;
    std::fill(hidden.surfaceId.begin(), hidden.surfaceId.end(), 2u);
    EXPECT_EQ(eval::compareFrames(hidden, b.states, b.before).comparedPx, 0);
    // Drawn with the previous casters, a mover stood in front of this frame's points.
    std::fill(b.before.raster.surfaceId.begin(), b.before.raster.surfaceId.end(), 3u);
    EXPECT_EQ(eval::compareFrames(a.states, b.states, b.before).comparedPx, 0);
}

// A surface that changed its shape between the frames (a skin, morph weights) has no "same world
// point" the frame before: its pixels are left out, whatever their states say, and a still
// surface's are compared as before. The ground here is instance 0 (surface id 1).
TEST(Temporal, AReshapedSurfacesOwnPixelsAreNotCompared) {
    const core::PerspectiveCamera cam = overGround(0.0);
    const GroundFrame a = ground(cam, 0.0, 0.0, 0.0, 0.0), b = ground(cam, 1.0, 1.0, 0.0, 0.0);
    const eval::TemporalFigures still = eval::compareFrames(a.states, b.states, b.before);
    ASSERT_GT(still.comparedPx, kSize * kSize / 3);
    ASSERT_GT(still.truthChangePct, 0.0);
    const std::vector<uint32_t> ground{0}, another{1};
    const eval::TemporalFigures reshaped = eval::compareFrames(a.states, b.states, b.before, {}, ground);
    EXPECT_EQ(reshaped.comparedPx, 0);
    EXPECT_EQ(reshaped.truthChangePct, 0.0);
    const eval::TemporalFigures other = eval::compareFrames(a.states, b.states, b.before, {}, another);
    EXPECT_EQ(other.comparedPx, still.comparedPx);
    EXPECT_EQ(other.truthChangePct, still.truthChangePct);
}

namespace {

// A 4 × 1 drawing: instance 7 at 10 m on every pixel, lit but for the last.
core::RasterBuffers drawing() {
    core::RasterBuffers r;
    r.width = 4, r.height = 1;
    r.surfaceId.assign(4, 7);
    r.viewDepth.assign(4, 10.0f);
    r.shadowTerm = {1.0f, 1.0f, 1.0f, 0.0f};
    return r;
}

} // namespace

TEST(LevelPops, OneDrawingAgainstItselfPopsNowhere) {
    const eval::LevelPops pops = eval::levelPops(drawing(), drawing());
    EXPECT_EQ(pops.drawnPx, 4);
    EXPECT_EQ(pops.popPct, 0.0);
}

// Each kind once: a pixel the other drawing leaves empty, another instance, the same instance a
// leaf further (beyond the depth tolerance), and — the same surface — a shadow across the threshold.
TEST(LevelPops, CoverageSurfaceDepthAndShadowEachPopOnceAndAGrazingDepthDoesNot) {
    core::RasterBuffers before = drawing(), now = drawing();
    now.surfaceId[0] = 0, now.viewDepth[0] = 0.0f; // uncovered now
    now.surfaceId[1] = 8;                          // another instance
    now.viewDepth[2] = 10.5f;                      // 5 %: another leaf
    now.shadowTerm[3] = 0.9f;                      // lit now
    eval::LevelPops pops = eval::levelPops(now, before);
    EXPECT_EQ(pops.drawnPx, 4);
    EXPECT_DOUBLE_EQ(pops.surfacePct, 75.0);
    EXPECT_DOUBLE_EQ(pops.shadowPct, 25.0);
    EXPECT_DOUBLE_EQ(pops.popPct, 100.0);

    now = drawing();
    now.viewDepth[2] = 10.1f; // 1 %, within the 2 % tolerance: the same surface
    now.shadowTerm[0] = 0.6f; // still lit
    before.surfaceId[1] = 0;  // covered by one drawing alone
    before.viewDepth[1] = 0.0f;
    pops = eval::levelPops(now, before);
    EXPECT_DOUBLE_EQ(pops.surfacePct, 25.0);
    EXPECT_DOUBLE_EQ(pops.shadowPct, 0.0);
    // Nothing drawn in either: nothing to pop, not a division by zero.
    core::RasterBuffers empty = drawing();
    empty.surfaceId.assign(4, 0);
    EXPECT_EQ(eval::levelPops(empty, empty).drawnPx, 0);
    EXPECT_EQ(eval::levelPops(empty, empty).popPct, 0.0);
}
