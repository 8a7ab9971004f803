#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/shadow_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace shadowkit::core;

namespace {

// Random camera / light / scene-box configurations, including the degenerate ones
// the issue names: view parallel and anti-parallel to the light, tiny and huge
// near/far ratios, flat and zero-size scene boxes.
class ConfigGenerator {
public:
    explicit ConfigGenerator(unsigned seed) : m_rng(seed) {}

    ShadowSetupInputs next() {
        ShadowSetupInputs in;
        const Vec3 center(uniform(-2000, 2000), uniform(-100, 100), uniform(-2000, 2000));
        Vec3 half(uniform(0, 1500), uniform(0, 60), uniform(0, 1500));
        if (chance(0.03)) half.y = 0.0; // flat scene (a terrain plane)
        if (chance(0.01)) half = Vec3(0.0); // zero-size scene
        in.wsSceneBounds = Aabb::fromMinMax(center - half, center + half);

        PerspectiveCamera& cam = in.camera;
        // Mostly inside the box, sometimes outside (then B may be empty).
        cam.wsEye = center + Vec3(uniform(-1.2, 1.2) * half.x, uniform(-1, 3) * half.y + uniform(0, 50),
                                  uniform(-1.2, 1.2) * half.z);
        cam.wsDirection = unitVector();
        cam.wsUp = unitVector();
        if (glm::length(glm::cross(cam.wsDirection, cam.wsUp)) < 1e-3) cam.wsUp = Vec3(0, 1, 0);
        if (glm::length(glm::cross(cam.wsDirection, cam.wsUp)) < 1e-3) cam.wsUp = Vec3(1, 0, 0);
        cam.fovYDegrees = uniform(5, 170);
        cam.aspect = uniform(0.3, 3);
        cam.zNear = std::pow(10.0, uniform(-3, 1.5));
        cam.zFar = cam.zNear * std::pow(10.0, uniform(0.01, 6)); // ratios 1.02 .. 1e6

        Vec3 l = unitVector();
        const double r = uniform(0, 1);
        if (r < 0.05) l = glm::normalize(cam.wsDirection);       // view along the light
        else if (r < 0.10) l = -glm::normalize(cam.wsDirection); // looking into the sun
        else if (r < 0.15) l = glm::normalize(cam.wsDirection + 1e-7 * unitVector());
        in.light = DirectionalLight{l};

        CascadeOptions& c = in.cascades; // used by csm only
        c.count = 1 + static_cast<int>(uniform(0, 8));
        c.lambda = uniform(0, 1);
        c.warp = chance(0.5) ? CascadeWarp::Lispsm : CascadeWarp::None;
        c.stabilize = c.warp == CascadeWarp::None && chance(0.5);
        c.blendBand = chance(0.5) ? uniform(0, 0.5) : 0.0;
        in.mapSize = chance(0.5) ? 1024 : 2048;
        return in;
    }

    Vec3 unitVector() {
        std::normal_distribution<double> n;
        for (;;) {
            const Vec3 v(n(m_rng), n(m_rng), n(m_rng));
            if (glm::length(v) > 1e-6) return glm::normalize(v);
        }
    }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }
    bool chance(double p) { return uniform(0, 1) < p; }

private:
    std::mt19937 m_rng;
};

// Max distance (in clip units) by which a point lies outside the clip cube x,y in [-1,1], z in [0,1].
double outsideClipCube(const Mat4& clipFromWorld, const Vec3& ws) {
    const Vec4 cs = clipFromWorld * Vec4(ws, 1.0);
    const Vec3 ndc = Vec3(cs) / cs.w;
    return std::max({std::abs(ndc.x) - 1.0, std::abs(ndc.y) - 1.0, -ndc.z, ndc.z - 1.0, 0.0});
}

// A random point of the view frustum (uniform in NDC x/y, uniform in view depth).
Vec3 pointInFrustum(const PerspectiveCamera& cam, ConfigGenerator& gen) {
    const auto c = cam.wsFrustumCorners();
    const double u = gen.uniform(0, 1), v = gen.uniform(0, 1), t = gen.uniform(0, 1);
    const Vec3 nearPoint = glm::mix(glm::mix(c[0], c[1], u), glm::mix(c[3], c[2], u), v);
    const Vec3 farPoint = glm::mix(glm::mix(c[4], c[5], u), glm::mix(c[7], c[6], u), v);
    return glm::mix(nearPoint, farPoint, t);
}

} // namespace

TEST(ShadowSetupTest, EveryPointOfBLiesInsideTheClipCubeForTenThousandConfigurations) {
    ConfigGenerator gen(20261122);
    int emptyBodies = 0, parallelFallbacks = 0, warped = 0;
    for (int i = 0; i < 10000; ++i) {
        ShadowSetupInputs in = gen.next();
        for (const TechniqueInfo& info : allTechniques()) {
            const Technique t = info.technique;
            in.technique = t;
            const Result<ShadowSetup> setup = computeShadowSetup(in);
            ASSERT_TRUE(setup) << "config " << i << ": " << setup.error();
            ASSERT_EQ(setup->views.size(), t == Technique::Csm ? size_t(in.cascades.count) : 1u);
            for (const ShadowView& view : setup->views) {
            ASSERT_TRUE(isFinite(view.clipFromWorld) && isFinite(view.lightFromWorld)) << "config " << i;

            // Standard must hold the whole scene box; the others B, each cascade its split's B.
            ConvexBody body = setup->body;
            if (t == Technique::Csm) {
                PerspectiveCamera slice = in.camera;
                slice.zNear = view.split->x;
                slice.zFar = view.split->y;
                body = computeFocusBody(slice, in.light, in.wsSceneBounds);
            }
            // A split that sees none of the scene has nothing to hold (the stabilised fit then
            // keeps its sphere); every other empty-B case falls back to the scene box.
            if (t == Technique::Csm && body.isEmpty() && in.cascades.stabilize) continue;
            std::vector<Vec3> mustFit;
            if (t == Technique::Standard || body.isEmpty()) {
                const auto corners = sceneBoxForFocus(in.wsSceneBounds).corners();
                mustFit.assign(corners.begin(), corners.end());
            } else {
                const ConvexBody::Points points = body.vertices();
                mustFit.assign(points.begin(), points.end());
            }
            for (const Vec3& p : mustFit) {
                // No point behind a projection centre (w > 0), none outside the clip cube.
                ASSERT_GT((view.clipFromWorld * Vec4(p, 1.0)).w, 0.0) << info.name << ", config " << i;
                ASSERT_LE(outsideClipCube(view.clipFromWorld, p), 1e-6) << info.name << ", config " << i;
            }
            warped += t == Technique::Lispsm && view.clipFromWorld[3][3] != 1.0; // perspective, not affine
            }

            if (t == Technique::Focused) {
                emptyBodies += setup->body.isEmpty();
                parallelFallbacks += !setup->fallbacks.empty() && !setup->body.isEmpty();
            }
        }
    }
    // The generator must actually exercise both degenerate paths.
    EXPECT_GT(emptyBodies, 0);
    EXPECT_GT(parallelFallbacks, 0);
    EXPECT_GT(warped, 4000); // LiSPSM set-ups really warp (the others: empty B, near-parallel views)
}

TEST(ShadowSetupTest, FocusBodyContainsTheVisibleSceneAndEverythingBetweenItAndTheLight) {
    ConfigGenerator gen(7);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        const ShadowSetupInputs in = gen.next();
        const ConvexBody body = computeFocusBody(in.camera, in.light, in.wsSceneBounds);
        const Aabb box = sceneBoxForFocus(in.wsSceneBounds);
        const double eps = 1e-7 * (box.diagonal() + glm::length(box.center()) + 1.0);

        for (const Vec3& v : body.vertices()) ASSERT_TRUE(box.contains(v, eps)) << "B leaves the scene box, config " << i;
        for (int s = 0; s < 50; ++s) {
            const Vec3 receiver = pointInFrustum(in.camera, gen);
            if (!box.contains(receiver)) continue;
            ++checked;
            ASSERT_TRUE(body.contains(receiver, eps)) << "visible point outside B, config " << i;
            // A caster between the receiver and the sun, inside the scene, is in B too.
            const Vec3 caster = receiver + gen.uniform(0, box.diagonal()) * in.light.wsTowardsLight();
            if (box.contains(caster)) {
                ASSERT_TRUE(body.contains(caster, eps)) << "caster outside B, config " << i;
            }
        }
    }
    EXPECT_GT(checked, 5000);
}

TEST(ShadowSetupTest, FocusedIsTighterThanStandardForAViewInsideALargeScene) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-512, 0, -512), Vec3(512, 30, 512));
    in.camera.wsEye = Vec3(0, 2, 0);
    in.camera.zNear = 0.1;
    in.camera.zFar = 70;
    in.light = *DirectionalLight::fromSunAngles(45, 90);
    in.technique = Technique::Standard;
    const Mat4 standard = computeShadowSetup(in)->views[0].clipFromWorld;
    in.technique = Technique::Focused;
    const Mat4 focused = computeShadowSetup(in)->views[0].clipFromWorld;
    // Texels per metre along world X grows by the ratio of covered widths (≈ 1024 m vs ≈ 140 m).
    EXPECT_GT(std::abs(focused[0][0]) + std::abs(focused[0][1]),
              5.0 * (std::abs(standard[0][0]) + std::abs(standard[0][1])));
}

TEST(ShadowSetupTest, ViewAlongTheLightKeepsAWellDefinedFrame) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-100, 0, -100), Vec3(100, 20, 100));
    in.camera.wsEye = Vec3(0, 50, 0);
    in.camera.wsDirection = Vec3(0, -1, 0);
    in.camera.wsUp = Vec3(0, 0, -1);
    in.technique = Technique::Focused;
    for (const Vec3 l : {Vec3(0, -1, 0), Vec3(0, 1, 0)}) {
        in.light = DirectionalLight{l};
        const Result<ShadowSetup> setup = computeShadowSetup(in);
        ASSERT_TRUE(setup);
        EXPECT_TRUE(isFinite(setup->views[0].clipFromWorld));
        ASSERT_EQ(setup->fallbacks.size(), 1u);
        EXPECT_NE(setup->fallbacks[0].find("parallel"), std::string::npos);
    }
}

TEST(ShadowSetupTest, ViewMissingTheSceneFallsBackToTheSceneBox) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-10, 0, -10), Vec3(10, 5, 10));
    in.camera.wsEye = Vec3(0, 100, 0);
    in.camera.wsDirection = Vec3(0, 1, 0); // looking at the sky
    in.camera.wsUp = Vec3(0, 0, -1);
    in.light = *DirectionalLight::fromSunAngles(60, 10);
    const Result<ShadowSetup> setup = computeShadowSetup(in);
    ASSERT_TRUE(setup);
    EXPECT_TRUE(setup->body.isEmpty());
    ASSERT_EQ(setup->fallbacks.size(), 1u);
    for (const Vec3& c : in.wsSceneBounds.corners()) EXPECT_LE(outsideClipCube(setup->views[0].clipFromWorld, c), 1e-9);
}

TEST(ShadowSetupTest, BadInputsAreErrorsNotNaN) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(0), Vec3(1));
    in.camera.zNear = 10;
    in.camera.zFar = 1;
    EXPECT_FALSE(computeShadowSetup(in));
    in.camera.zFar = 100;
    in.wsSceneBounds = Aabb{};
    const auto r = computeShadowSetup(in);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.errorInfo().field, "scene_bounds");
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(0), Vec3(1));
    in.light.wsDirection = Vec3(NAN, 0, 0);
    EXPECT_FALSE(computeShadowSetup(in));
}

TEST(ShadowSetupTest, TechniqueNamesRoundTrip) {
    for (const TechniqueInfo& info : allTechniques()) EXPECT_EQ(parseTechnique(info.name), info.technique);
    EXPECT_FALSE(parseTechnique("lispsm-typo"));
}
