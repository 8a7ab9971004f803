// Set-up hysteresis: a held view samples the same world lattice as the refit it came from
// (a whole-texel shift), covers this frame's focus body of its view, and never costs more
// than the allowed texel growth on the central ray; it refits when the camera has moved on
// far enough, when the light moves, and is bit-identical while nothing needs to move.
#include "shadowkit/core/setup_hysteresis.h"

#include "shadowkit/core/focus_body.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace shadowkit::core;

namespace {

PerspectiveCamera groundCamera() {
    PerspectiveCamera c;
    c.wsEye = {0.0, 1.8, 0.0};
    c.wsDirection = {0.3, -0.05, -1.0};
    c.fovYDegrees = 60.0;
    c.aspect = 16.0 / 9.0;
    c.zNear = 0.5;
    c.zFar = 300.0;
    return c;
}

ShadowSetupInputs inputs(const PerspectiveCamera& c, Technique t) {
    ShadowSetupInputs in{.camera = c,
                         .light = DirectionalLight::fromSunAngles(35.0, 110.0).value(),
                         .wsSceneBounds = Aabb::fromMinMax(Vec3(-500, -10, -500), Vec3(500, 40, 500)),
                         .technique = t,
                         .mapSize = 1024};
    if (t == Technique::Csm) in.cascades.warp = CascadeWarp::Lispsm;
    return in;
}

// A walk: forward and a little sideways and up each step, turning slowly.
PerspectiveCamera step(const PerspectiveCamera& c, int k) {
    PerspectiveCamera out = c;
    out.wsEye += Vec3(0.05, 0.02, -0.25);
    const double turn = glm::radians(0.2 * std::sin(0.1 * k));
    const Vec3 d = glm::normalize(c.wsDirection);
    out.wsDirection =
        Vec3(d.x * std::cos(turn) - d.z * std::sin(turn), d.y, d.x * std::sin(turn) + d.z * std::cos(turn));
    return out;
}

Vec2 ndc(const ShadowView& v, const Vec3& p) {
    const Vec4 c = v.clipFromWorld * Vec4(p, 1.0);
    return Vec2(c) / c.w;
}

ConvexBody::Points bodyOf(const ShadowSetupInputs& in, const ShadowView& v) {
    PerspectiveCamera slice = in.camera;
    if (v.split) slice.zNear = v.split->x, slice.zFar = v.split->y;
    return computeFocusBody(slice, in.light, in.wsSceneBounds).vertices();
}

} // namespace

TEST(SetupHysteresis, HeldViewsAreWholeTexelShiftsOfTheirRefitAndCoverTheirBody) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-50.0, 50.0);
    const HysteresisOptions o{.margin = 0.05, .maxTexelGrowth = 1.3};
    for (const Technique t : {Technique::Lispsm, Technique::Tsm, Technique::Focused, Technique::Csm}) {
        SetupHysteresis hysteresis(o);
        PerspectiveCamera c = groundCamera();
        std::vector<ShadowView> refit; // per view: the matrices of its last refit
        int held = 0, refits = 0;
        for (int k = 0; k < 80; ++k, c = step(c, k)) {
            const ShadowSetupInputs in = inputs(c, t);
            auto setup = hysteresis.next(in);
            ASSERT_TRUE(setup) << setup.error();
            if (k == 0) {
                EXPECT_EQ(hysteresis.refittedViews(), int(setup->views.size()));
                refit.assign(setup->views.begin(), setup->views.end());
            }
            for (size_t i = 0; i < setup->views.size(); ++i) {
                const ShadowView& v = setup->views[i];
                // Coverage: every vertex of the view's focus body lies in the map, depth included.
                for (const Vec3& p : bodyOf(in, v)) {
                    const Vec4 cs = v.clipFromWorld * Vec4(p, 1.0);
                    ASSERT_GT(cs.w, 0.0);
                    ASSERT_LE(std::abs(cs.x / cs.w), 1.0 + 1e-9) << techniqueName(t) << " frame " << k << " view " << i;
                    ASSERT_LE(std::abs(cs.y / cs.w), 1.0 + 1e-9) << techniqueName(t) << " frame " << k << " view " << i;
                    ASSERT_GE(cs.z / cs.w, -1e-9);
                    ASSERT_LE(cs.z / cs.w, 1.0 + 1e-9);
                }
                // The same lattice: NDC differs from the refit's by one whole-texel vector everywhere.
                const Vec2 offset = ndc(v, c.wsEye + Vec3(0, 0, -20)) - ndc(refit[i], c.wsEye + Vec3(0, 0, -20));
                const double texel = 2.0 / in.mapSize;
                bool same = true;
                for (int s = 0; s < 20; ++s) {
                    const Vec3 p = c.wsEye + Vec3(u(rng), 0.5 * u(rng) * 0.2, -std::abs(u(rng)) - 5.0);
                    same = same && glm::length(ndc(v, p) - ndc(refit[i], p) - offset) < 1e-7;
                }
                const bool whole = std::abs(offset.x / texel - std::round(offset.x / texel)) < 1e-6 &&
                                   std::abs(offset.y / texel - std::round(offset.y / texel)) < 1e-6;
                if (same && whole) {
                    ++held;
                } else { // not the old lattice: must have been refitted this frame
                    ASSERT_TRUE(hysteresis.refitted()) << techniqueName(t) << " frame " << k << " view " << i;
                    refit[i] = v;
                    ++refits;
                }
            }
        }
        // The walk (20 m) is long enough to force a warp to refit and slow enough to hold most
        // frames; a focused map's texels are the same size everywhere, so it may hold throughout.
        if (t != Technique::Focused) {
            EXPECT_GT(refits, 0) << techniqueName(t);
        }
        EXPECT_GT(held, 3 * refits) << techniqueName(t);
        std::printf("%s: %d held, %d refitted views over 80 frames\n", std::string(techniqueName(t)).c_str(), held,
                    refits);
    }
}

TEST(SetupHysteresis, HeldTexelsNeverGrowBeyondTheBoundOnTheCentralRay) {
    // Without lookahead a refit is a fresh fit with the margin, so held texels stay within
    // maxTexelGrowth · (1 + margin) of a fresh fit's.
    const HysteresisOptions o{.margin = 0.05, .maxTexelGrowth = 1.25, .lookaheadFrames = 0.0};
    SetupHysteresis hysteresis(o);
    PerspectiveCamera c = groundCamera();
    double worstSeen = 0.0;
    for (int k = 0; k < 80; ++k, c = step(c, k)) {
        const ShadowSetupInputs in = inputs(c, Technique::Lispsm);
        auto setup = hysteresis.next(in);
        auto fresh = computeShadowSetup(in);
        ASSERT_TRUE(setup && fresh);
        for (const double depth : {0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0}) {
            const Vec3 p = c.wsEye + depth * glm::normalize(c.wsDirection);
            const double growth = texelFootprint(setup->views[0], in.mapSize, in.light.wsDirection, p) /
                                  texelFootprint(fresh->views[0], in.mapSize, in.light.wsDirection, p);
            worstSeen = std::max(worstSeen, growth);
            ASSERT_LE(growth, o.maxTexelGrowth * (1.0 + o.margin) + 1e-9) << "frame " << k << " depth " << depth;
        }
    }
    EXPECT_GT(worstSeen, 1.0 + o.margin); // the bound was approached, not trivially met
}

TEST(SetupHysteresis, BitIdenticalWhileStillAndRefitsWhenTheLightMoves) {
    SetupHysteresis hysteresis;
    const PerspectiveCamera c = groundCamera();
    auto first = hysteresis.next(inputs(c, Technique::Tsm));
    ASSERT_TRUE(first);
    auto again = hysteresis.next(inputs(c, Technique::Tsm));
    ASSERT_TRUE(again);
    EXPECT_FALSE(hysteresis.refitted());
    EXPECT_EQ(again->views[0].clipFromWorld, first->views[0].clipFromWorld);
    EXPECT_EQ(again->views[0].linearDepthFromWorld, first->views[0].linearDepthFromWorld);
    ShadowSetupInputs in = inputs(c, Technique::Tsm);
    in.light = DirectionalLight::fromSunAngles(35.5, 110.0).value();
    ASSERT_TRUE(hysteresis.next(in));
    EXPECT_TRUE(hysteresis.refitted());
    in.mapSize = 2048;
    ASSERT_TRUE(hysteresis.next(in));
    EXPECT_TRUE(hysteresis.refitted());
}

TEST(SetupHysteresis, AStillCameraOrAMovingLightPaysOnlyTheMargin) {
    auto ratioOnCentralRay = [](const ShadowSetupInputs& in, const ShadowSetup& held, const ShadowSetup& fresh,
                                double depth) {
        const Vec3 p = in.camera.wsEye + depth * glm::normalize(in.camera.wsDirection);
        return texelFootprint(held.views[0], in.mapSize, in.light.wsDirection, p) /
               texelFootprint(fresh.views[0], in.mapSize, in.light.wsDirection, p);
    };
    SetupHysteresis hysteresis(HysteresisOptions{.margin = 0.1, .maxTexelGrowth = 1.5, .lookaheadFrames = 10.0});
    // A first frame (a still view): the fresh fit with the margin.
    ShadowSetupInputs in = inputs(groundCamera(), Technique::Lispsm);
    auto held = hysteresis.next(in);
    auto fresh = computeShadowSetup(in);
    ASSERT_TRUE(held && fresh);
    for (const double depth : {1.0, 10.0, 100.0}) EXPECT_NEAR(ratioOnCentralRay(in, *held, *fresh, depth), 1.1, 1e-6);
    // A camera moving sideways whose map must be refitted because the sun moved: a moving
    // light refits every frame, so the refit is the margin's alone, with no room for motion.
    in.camera.wsEye.x += 3.0;
    in.light = DirectionalLight::fromSunAngles(36.0, 110.0).value();
    held = hysteresis.next(in);
    fresh = computeShadowSetup(in);
    ASSERT_TRUE(held && fresh);
    EXPECT_TRUE(hysteresis.refitted());
    for (const double depth : {1.0, 10.0, 100.0}) EXPECT_NEAR(ratioOnCentralRay(in, *held, *fresh, depth), 1.1, 1e-6);
    // Under a held sun a moving camera's refit also covers where it is going: the turning
    // climb below (TheLookaheadsRoomCosts...).
}

namespace {

// The largest ratio of `held`'s texel footprint to `fresh`'s at the points where the hysteresis
// weighs texels: the central ray from the near plane out, doubling, inside the scene.
double worstOnCentralRay(const ShadowSetupInputs& in, const ShadowView& held, const ShadowView& fresh) {
    double worst = 0.0;
    const Vec3 forward = glm::normalize(in.camera.wsDirection);
    for (double depth = in.camera.zNear;; depth *= 2.0) {
        const Vec3 p = in.camera.wsEye + std::min(depth, in.camera.zFar) * forward;
        if (in.wsSceneBounds.contains(p))
            worst = std::max(worst, texelFootprint(held, in.mapSize, in.light.wsDirection, p) /
                                        texelFootprint(fresh, in.mapSize, in.light.wsDirection, p));
        if (depth >= in.camera.zFar) break;
    }
    return worst;
}

// A climb that turns: up and forward, the view swinging 1.5° a frame — extrapolated far, the
// camera sees most of the terrain, and turns behind a warp's projection centre.
PerspectiveCamera climb(const PerspectiveCamera& c, int) {
    PerspectiveCamera out = c;
    out.wsEye += Vec3(0.1, 0.4, -0.3);
    const double turn = glm::radians(1.5);
    const Vec3 d = glm::normalize(c.wsDirection);
    out.wsDirection =
        Vec3(d.x * std::cos(turn) - d.z * std::sin(turn), d.y, d.x * std::sin(turn) + d.z * std::cos(turn));
    return out;
}

} // namespace

TEST(SetupHysteresis, TheLookaheadsRoomCostsAtMostThreeFreshTexelsAndHeldTexelsGrowAtMostTheBoundBeyondIt) {
    // However far the lookahead reaches, a refit's texels on the central ray stay within 3x a
    // fresh fit's (the cap on the lookahead's room), and a held view within maxTexelGrowth of
    // what a refit would give now: so never beyond 3 · maxTexelGrowth.
    for (const double lookahead : {10.0, 60.0, 240.0}) {
        const HysteresisOptions o{.margin = 0.05, .maxTexelGrowth = 1.25, .lookaheadFrames = lookahead};
        SetupHysteresis hysteresis(o);
        PerspectiveCamera c = groundCamera();
        double worstRefit = 0.0;
        for (int k = 0; k < 60; ++k, c = climb(c, k)) {
            const ShadowSetupInputs in = inputs(c, Technique::Lispsm);
            auto setup = hysteresis.next(in);
            auto fresh = computeShadowSetup(in);
            ASSERT_TRUE(setup && fresh);
            const double ratio = worstOnCentralRay(in, setup->views[0], fresh->views[0]);
            if (hysteresis.refitted()) {
                ASSERT_LE(ratio, 3.0 + 1e-9) << "lookahead " << lookahead << " frame " << k;
                worstRefit = std::max(worstRefit, ratio);
            }
            ASSERT_LE(ratio, 3.0 * o.maxTexelGrowth + 1e-9) << "lookahead " << lookahead << " frame " << k;
        }
        // The room is taken at 1, 2, 4, … frames on and then at quarters of the lookahead, as
        // far as each costs at most the cap: 60 frames take some of it; with any lookahead the
        // room stops at the last sample within the cap (the asserts above).
        if (lookahead == 60.0) {
            EXPECT_GT(worstRefit, 1.5) << "the lookahead's room was taken";
        }
    }
}

TEST(SetupHysteresis, ALookaheadHoldsATurningClimbWithFewerRefits) {
    auto refitsAlong = [](double lookahead, auto motion, int frames) {
        SetupHysteresis hysteresis(HysteresisOptions{.lookaheadFrames = lookahead});
        PerspectiveCamera c = groundCamera();
        int refits = -1; // the first frame always fits
        for (int k = 0; k < frames; ++k, c = motion(c, k)) {
            EXPECT_TRUE(hysteresis.next(inputs(c, Technique::Tsm)));
            refits += hysteresis.refitted();
        }
        return refits;
    };
    const int without = refitsAlong(0.0, climb, 60), with = refitsAlong(60.0, climb, 60);
    std::printf("turning climb, 60 frames: %d refits without lookahead, %d with 60 frames\n", without, with);
    EXPECT_LT(with, without);
}

TEST(TexelFootprint, UniformMapsAreEvenWarpedMapsGrowAwayFromTheViewer) {
    const ShadowSetupInputs in = inputs(groundCamera(), Technique::Focused);
    auto focused = computeShadowSetup(in);
    ShadowSetupInputs warped = in;
    warped.technique = Technique::Lispsm;
    auto lispsm = computeShadowSetup(warped);
    ASSERT_TRUE(focused && lispsm);
    const Vec3 forward = glm::normalize(in.camera.wsDirection), l = in.light.wsDirection;
    const double at1 = texelFootprint(focused->views[0], in.mapSize, l, in.camera.wsEye + forward);
    double previous = 0.0;
    for (const double depth : {1.0, 4.0, 16.0, 64.0, 256.0}) {
        const Vec3 p = in.camera.wsEye + depth * forward;
        EXPECT_NEAR(texelFootprint(focused->views[0], in.mapSize, l, p), at1, 1e-9 * at1);
        const double warpedHere = texelFootprint(lispsm->views[0], in.mapSize, l, p);
        EXPECT_GT(warpedHere, previous);
        previous = warpedHere;
    }
    // Twice the texels per side, half the footprint.
    EXPECT_NEAR(texelFootprint(focused->views[0], 2 * in.mapSize, l, in.camera.wsEye + forward), 0.5 * at1, 1e-9 * at1);
    // Behind a warp's projection centre there is no texel.
    EXPECT_TRUE(std::isinf(texelFootprint(lispsm->views[0], in.mapSize, l, in.camera.wsEye - 1e4 * forward)));
}

TEST(SetupHysteresis, RefusesBadOptionsNamingTheField) {
    auto margin = validate(HysteresisOptions{.margin = -0.1});
    ASSERT_FALSE(margin);
    EXPECT_EQ(margin.errorInfo().field, "hysteresis.margin");
    auto growth = validate(HysteresisOptions{.maxTexelGrowth = 1.0});
    ASSERT_FALSE(growth);
    EXPECT_EQ(growth.errorInfo().field, "hysteresis.growth");
    EXPECT_EQ(validate(HysteresisOptions{.lookaheadFrames = -1.0}).errorInfo().field, "hysteresis.lookahead");
    SetupHysteresis bad(HysteresisOptions{.margin = 2.0});
    EXPECT_FALSE(bad.next(inputs(groundCamera(), Technique::Lispsm)));
}

TEST(SetupHysteresis, ALookaheadHoldsATurntableRoundAModelOnAWideGround) {
    // The camera of `--path orbit` round a compact model that stands on a 300 m ground: close to
    // the model, so the ground behind it fills the view and the focus body swings round with the
    // camera. A refit's room for the motion must hold at least the next frame: sampled only at
    // quarters of the lookahead, the first quarter (22.5° on) lay behind the warp's projection
    // centre for a third of the turn, every refit there had no room, and the camera outgrew
    // each one's margin the next frame — refits in 32 frames running.
    auto turntable = [](int k) {
        const double a = glm::radians(1.5 * k);
        PerspectiveCamera c = groundCamera();
        c.wsEye = Vec3(20.0 * std::sin(a), 8.0, 20.0 * std::cos(a));
        c.wsDirection = Vec3(0.0, 2.0, 0.0) - c.wsEye;
        c.zNear = 0.5, c.zFar = 400.0;
        return c;
    };
    auto refitsOnce = [&](double lookahead, Technique technique) {
        SetupHysteresis hysteresis(HysteresisOptions{.lookaheadFrames = lookahead});
        int refits = -1; // the first frame always fits
        bool coverRefitLastFrame = false;
        for (int k = 0; k < 240; ++k) {
            ShadowSetupInputs in = inputs(turntable(k), technique);
            in.wsSceneBounds = Aabb::fromMinMax(Vec3(-150, -1, -150), Vec3(150, 6, 150));
            EXPECT_TRUE(hysteresis.next(in));
            refits += hysteresis.refitted();
            const bool coverRefit = k > 0 && hysteresis.lastRefits().toCover > 0;
            if (lookahead > 0.0) {
                EXPECT_FALSE(coverRefit && coverRefitLastFrame)
                    << techniqueName(technique) << " frame " << k << ": the last refit did not hold one frame";
            }
            coverRefitLastFrame = coverRefit;
        }
        return refits;
    };
    for (const Technique t : {Technique::Tsm, Technique::Lispsm}) {
        const int without = refitsOnce(0.0, t), with = refitsOnce(60.0, t);
        std::printf("%s once round a model: %d refits without lookahead, %d with 60 frames\n",
                    std::string(techniqueName(t)).c_str(), without, with);
        EXPECT_LT(with, without) << techniqueName(t);
    }
}
