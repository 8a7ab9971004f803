// The clipmap of virtual shadow maps: levels hold what their rule gives them, nest, keep
// their page keys under camera motion, and a page's own matrix agrees with its level's.
#include "setup_configs.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/virtual_clipmap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

using namespace shadowkit::core;
using namespace shadowkit::core::testing;

namespace {

// The standard scene's kind of view: an eye 1.8 m over a 2 km forest box, sun at 30°; the box
// and the page grid's origin `wsWorld` (the world's origin, moved to test large worlds).
ShadowSetupInputs forestView(const Vec3& wsEye = Vec3(0.0, 1.8, 0.0), const Vec3& wsWorld = Vec3(0.0)) {
    ShadowSetupInputs in;
    in.technique = Technique::Virtual;
    in.camera.wsEye = wsEye;
    in.camera.wsDirection = Vec3(0.0, -0.1, -1.0);
    in.camera.zNear = 0.5;
    in.camera.zFar = 500.0;
    in.light = DirectionalLight{glm::normalize(Vec3(-0.75, -0.5, -0.43))};
    in.wsSceneBounds = Aabb::fromMinMax(wsWorld + Vec3(-1000.0, -2.0, -1000.0), wsWorld + Vec3(1000.0, 30.0, 1000.0));
    in.wsGridOrigin = wsWorld;
    in.virtualMaps.imageHeight = 720;
    return in;
}

const ClipmapLevel& levelOf(const ShadowView& view) { return std::get<ClipmapLevel>(view.warp); }

// Light-space rect of a level's window as NDC of another level's view: the corners of one
// level, mapped by the other's clip matrix.
double worstOutside(const ShadowView& outer, const ShadowView& inner) {
    const Mat4 worldFromInnerClip = glm::inverse(inner.clipFromWorld);
    double worst = 0.0;
    for (const double x : {-1.0, 1.0})
        for (const double y : {-1.0, 1.0}) {
            const Vec4 p = worldFromInnerClip * Vec4(x, y, 0.5, 1.0);
            worst = std::max(worst, outsideClipCube(outer.clipFromWorld, Vec3(p) / p.w));
        }
    return worst;
}

} // namespace

TEST(VirtualClipmapTest, LevelsDoubleTheirTexelsAndEachHoldsTheFinerOne) {
    for (const double x : {0.0, 3.7, -250.3, 1.0e6}) {
        const Vec3 world(x, 0.0, -0.5 * x);
        const ShadowSetupInputs in = forestView(world + Vec3(0.3, 1.8, 0.2), world);
        const auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        ASSERT_TRUE(setup->clipmap);
        ASSERT_GE(setup->views.size(), 6u); // ~1 mm at the near plane to ~1 m at 500 m
        EXPECT_EQ(setup->mapSize, in.virtualMaps.virtualTexels);
        for (size_t k = 1; k < setup->views.size(); ++k) {
            EXPECT_EQ(levelOf(setup->views[k]).exponent, levelOf(setup->views[k - 1]).exponent + 1);
            EXPECT_LE(worstOutside(setup->views[k], setup->views[k - 1]), 1e-9) << "level " << k << " at x " << x;
        }
        // The scene box's whole depth range lies in [0, 1] of every level.
        for (const ShadowView& view : setup->views)
            for (const Vec3& corner : in.wsSceneBounds.corners()) {
                const Vec4 c = view.clipFromWorld * Vec4(corner, 1.0);
                EXPECT_GE(c.z / c.w, -1e-9);
                EXPECT_LE(c.z / c.w, 1.0 + 1e-9);
            }
    }
}

TEST(VirtualClipmapTest, TheLevelRuleGivesTheLargestTexelNoLargerThanTheFootprint) {
    RandomSource random(32);
    for (int i = 0; i < 10000; ++i) {
        const double footprint = std::exp2(random.uniform(-14.0, 6.0));
        const int e = clipmapExponentFor(footprint, 0.0);
        EXPECT_LE(std::ldexp(1.0, e), footprint);     // one texel per pixel or finer...
        EXPECT_GT(std::ldexp(1.0, e + 1), footprint); // ...and never more than one level finer
        EXPECT_EQ(clipmapExponentFor(footprint, 1.0), e + 1);
        EXPECT_EQ(clipmapExponentFor(footprint, -2.0), e - 2);
    }
    // A pixel of a 720-row image at 60°: 1.6 mm per metre of depth.
    PerspectiveCamera camera;
    EXPECT_NEAR(pixelFootprintPerMetre(camera, 720), 2.0 * std::tan(glm::radians(30.0)) / 720.0, 1e-15);
}

TEST(VirtualClipmapTest, EveryVisibleReceiverLiesInsideTheLevelItsRulePicks) {
    ConfigGenerator gen(321);
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
        ShadowSetupInputs in = gen.next();
        in.technique = Technique::Virtual;
        in.camera.fovYDegrees = std::min(in.camera.fovYDegrees, 120.0);
        in.camera.zNear = std::max(in.camera.zNear, 0.05);
        in.camera.zFar = std::min(in.camera.zFar, 1000.0 * in.camera.zNear);
        if (in.camera.zFar <= in.camera.zNear * 1.01) continue;
        in.virtualMaps.imageHeight = 720;
        const auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        if (setup->views.size() == size_t(kMaxClipmapLevels)) continue; // finest dropped: nothing to hold below it
        const Vec3 forward = glm::normalize(in.camera.wsDirection);
        for (int s = 0; s < 50; ++s) {
            const Vec3 p = pointInFrustum(in.camera, gen);
            if (!in.wsSceneBounds.contains(p, 1e-9)) continue; // only receivers in the scene
            const double depth = glm::dot(p - in.camera.wsEye, forward);
            const int rule = clipmapLevelFor(*setup->clipmap, int(setup->views.size()), depth);
            const std::optional<int> level = clipmapLevelHolding(*setup, depth, p);
            // Some level holds every receiver in the scene (the last holds the whole box)...
            ASSERT_TRUE(level) << "config " << i << ", depth " << depth;
            EXPECT_TRUE(clipmapPageOf(*setup, *level, p));
            EXPECT_GE(*level, rule);
            // ...and at a field of view of 10° or more the rule's own level does (720 rows).
            if (in.camera.fovYDegrees >= 10.0) {
                EXPECT_EQ(*level, rule) << "config " << i << ", depth " << depth;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(VirtualClipmapTest, PageKeysAreAnchoredToTheWorldWhileTheSunIsStill) {
    const Vec3 receivers[] = {{3.0, 0.0, -10.0}, {-20.0, 5.0, -60.0}, {100.0, 0.0, -300.0}};
    const auto before = computeShadowSetup(forestView());
    ASSERT_TRUE(before);
    int compared = 0;
    for (const Vec3& step : {Vec3(0.004, 0.0, 0.0), Vec3(0.3, 0.1, -0.7), Vec3(-12.0, 0.0, -35.0)}) {
        const auto after = computeShadowSetup(forestView(Vec3(0.0, 1.8, 0.0) + step));
        ASSERT_TRUE(after);
        for (size_t a = 0; a < before->views.size(); ++a)
            for (size_t b = 0; b < after->views.size(); ++b) {
                if (levelOf(before->views[a]).exponent != levelOf(after->views[b]).exponent) continue;
                for (const Vec3& p : receivers) {
                    const auto k0 = clipmapPageOf(*before, int(a), p), k1 = clipmapPageOf(*after, int(b), p);
                    if (!k0 || !k1) continue;
                    EXPECT_EQ(*k0, *k1) << "exponent " << k0->exponent;
                    ++compared;
                }
            }
    }
    EXPECT_GT(compared, 20);
}

TEST(VirtualClipmapTest, APagesTableCellIsItsGridIndexModuloThePagesASideNegativeIndicesIncluded) {
    // Grid indices run negative west and south of the grid origin; a window straddling it has
    // pages on both sides, every one in its own cell.
    constexpr int n = 128;
    for (const auto& [index, cell] : std::vector<std::pair<int64_t, int>>{{0, 0},
                                                                          {5, 5},
                                                                          {127, 127},
                                                                          {128, 0},
                                                                          {-1, 127},
                                                                          {-128, 0},
                                                                          {-129, 127},
                                                                          {int64_t(1) << 40, 0},
                                                                          {-(int64_t(1) << 40) - 3, 125}}) {
        EXPECT_EQ(pageTableCellOf(index, 0, n).x, cell) << index;
        EXPECT_EQ(pageTableCellOf(7, index, n).y, cell) << index;
    }
    std::set<std::pair<int, int>> cells;
    for (int64_t y = -70; y < -70 + n; ++y)
        for (int64_t x = -3; x < -3 + n; ++x) {
            const PageTableCell c = pageTableCellOf(x, y, n);
            cells.insert({c.x, c.y});
        }
    EXPECT_EQ(cells.size(), size_t(n) * n) << "a window of n² pages fills every cell once";
}

TEST(VirtualClipmapTest, APagesOwnMatrixAgreesWithItsLevelToAMillionthOfATexel) {
    // The renderer draws a page with clipmapPageClipFromWorld and looks it up through the
    // level's view: the same texel both ways, also a thousand kilometres from the origin.
    for (const double offset : {0.0, 1.0e6}) {
        const Vec3 wsEye(offset, 1.8, offset);
        const ShadowSetupInputs in = forestView(wsEye, Vec3(offset, 0.0, offset));
        const auto setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        const VirtualClipmap& c = *setup->clipmap;
        const int guard = 3;
        const double pageSpan = c.pageTexels + 2.0 * guard;
        // The renderer's space: the scene's origin near the eye.
        const Vec3 wsSpace = wsEye + Vec3(12.0, 0.0, -7.0);
        const ShadowSetup local = rebased(*setup, wsSpace);
        for (size_t level = 0; level < local.views.size(); ++level)
            for (const Vec3& rel : {Vec3(1.0, 0.0, -2.0), Vec3(-4.0, 0.2, -30.0), Vec3(0.0, 0.0, 0.0)}) {
                const Vec3 p = wsEye + rel;
                const auto key = clipmapPageOf(*setup, int(level), p);
                if (!key) continue;
                const Vec4 levelClip = local.views[level].clipFromWorld * Vec4(p - wsSpace, 1.0);
                const Vec4 pageClip = clipmapPageClipFromWorld(*local.clipmap, *key, guard) * Vec4(p - wsSpace, 1.0);
                const auto& info = levelOf(local.views[level]);
                for (int axis = 0; axis < 2; ++axis) {
                    const int64_t page = axis == 0 ? key->x - info.firstPageX : key->y - info.firstPageY;
                    const double levelTexel = (0.5 * levelClip[axis] + 0.5) * c.virtualTexels;
                    const double pageTexel = (0.5 * pageClip[axis] + 0.5) * pageSpan;
                    EXPECT_NEAR(levelTexel - double(page) * c.pageTexels + guard, pageTexel, 1e-6)
                        << "offset " << offset << ", level " << level;
                }
                EXPECT_NEAR(levelClip.z, pageClip.z, 1e-9); // the same depth in every page and level
            }
    }
}

TEST(VirtualClipmapTest, BadOptionsAreRefusedByName) {
    ShadowSetupInputs in = forestView();
    in.virtualMaps.pageTexels = 100;
    EXPECT_EQ(computeShadowSetup(in).errorInfo().field, "virtual.page_texels");
    in = forestView();
    in.virtualMaps.virtualTexels = 3000;
    EXPECT_EQ(computeShadowSetup(in).errorInfo().field, "virtual.texels");
    in = forestView();
    in.virtualMaps.lodBias = NAN;
    EXPECT_EQ(computeShadowSetup(in).errorInfo().field, "virtual.lod_bias");
    in = forestView();
    in.virtualMaps.firstLevel = 40;
    EXPECT_EQ(computeShadowSetup(in).errorInfo().field, "virtual.first_level");
}

TEST(VirtualClipmapTest, AnEyeBeyondAnyPageIndexMovesTheGridToItselfAndSaysSo) {
    // 1e30 m from the grid origin is far more than 2^50 pages: page indices would overflow and
    // the levels' squares vanish in double. The grid passes through the eye instead: finite
    // levels that hold the view, and a note saying why. (The eye itself stays within
    // kMaxWorldMetres of the world's origin; the grid's origin is where an engine puts it.)
    ShadowSetupInputs in = forestView(Vec3(1e12, 1.8, 0.0), Vec3(1e12, 0.0, 0.0));
    in.wsGridOrigin = Vec3(-1e30, 0.0, 0.0);
    const auto setup = computeShadowSetup(in);
    ASSERT_TRUE(setup) << setup.error();
    for (const ShadowView& view : setup->views) EXPECT_TRUE(isFinite(view.clipFromEyeRelative));
    ASSERT_FALSE(setup->fallbacks.empty());
    EXPECT_NE(setup->fallbacks.back().find("2^50 pages"), std::string::npos);
    const ShadowView& finest = setup->views[0];
    EXPECT_LE(outsideClipCube(finest.clipFromEyeRelative, Vec3(0.5, -1.8, -2.0)), 0.0); // 2 m ahead, on the ground
}

TEST(VirtualClipmapTest, AClipmapKeptFromAnEarlierFramePlacesItsLevelsAroundALaterEyeAsTheSetUpWould) {
    // gl's page budget keeps a clipmap drawn for an earlier sun on screen and places its levels
    // around each new eye with clipmapLevelView: the windows and matrices the set-up itself
    // gives at that eye, in the renderer's space, far from the origin too.
    for (const double offset : {0.0, 1.0e6}) {
        const Vec3 wsWorld(offset, 0.0, offset), wsEye0 = wsWorld + Vec3(0.0, 1.8, 0.0);
        const auto kept = computeShadowSetup(forestView(wsEye0, wsWorld));
        ASSERT_TRUE(kept);
        const Vec3 wsSpace = wsEye0 + Vec3(5.0, 0.0, 3.0);
        const VirtualClipmap keptLocal = *rebased(*kept, wsSpace).clipmap;
        for (const Vec3& step : {Vec3(0.3, 0.0, -0.7), Vec3(-40.0, 25.0, -90.0)}) {
            const auto now = computeShadowSetup(forestView(wsEye0 + step, wsWorld));
            ASSERT_TRUE(now);
            const ShadowSetup nowLocal = rebased(*now, wsSpace);
            for (const ShadowView& expected : nowLocal.views) {
                const ShadowView placed =
                    clipmapLevelView(keptLocal, levelOf(expected).exponent, wsEye0 + step - wsSpace);
                EXPECT_EQ(levelOf(placed).firstPageX, levelOf(expected).firstPageX);
                EXPECT_EQ(levelOf(placed).firstPageY, levelOf(expected).firstPageY);
                for (const Vec3& rel : {Vec3(1.0, 0.0, -2.0), Vec3(-30.0, 4.0, -60.0)}) {
                    const Vec3 p = wsEye0 + step + rel - wsSpace;
                    const Vec4 a = placed.clipFromWorld * Vec4(p, 1.0), b = expected.clipFromWorld * Vec4(p, 1.0);
                    EXPECT_NEAR(a.x * 0.5 * kept->clipmap->virtualTexels, b.x * 0.5 * kept->clipmap->virtualTexels,
                                1e-6);
                    EXPECT_NEAR(a.y * 0.5 * kept->clipmap->virtualTexels, b.y * 0.5 * kept->clipmap->virtualTexels,
                                1e-6);
                    EXPECT_NEAR(a.z, b.z, 1e-9);
                }
            }
        }
    }
}
