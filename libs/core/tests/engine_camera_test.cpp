// A camera from an engine's matrices: the same set-ups as eye/direction/fov for the same
// frustum, every recognised projection contained, bad matrices named.
#include "setup_configs.h"
#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/shadow_setup.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <random>

using namespace shadowkit::core;

namespace {

struct Random : shadowkit::core::testing::RandomSource {
    Random() : RandomSource(20261123) {}
    PerspectiveCamera camera() {
        PerspectiveCamera c;
        c.wsEye = Vec3(uniform(-200, 200), uniform(1, 40), uniform(-200, 200));
        c.wsDirection = unit();
        c.wsUp = Vec3(0, 1, 0);
        if (glm::length(glm::cross(c.wsDirection, c.wsUp)) < 0.05) c.wsUp = Vec3(1, 0, 0);
        c.fovYDegrees = uniform(10, 120);
        c.aspect = uniform(0.5, 2.5);
        c.zNear = uniform(0.05, 2);
        c.zFar = c.zNear * uniform(20, 2000);
        return c;
    }
    ShadowSetupInputs inputs() {
        ShadowSetupInputs in;
        in.wsSceneBounds = Aabb::fromMinMax(Vec3(-300, 0, -300), Vec3(300, 30, 300));
        Vec3 l = unit();
        if (l.y > 0) l.y = -l.y;
        in.light = DirectionalLight{l};
        in.cascades.warp = CascadeWarp::Lispsm;
        return in;
    }
};

// Every entry of b within `relative` of a, relative to a's largest entry.
void expectNear(const Mat4& a, const Mat4& b, double relative, const std::string& what) {
    double largest = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) largest = std::max(largest, std::abs(a[c][r]));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            ASSERT_NEAR(a[c][r], b[c][r], relative * largest) << what << " [" << c << "][" << r << "]";
}

// Every point of the set-up's focus body inside each view's clip volume (x, y in [-1, 1],
// depth in [0, 1], in front of the projection centre).
void expectContained(const ShadowSetup& setup, const std::string& what) {
    ASSERT_FALSE(setup.views.empty()) << what;
    for (const ShadowView& view : setup.views) {
        ASSERT_TRUE(isFinite(view.clipFromWorld)) << what;
        if (view.split) continue; // a cascade holds its own split's body, tested in cascades_test
        for (const Vec3& p : setup.body.vertices()) {
            const Vec4 c = view.clipFromWorld * Vec4(p, 1.0);
            ASSERT_GT(c.w, 0.0) << what;
            const Vec3 ndc = Vec3(c) / c.w;
            EXPECT_LE(std::max(std::abs(ndc.x), std::abs(ndc.y)), 1.0 + 1e-6) << what;
            EXPECT_GE(ndc.z, -1e-6) << what;
            EXPECT_LE(ndc.z, 1.0 + 1e-6) << what;
        }
    }
}

// Every technique's set-up for these inputs is computed and contained.
void expectEveryTechniqueContained(ShadowSetupInputs in, const std::string& what) {
    for (const TechniqueInfo& info : allTechniques()) {
        in.technique = info.technique;
        const Result<ShadowSetup> setup = computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        expectContained(*setup, std::string(info.name) + what);
    }
}

// The engine frustum's eight corners: NDC cube corners through the inverse of clip ∘ view.
std::vector<Vec3> engineCorners(const EngineCamera& e, double nearNdc, double farNdc) {
    const Mat4 worldFromClip = glm::inverse(e.clipFromView * e.viewFromWorld);
    std::vector<Vec3> corners;
    for (double z : {nearNdc, farNdc})
        for (double y : {-1.0, 1.0})
            for (double x : {-1.0, 1.0}) {
                const Vec4 p = worldFromClip * Vec4(x, y, z, 1.0);
                corners.push_back(Vec3(p) / p.w);
            }
    return corners;
}

// Largest signed distance of the points outside the camera's frustum planes (all six, or the
// four sides), relative to the frustum's far distance (<= 0: all inside).
double outsideFrustum(const PerspectiveCamera& camera, const std::vector<Vec3>& points, bool sidesOnly = false) {
    const auto planes = camera.wsFrustumPlanes();
    double worst = -INFINITY;
    for (size_t i = sidesOnly ? 2 : 0; i < planes.size(); ++i)
        for (const Vec3& p : points) worst = std::max(worst, planes[i].signedDistance(p) / camera.zFar);
    return worst;
}

} // namespace

TEST(EngineCameraTest, SymmetricPerspectiveGivesTheSameSetupsAsEyeDirectionAndFov) {
    Random random;
    for (int i = 0; i < 200; ++i) {
        const PerspectiveCamera camera = random.camera();
        ShadowSetupInputs in = random.inputs();
        for (ClipDepthRange range : {ClipDepthRange::ZeroToOne, ClipDepthRange::MinusOneToOne}) {
            EngineCamera engine;
            engine.viewFromWorld = camera.viewFromWorld();
            engine.clipDepth = range;
            engine.clipFromView =
                range == ClipDepthRange::ZeroToOne
                    ? camera.clipFromView()
                    : glm::perspectiveRH_NO(glm::radians(camera.fovYDegrees), camera.aspect, camera.zNear, camera.zFar);
            const Result<PerspectiveCamera> fromMatrices = cameraFromMatrices(engine);
            ASSERT_TRUE(fromMatrices) << fromMatrices.error();
            EXPECT_NEAR(fromMatrices->fovYDegrees, camera.fovYDegrees, 1e-9 * camera.fovYDegrees);
            EXPECT_NEAR(fromMatrices->zNear, camera.zNear, 1e-9 * camera.zNear);
            EXPECT_NEAR(fromMatrices->zFar, camera.zFar, 1e-9 * camera.zFar);
            for (const TechniqueInfo& info : allTechniques()) {
                in.technique = info.technique;
                in.camera = camera;
                const Result<ShadowSetup> expected = computeShadowSetup(in);
                in.camera = *fromMatrices;
                const Result<ShadowSetup> actual = computeShadowSetup(in);
                ASSERT_TRUE(expected && actual);
                ASSERT_EQ(expected->views.size(), actual->views.size());
                for (size_t v = 0; v < expected->views.size(); ++v)
                    expectNear(expected->views[v].clipFromWorld, actual->views[v].clipFromWorld, 1e-9,
                               std::string(info.name) + " config " + std::to_string(i));
            }
        }
    }
}

TEST(EngineCameraTest, LeftHandedDirect3DMatricesGiveTheSameCamera) {
    Random random;
    for (int i = 0; i < 50; ++i) {
        const PerspectiveCamera camera = random.camera();
        EngineCamera engine;
        engine.viewFromWorld = glm::lookAtLH(camera.wsEye, camera.wsEye + camera.wsDirection, camera.wsUp);
        engine.clipFromView =
            glm::perspectiveLH_ZO(glm::radians(camera.fovYDegrees), camera.aspect, camera.zNear, camera.zFar);
        const Result<PerspectiveCamera> c = cameraFromMatrices(engine);
        ASSERT_TRUE(c) << c.error();
        EXPECT_LT(glm::distance(c->wsEye, camera.wsEye), 1e-9 * glm::length(camera.wsEye) + 1e-12);
        EXPECT_LT(glm::distance(glm::normalize(c->wsDirection), glm::normalize(camera.wsDirection)), 1e-9);
        EXPECT_NEAR(c->fovYDegrees, camera.fovYDegrees, 1e-9 * camera.fovYDegrees);
        EXPECT_NEAR(c->aspect, camera.aspect, 1e-9 * camera.aspect);
    }
}

TEST(EngineCameraTest, ReversedZAndInfiniteFarAreRecognisedAndGiveContainedSetups) {
    Random random;
    for (int i = 0; i < 100; ++i) {
        const PerspectiveCamera camera = random.camera();
        const double f = 1.0 / std::tan(0.5 * glm::radians(camera.fovYDegrees)), n = camera.zNear;
        // Reversed infinite [0, 1] (the float-precision favourite): clip z = n, w = -z, so depth
        // n / d is 1 at the near plane and tends to 0.
        Mat4 reversedInfinite(0.0);
        reversedInfinite[0][0] = f / camera.aspect;
        reversedInfinite[1][1] = f;
        reversedInfinite[2][3] = -1.0;
        reversedInfinite[3][2] = n;
        const Result<RecognisedProjection> p = recogniseProjection(reversedInfinite, ClipDepthRange::ZeroToOne);
        ASSERT_TRUE(p) << p.error();
        EXPECT_TRUE(p->reversedZ && p->infiniteFar && !p->orthographic && !p->offCentre);
        EXPECT_NEAR(p->zNear, n, 1e-12 * n);

        EngineCamera engine{camera.viewFromWorld(), reversedInfinite};
        const Result<PerspectiveCamera> noDistance = cameraFromMatrices(engine);
        ASSERT_FALSE(noDistance);
        EXPECT_EQ(noDistance.errorInfo().field, "camera.shadow_distance");
        engine.shadowDistance = camera.zFar;
        const Result<PerspectiveCamera> c = cameraFromMatrices(engine);
        ASSERT_TRUE(c) << c.error();
        EXPECT_DOUBLE_EQ(c->zFar, camera.zFar);

        // Reversed with a finite far plane, [-1, 1]: far recognised.
        Mat4 reversedFinite =
            glm::perspectiveRH_NO(glm::radians(camera.fovYDegrees), camera.aspect, camera.zFar, camera.zNear);
        const Result<RecognisedProjection> q = recogniseProjection(reversedFinite, ClipDepthRange::MinusOneToOne);
        ASSERT_TRUE(q) << q.error();
        EXPECT_TRUE(q->reversedZ && !q->infiniteFar);
        EXPECT_NEAR(q->zNear, camera.zNear, 1e-9 * camera.zNear);
        EXPECT_NEAR(q->zFar, camera.zFar, 1e-9 * camera.zFar);

        ShadowSetupInputs in = random.inputs();
        in.camera = *c;
        expectEveryTechniqueContained(in, " config " + std::to_string(i));
    }
}

TEST(EngineCameraTest, ShadowDistanceLimitsTheFrustumOnlyWhenNearer) {
    const PerspectiveCamera camera;
    EngineCamera engine{camera.viewFromWorld(), camera.clipFromView()};
    engine.shadowDistance = 80.0;
    EXPECT_DOUBLE_EQ(cameraFromMatrices(engine)->zFar, 80.0);
    engine.shadowDistance = 5000.0; // beyond the far plane: the far plane stays
    EXPECT_NEAR(cameraFromMatrices(engine)->zFar, camera.zFar, 1e-9 * camera.zFar);
    engine.shadowDistance = 0.1; // before the near plane
    EXPECT_EQ(cameraFromMatrices(engine).errorInfo().field, "camera.shadow_distance");
}

TEST(EngineCameraTest, OffCentreAndJitteredFrustumsAreEnclosedTightly) {
    Random random;
    for (int i = 0; i < 200; ++i) {
        const PerspectiveCamera camera = random.camera();
        EngineCamera engine{camera.viewFromWorld(), {}};
        if (i % 2 == 0) {
            // Off-centre (a tile of a larger image, a stereo eye): glm::frustum with [0, 1] depth.
            const double l = random.uniform(-1, 0.2), r = l + random.uniform(0.2, 1.5);
            const double b = random.uniform(-1, 0.2), t = b + random.uniform(0.2, 1.5);
            engine.clipFromView = glm::frustumRH_ZO(l * camera.zNear, r * camera.zNear, b * camera.zNear,
                                                    t * camera.zNear, camera.zNear, camera.zFar);
        } else {
            // A TAA jitter of up to a pixel of a 1280 × 720 image.
            engine.clipFromView = camera.clipFromView();
            engine.clipFromView[2][0] += random.uniform(-1, 1) / 1280.0;
            engine.clipFromView[2][1] += random.uniform(-1, 1) / 720.0;
        }
        const Result<RecognisedProjection> p = recogniseProjection(engine.clipFromView, ClipDepthRange::ZeroToOne);
        ASSERT_TRUE(p) << p.error();
        EXPECT_TRUE(p->offCentre);
        const Result<PerspectiveCamera> c = cameraFromMatrices(engine);
        ASSERT_TRUE(c) << c.error();
        const std::vector<Vec3> corners = engineCorners(engine, 0.0, 1.0);
        EXPECT_LE(outsideFrustum(*c, corners), 1e-9) << "config " << i; // every corner inside ...
        EXPECT_GE(outsideFrustum(*c, corners, true), -1e-9)
            << "config " << i; // ... one on a side: no wider than needed
    }
}

TEST(EngineCameraTest, OrthographicViewsAreEnclosedWithTheStatedOverscan) {
    Random random;
    for (int i = 0; i < 100; ++i) {
        const PerspectiveCamera look = random.camera();
        const bool leftHanded = i % 2 == 1;
        EngineCamera engine;
        const double l = random.uniform(-80, 0), r = l + random.uniform(5, 100);
        const double b = random.uniform(-80, 0), t = b + random.uniform(5, 100);
        const double n = random.uniform(-10, 5), f = n + random.uniform(20, 400);
        engine.viewFromWorld =
            leftHanded ? glm::lookAtLH(look.wsEye, look.wsEye + look.wsDirection, look.wsUp) : look.viewFromWorld();
        engine.clipFromView = leftHanded ? glm::orthoLH_ZO(l, r, b, t, n, f) : glm::orthoRH_ZO(l, r, b, t, n, f);
        engine.handedness = leftHanded ? ViewHandedness::LeftHanded : ViewHandedness::RightHanded;
        const Result<PerspectiveCamera> c = cameraFromMatrices(engine);
        ASSERT_TRUE(c) << c.error();
        EXPECT_LE(outsideFrustum(*c, engineCorners(engine, 0.0, 1.0)), 1e-9) << "config " << i;
        EXPECT_LE(c->zFar / c->zNear, 1.0 + kOrthographicOverscan + 1e-12);
        EXPECT_LT(glm::distance(glm::normalize(c->wsDirection), glm::normalize(look.wsDirection)), 1e-9);

        ShadowSetupInputs in = random.inputs();
        in.camera = *c;
        expectEveryTechniqueContained(in, " ortho config " + std::to_string(i));
    }
}

TEST(EngineCameraTest, AFloatEnginesRotationIsRigidAndAScaleIsNot) {
    // Engines with float matrices (OGRE's Real): a view built in float from a float quaternion,
    // as such an engine builds it, is a rigid view; a scale of 1.0001 is not.
    std::mt19937 rng(7);
    std::normal_distribution<float> n;
    int accepted = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::quat q = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
        glm::mat4 viewF = glm::mat4_cast(q);
        viewF[3] = glm::vec4(300.0f * n(rng), 40.0f * n(rng), 300.0f * n(rng), 1.0f);
        const Mat4 view(viewF);
        const PerspectiveCamera camera;
        accepted += cameraFromMatrices({view, camera.clipFromView()}).hasValue();
        if (i == 0) {
            const Result<PerspectiveCamera> scaled =
                cameraFromMatrices({glm::scale(view, Vec3(1.0001)), camera.clipFromView()});
            ASSERT_FALSE(scaled);
            EXPECT_EQ(scaled.errorInfo().field, "camera.view_from_world");
        }
    }
    EXPECT_EQ(accepted, 2000);
}

TEST(EngineCameraTest, BadMatricesAreNamedErrors) {
    const PerspectiveCamera camera;
    const Mat4 view = camera.viewFromWorld(), projection = camera.clipFromView();
    auto field = [](const EngineCamera& e) {
        const Result<PerspectiveCamera> c = cameraFromMatrices(e);
        return c ? std::string("accepted") : c.errorInfo().field;
    };
    Mat4 nan = projection;
    nan[1][1] = NAN;
    EXPECT_EQ(field({view, nan}), "camera.clip_from_view");
    EXPECT_EQ(field({glm::scale(view, Vec3(2.0)), projection}), "camera.view_from_world");
    Mat4 wFromX = projection;
    wFromX[0][3] = 0.3; // w depends on x: not a pinhole projection
    EXPECT_EQ(field({view, wFromX}), "camera.clip_from_view");
    Mat4 oblique = projection;
    oblique[0][2] = 0.2; // an oblique near plane
    EXPECT_EQ(field({view, oblique}), "camera.clip_from_view");
    EXPECT_EQ(field({view, Mat4(0.0)}), "camera.clip_from_view");
    EXPECT_EQ(field({view, projection}), "accepted");
}
