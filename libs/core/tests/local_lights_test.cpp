// Spot and point light set-ups: every receiver the camera can see inside the light's volume
// lands in a map that is not skipped, inside its frustum, with its distance in the stored
// range, and its casters in front of it; faces follow OpenGL's cube-map table; degenerate
// placements have defined answers; bad lights are refused naming the field. A point light in
// one map (for engines without cube maps) holds the same receivers in the narrowest cone.
#include "shadowkit/core/local_lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace shadowkit::core;

namespace {

const Aabb kScene = Aabb::fromMinMax(Vec3(-100, 0, -100), Vec3(100, 30, 100));

Vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return glm::normalize(Vec3(g(rng), g(rng), g(rng)));
}

PerspectiveCamera randomCamera(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    PerspectiveCamera c;
    c.wsEye = Vec3(-90 + 180 * u(rng), 1 + 40 * u(rng), -90 + 180 * u(rng));
    c.wsDirection = randomUnit(rng);
    c.fovYDegrees = 30 + 70 * u(rng);
    c.aspect = 0.8 + u(rng);
    c.zNear = 0.1 + 2 * u(rng);
    c.zFar = 50 + 450 * u(rng);
    return c;
}

// A point of the view frustum (trilinear in its corners), not uniformly spread but reaching
// every part of it.
Vec3 pointInFrustum(const PerspectiveCamera& c, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto k = c.wsFrustumCorners();
    const double a = u(rng), b = u(rng), depth = std::pow(u(rng), 2.0);
    auto on = [&](int base) {
        return glm::mix(glm::mix(k[base], k[base + 1], a), glm::mix(k[base + 3], k[base + 2], a), b);
    };
    return glm::mix(on(0), on(4), depth);
}

// p lands inside the view: in front of it, inside its x/y extent, its distance in range.
void expectHolds(const ShadowSetup& setup, const ShadowView& view, const Vec3& p, const char* what) {
    const Vec4 c = view.clipFromWorld * Vec4(p, 1.0);
    ASSERT_GT(c.w, 0.0) << what;
    EXPECT_LE(std::abs(c.x / c.w), 1.0 + 1e-7) << what;
    EXPECT_LE(std::abs(c.y / c.w), 1.0 + 1e-7) << what;
    const double depth = lightDistanceDepth(setup, view, p);
    EXPECT_GE(depth, -1e-7) << what;
    EXPECT_LE(depth, 1.0 + 1e-7) << what;
    // Its casters: every point between it and the light is in the same view, nearer.
    for (const double s : {0.001, 0.3, 0.9}) {
        const Vec3 q = setup.wsLightPosition + s * (p - setup.wsLightPosition);
        const Vec4 cq = view.clipFromWorld * Vec4(q, 1.0);
        ASSERT_GT(cq.w, 0.0) << what << " caster";
        EXPECT_LE(std::abs(cq.x / cq.w), 1.0 + 1e-7) << what << " caster";
        EXPECT_LE(std::abs(cq.y / cq.w), 1.0 + 1e-7) << what << " caster";
        EXPECT_LE(std::clamp(lightDistanceDepth(setup, view, q), 0.0, 1.0), depth + 1e-9) << what << " caster";
    }
}

const ShadowView* faceView(const ShadowSetup& setup, int face) {
    for (const ShadowView& v : setup.views)
        if (v.face == face) return &v;
    return nullptr;
}

} // namespace

TEST(LocalLights, EveryVisibleReceiverInRangeIsHeldWithItsCastersOverRandomConfigurations) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long checked = 0, skipped = 0, singleMaps = 0, refused = 0, heldByAimed = 0;
    for (int config = 0; config < 10000; ++config) {
        const LocalShadowInputs in{.camera = randomCamera(rng), .wsSceneBounds = kScene, .mapSize = 512};
        // Mostly near the camera (where lights matter), sometimes anywhere, outside the scene too.
        const Vec3 position = config % 4 == 0 ? Vec3(-120 + 240 * u(rng), -5 + 45 * u(rng), -120 + 240 * u(rng))
                                              : in.camera.wsEye + 40.0 * u(rng) * randomUnit(rng);
        const double range = 1 + 79 * u(rng);
        const PointLight point{.wsPosition = position, .range = range};
        const SpotLight spot{
            .wsPosition = position, .wsDirection = randomUnit(rng), .coneDegrees = 5 + 165 * u(rng), .range = range};
        auto cube = computePointShadowSetup(in, point);
        auto cone = computeSpotShadowSetup(in, spot);
        ASSERT_TRUE(cube && cone) << config;
        // The point light in one map, where what the camera sees spans less than 170° from it.
        auto single = computePointSingleMapSetup(in, point);
        if (single) {
            ++singleMaps;
            ASSERT_LE(single->views.size(), 1u);
            EXPECT_EQ(single->lightType, LightType::Spot); // one perspective map, no cube face
        } else {
            ++refused;
            EXPECT_EQ(single.errorInfo().field, "point.position");
        }
        // Where it is refused, the map aimed at the middle of it holds what lies in its cone: what
        // an engine without cube maps asks for in one call, the single map where there is one.
        auto aimed = computePointSingleOrAimedMapSetup(in, point);
        ASSERT_TRUE(aimed) << aimed.error();
        if (single) {
            ASSERT_EQ(aimed->views.size(), single->views.size());
            if (!single->views.empty()) EXPECT_EQ(aimed->views[0].clipFromWorld, single->views[0].clipFromWorld);
            EXPECT_FALSE(aimed->holdsPartOfView);
        } else {
            EXPECT_EQ(aimed->holdsPartOfView, !aimed->views.empty());
        }
        const double cosAimed = std::cos(glm::radians(85.0));
        const Vec3 wsAimedAxis =
            aimed->views.empty()
                ? Vec3(0.0)
                : -glm::normalize(Vec3(glm::inverse(aimed->views[0].lightFromWorld) * Vec4(0, 0, 1, 0)));
        EXPECT_EQ(int(cube->views.size()) + cube->skippedFaces, 6);
        skipped += cube->skippedFaces;
        for (const ShadowSetup* s : {&*cube, &*cone})
            for (const ShadowView& v : s->views) {
                ASSERT_TRUE(isFinite(v.clipFromWorld)) << config;
                ASSERT_TRUE(isFinite(v.lightDistance) && v.lightDistance.y > v.lightDistance.x &&
                            v.lightDistance.x >= 0.0)
                    << config;
            }
        const double cosHalf = std::cos(0.5 * glm::radians(spot.coneDegrees));
        const auto frustum = in.camera.wsFrustumPlanes();
        for (int k = 0; k < 20; ++k) {
            // Half from the view frustum, half from the light's ball: visible, in the scene, in range.
            const Vec3 p =
                k % 2 ? pointInFrustum(in.camera, rng) : position + range * std::cbrt(u(rng)) * randomUnit(rng);
            bool visible = true;
            for (const Plane& plane : frustum) visible = visible && plane.signedDistance(p) <= 0.0;
            if (!visible || !kScene.contains(p) || glm::distance(p, position) > range ||
                glm::distance(p, position) < 1e-6)
                continue;
            ++checked;
            const ShadowView* face = faceView(*cube, cubeFaceOf(p - position));
            ASSERT_NE(face, nullptr) << "config " << config << ": a visible receiver's face was skipped";
            expectHolds(*cube, *face, p, "point");
            if (single) {
                ASSERT_EQ(single->views.size(), 1u) << "config " << config << ": a lit receiver but no single map";
                expectHolds(*single, single->views[0], p, "point, one map");
            } else {
                ASSERT_EQ(aimed->views.size(), 1u) << "config " << config << ": a lit receiver but no aimed map";
                if (glm::dot(glm::normalize(p - position), wsAimedAxis) >= cosAimed) {
                    ++heldByAimed;
                    expectHolds(*aimed, aimed->views[0], p, "point, aimed map");
                }
            }
            if (glm::dot(glm::normalize(p - position), glm::normalize(spot.wsDirection)) >= cosHalf) {
                ASSERT_EQ(cone->views.size(), 1u) << "config " << config << ": a lit receiver but no spot map";
                expectHolds(*cone, cone->views[0], p, "spot");
            }
        }
    }
    EXPECT_GT(checked, 10000);   // the configurations are not all vacuous
    EXPECT_GT(singleMaps, 1000); // and both answers of the single map are exercised
    EXPECT_GT(refused, 400);
    EXPECT_GT(heldByAimed, 100);
    std::printf("%ld receivers checked; %.2f of 6 faces skipped on average; one map for %ld point lights, a cube "
                "needed for %ld (%ld of their receivers in the aimed map's cone)\n",
                checked, double(skipped) / 10000.0, singleMaps, refused, heldByAimed);
}

TEST(LocalLights, CubeFacesFollowTheOpenGlTable) {
    // OpenGL 4.5 §8.13, Table 8.19: for the major axis, (sc, tc) and ma; s = sc / |ma|.
    std::mt19937 rng(9);
    for (int k = 0; k < 1000; ++k) {
        const Vec3 r = randomUnit(rng);
        const int face = cubeFaceOf(r);
        double sc = 0, tc = 0, ma = 0;
        switch (face) {
        case 0:
            sc = -r.z, tc = -r.y, ma = r.x;
            break;
        case 1:
            sc = r.z, tc = -r.y, ma = r.x;
            break;
        case 2:
            sc = r.x, tc = r.z, ma = r.y;
            break;
        case 3:
            sc = r.x, tc = -r.z, ma = r.y;
            break;
        case 4:
            sc = r.x, tc = -r.y, ma = r.z;
            break;
        case 5:
            sc = -r.x, tc = -r.y, ma = r.z;
            break;
        }
        const CubeFace& f = cubeFaces()[size_t(face)];
        EXPECT_GT(glm::dot(r, f.wsAxis), 0.0);
        const Mat4 view = glm::lookAt(Vec3(0.0), f.wsAxis, f.wsUp);
        const Vec3 v(view * Vec4(r, 0.0));
        EXPECT_NEAR(v.x / -v.z, sc / std::abs(ma), 1e-12) << "face " << face;
        EXPECT_NEAR(v.y / -v.z, tc / std::abs(ma), 1e-12) << "face " << face;
    }
}

TEST(LocalLights, DegeneratePlacementsHaveDefinedAnswers) {
    PerspectiveCamera c;
    c.wsEye = {0, 2, 0};
    c.wsDirection = {0, 0, -1};
    c.zFar = 200;
    const LocalShadowInputs in{.camera = c, .wsSceneBounds = kScene};
    // A light inside what the camera sees: every cube face sees some of it; the spot keeps its whole cone.
    auto inside = computePointShadowSetup(in, PointLight{.wsPosition = {0, 3, -20}, .range = 10});
    ASSERT_TRUE(inside);
    EXPECT_EQ(inside->views.size(), 6u);
    const SpotLight torch{.wsPosition = {0, 3, -20}, .wsDirection = {0, -1, -1}, .coneDegrees = 60, .range = 10};
    auto full = computeSpotShadowSetup(in, torch);
    ASSERT_TRUE(full);
    ASSERT_EQ(full->views.size(), 1u);
    EXPECT_NEAR(full->views[0].clipFromLight[0][0], 1.0 / std::tan(glm::radians(30.0)), 1e-9);
    // Behind the camera and out of reach: nothing to draw, said so.
    auto behind = computePointShadowSetup(in, PointLight{.wsPosition = {0, 3, 40}, .range = 10});
    ASSERT_TRUE(behind);
    EXPECT_TRUE(behind->views.empty());
    EXPECT_EQ(behind->skippedFaces, 6);
    EXPECT_FALSE(behind->fallbacks.empty());
    // A spot above the scene pointing at the sky lights nothing: no map, said so.
    auto sky = computeSpotShadowSetup(
        in, SpotLight{.wsPosition = {0, 50, -20}, .wsDirection = {0, 1, 0}, .coneDegrees = 30, .range = 10});
    ASSERT_TRUE(sky);
    EXPECT_TRUE(sky->views.empty());
    EXPECT_FALSE(sky->fallbacks.empty());
    // A light on one side of the view: the faces looking away from the frustum are skipped.
    auto side = computePointShadowSetup(in, PointLight{.wsPosition = {0, 3, 5}, .range = 60});
    ASSERT_TRUE(side);
    EXPECT_EQ(faceView(*side, 4), nullptr); // +Z: behind the camera, outside the frustum
    EXPECT_GT(side->skippedFaces, 0);
}

TEST(LocalLights, TheSpotMapNarrowsToWhatTheCameraSeesOfTheCone) {
    PerspectiveCamera c;
    c.wsEye = {0, 2, 0};
    c.wsDirection = {0, -0.2, -1};
    c.fovYDegrees = 30;
    c.zFar = 40;
    const LocalShadowInputs in{.camera = c, .wsSceneBounds = kScene};
    // A wide lamp high above, looking down over an area much larger than the view.
    const SpotLight lamp{.wsPosition = {0, 25, -20}, .wsDirection = {0, -1, 0}, .coneDegrees = 150, .range = 60};
    auto setup = computeSpotShadowSetup(in, lamp);
    ASSERT_TRUE(setup);
    ASSERT_EQ(setup->views.size(), 1u);
    const double tanHalf = std::tan(glm::radians(75.0));
    const double width = 2.0 / setup->views[0].clipFromLight[0][0], height = 2.0 / setup->views[0].clipFromLight[1][1];
    EXPECT_LT(width * height, 0.25 * (2 * tanHalf) * (2 * tanHalf)); // a quarter of the cone's area or less
}

TEST(LocalLights, APointLightInOneMapTakesTheNarrowestConeOverWhatTheCameraSees) {
    // A 20 m square yard, 1 m deep, seen whole from 100 m above; a lamp 20 m over its centre.
    // The narrowest cone from the lamp that holds the yard is centred straight down, its half-
    // angle the one to a bottom corner: atan(10√2 / 20).
    PerspectiveCamera c;
    c.wsEye = {0, 100, 0};
    c.wsDirection = {0, -1, 0};
    c.wsUp = {0, 0, -1};
    c.zFar = 200;
    const Aabb yard = Aabb::fromMinMax(Vec3(-10, 0, -10), Vec3(10, 1, 10));
    const LocalShadowInputs in{.camera = c, .wsSceneBounds = yard, .mapSize = 1024};
    auto above = computePointSingleMapSetup(in, PointLight{.wsPosition = {0, 20, 0}, .range = 60});
    ASSERT_TRUE(above) << above.error();
    ASSERT_EQ(above->views.size(), 1u);
    EXPECT_EQ(above->lightType, LightType::Spot); // one perspective map, no cube face
    const ShadowView& map = above->views[0];
    // The axis: the map's view direction (its −z) points down.
    const Vec3 wsAxis = -glm::normalize(Vec3(glm::inverse(map.lightFromWorld) * Vec4(0, 0, 1, 0)));
    EXPECT_GT(glm::dot(wsAxis, Vec3(0, -1, 0)), std::cos(glm::radians(0.5)));
    // The map spans the yard's top corners' tangents, 10 / 19, each way: no wider.
    const double width = 2.0 / map.clipFromLight[0][0], height = 2.0 / map.clipFromLight[1][1];
    EXPECT_NEAR(width, 2.0 * 10.0 / 19.0, 0.02);
    EXPECT_NEAR(height, 2.0 * 10.0 / 19.0, 0.02);

    // The same lamp off to the side, 30 m from the yard's edge: one map, far narrower than the
    // 90° faces a cube would give it, and the yard's farther corners inside it.
    auto side = computePointSingleMapSetup(in, PointLight{.wsPosition = {40, 5, 0}, .range = 80});
    ASSERT_TRUE(side);
    ASSERT_EQ(side->views.size(), 1u);
    EXPECT_LT(2.0 / side->views[0].clipFromLight[0][0], 1.0);

    // Inside the yard the lamp is surrounded by what the camera sees: no map under 180° holds it.
    auto among = computePointSingleMapSetup(in, PointLight{.wsPosition = {0, 0.5, 0}, .range = 30});
    ASSERT_FALSE(among);
    EXPECT_EQ(among.errorInfo().field, "point.position");
    EXPECT_NE(among.error().find("surrounds it"), std::string::npos) << among.error();
    EXPECT_NE(among.error().find("a cube holds it"), std::string::npos) << among.error();
    EXPECT_EQ(among.error().find('\n'), std::string::npos);
    // Beside it, half a metre from its edge: the yard spans more than 170° seen from there.
    auto beside = computePointSingleMapSetup(in, PointLight{.wsPosition = {10.5, 0.5, 0}, .range = 30});
    ASSERT_FALSE(beside);
    EXPECT_NE(beside.error().find("spans a cone of 17"), std::string::npos) << beside.error();
    // There the best one map is a 170° cone aimed at the middle of what the camera sees: the
    // yard's middle from beside it, and the camera's direction from its very middle (a lamp at
    // the mean of R's corners has no direction to it), saying that it holds only part.
    for (const auto& [wsLamp, wsAxis] :
         {std::pair{Vec3(10.5, 0.5, 0), Vec3(-1, 0, 0)}, std::pair{Vec3(0, 0.5, 0), Vec3(0, -1, 0)}}) {
        auto aimed = computePointAimedMapSetup(in, PointLight{.wsPosition = wsLamp, .range = 30});
        ASSERT_TRUE(aimed) << aimed.error();
        ASSERT_EQ(aimed->views.size(), 1u);
        const Vec3 wsMapAxis = -glm::normalize(Vec3(glm::inverse(aimed->views[0].lightFromWorld) * Vec4(0, 0, 1, 0)));
        EXPECT_GT(glm::dot(wsMapAxis, wsAxis), std::cos(glm::radians(1.0)));
        ASSERT_FALSE(aimed->fallbacks.empty());
        EXPECT_NE(aimed->fallbacks.back().find("receivers outside that cone get no shadow"), std::string::npos);
    }
    EXPECT_EQ(computePointAimedMapSetup(in, PointLight{}, 175.0).errorInfo().field, "point.cone");
    // Out of reach of the yard: nothing to draw, and that is no error.
    auto far = computePointSingleMapSetup(in, PointLight{.wsPosition = {0, 60, 0}, .range = 30});
    ASSERT_TRUE(far);
    EXPECT_TRUE(far->views.empty());
    EXPECT_FALSE(far->fallbacks.empty());
    // A bad light is refused as the cube's is.
    EXPECT_EQ(computePointSingleMapSetup(in, PointLight{.range = -1}).errorInfo().field, "point.range");
}

TEST(LocalLights, BadLightsAreRefusedNamingTheField) {
    const LocalShadowInputs in{.camera = PerspectiveCamera{}, .wsSceneBounds = kScene};
    auto field = [](const auto& result) { return result ? std::string() : result.errorInfo().field; };
    EXPECT_EQ(field(computePointShadowSetup(in, PointLight{.range = 0})), "point.range");
    EXPECT_EQ(field(computePointShadowSetup(in, PointLight{.wsPosition = {NAN, 0, 0}})), "point.position");
    EXPECT_EQ(field(computePointShadowSetup(in, PointLight{.wsPosition = {0, 1e20, 0}})),
              "point.position"); // past the world's end
    EXPECT_EQ(field(computeSpotShadowSetup(in, SpotLight{.wsPosition = {0, 1e20, 0}})), "spot.position");
    EXPECT_EQ(field(computeSpotShadowSetup(in, SpotLight{.wsDirection = {0, 0, 0}})), "spot.direction");
    EXPECT_EQ(field(computeSpotShadowSetup(in, SpotLight{.coneDegrees = 180})), "spot.cone");
    EXPECT_EQ(field(computeSpotShadowSetup(in, SpotLight{.range = INFINITY})), "spot.range");
    LocalShadowInputs flat = in;
    flat.mapSize = 4;
    EXPECT_EQ(field(computeSpotShadowSetup(flat, SpotLight{})), "map_size");
}
