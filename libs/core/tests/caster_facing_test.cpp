#include "shadowkit/core/caster_facing.h"
#include "shadowkit/core/shadow_setup.h"

#include "setup_configs.h"

#include <gtest/gtest.h>

#include <map>

using namespace shadowkit::core;

namespace {

// The winding a small triangle at `wsAt`, its counter-clockwise side towards `wsTowards`, shows
// in the window space of `clipFromWorld` — projected and divided as GL does; nullopt where a
// corner has w ≤ 0 (GL would clip it) or the triangle is too thin to tell.
std::optional<Winding> projectedWinding(const Mat4& clipFromWorld, const Vec3& wsAt, const Vec3& wsTowards,
                                        double size) {
    const Vec3 n = glm::normalize(wsTowards);
    const Vec3 u = glm::normalize(glm::cross(std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 0, 1), n));
    const Vec3 v = glm::cross(n, u);
    const Vec3 corners[3] = {wsAt, wsAt + size * u, wsAt + size * v};
    glm::dvec2 ndc[3];
    for (int i = 0; i < 3; ++i) {
        const Vec4 cs = clipFromWorld * Vec4(corners[i], 1.0);
        if (!(cs.w > 0.0)) return std::nullopt;
        ndc[i] = glm::dvec2(cs.x, cs.y) / cs.w;
    }
    const glm::dvec2 e1 = ndc[1] - ndc[0], e2 = ndc[2] - ndc[0];
    const double area = e1.x * e2.y - e1.y * e2.x;
    const double scale = glm::length(e1) * glm::length(e2);
    if (!(std::abs(area) > 1e-6 * scale) || scale == 0.0) return std::nullopt;
    return area > 0.0 ? Winding::CounterClockwise : Winding::Clockwise;
}

Winding opposite(Winding w) { return w == Winding::Clockwise ? Winding::CounterClockwise : Winding::Clockwise; }

} // namespace

TEST(CasterFacingTest, AgreesWithProjectedTrianglesForEveryTechniqueAndView) {
    // Random cameras, suns and scenes (degenerate ones included): for each view of each
    // technique, small triangles at the points the view must hold are projected as GL would;
    // every one turned towards the sun winds as the function says, every one turned away the
    // other way.
    shadowkit::core::testing::ConfigGenerator gen(20261127);
    std::map<Technique, std::map<Winding, int>> seen;
    int compared = 0;
    for (int config = 0; config < 300; ++config) {
        ShadowSetupInputs in = gen.next();
        for (const TechniqueInfo& info : allTechniques()) {
            in.technique = info.technique;
            const auto setup = computeShadowSetup(in);
            if (!setup) continue;
            const Vec3 towards = in.light.wsTowardsLight();
            for (const ShadowView& view : setup->views) {
                const Winding said = lightFacingWinding(view.clipFromWorld, towards);
                const std::vector<Vec3> points = shadowkit::core::testing::pointsToHold(in, *setup, view);
                const double size = 1e-3 * std::max(1.0, glm::length(in.wsSceneBounds.extent()));
                for (const Vec3& p : points) {
                    const auto facing = projectedWinding(view.clipFromWorld, p, towards, size);
                    const auto away = projectedWinding(view.clipFromWorld, p, -towards, size);
                    if (!facing || !away) continue;
                    ASSERT_EQ(*facing, said) << info.name << " config " << config;
                    ASSERT_EQ(*away, opposite(said)) << info.name << " config " << config;
                    ++seen[info.technique][said];
                    ++compared;
                }
            }
        }
    }
    EXPECT_GT(compared, 10000);
    // PSM's and TSM's projections flip the winding for some views and suns (LiSPSM's and the
    // uniform fits do not here): the cases a fixed glFrontFace(GL_CCW) gets wrong.
    for (const Technique t : {Technique::Psm, Technique::Tsm}) {
        EXPECT_GT(seen[t][Winding::Clockwise], 0) << int(t);
        EXPECT_GT(seen[t][Winding::CounterClockwise], 0) << int(t);
    }
}

TEST(CasterFacingTest, AMirroredMapFlipsTheWinding) {
    const Vec3 towards = glm::normalize(Vec3(0.3, 1.0, -0.2));
    const Mat4 clipFromLight = glm::ortho(-50.0, 50.0, -50.0, 50.0, 0.0, 200.0);
    const Mat4 lightFromWorld = glm::lookAt(100.0 * towards, Vec3(0.0), Vec3(0, 0, 1));
    const Mat4 clipFromWorld = clipFromLight * lightFromWorld;
    EXPECT_EQ(lightFacingWinding(clipFromWorld, towards), Winding::CounterClockwise);
    EXPECT_EQ(lightFacingWinding(glm::scale(Mat4(1.0), Vec3(-1, 1, 1)) * clipFromWorld, towards), Winding::Clockwise);
    // The light's side of a face decides, not where the face is: far from the world's origin too.
    const Mat4 far = clipFromWorld * glm::translate(Mat4(1.0), Vec3(-3e6, 0, 2e6));
    EXPECT_EQ(lightFacingWinding(far, towards), Winding::CounterClockwise);
    EXPECT_EQ(lightFacingWinding(clipFromWorld, -towards), Winding::Clockwise);
}
