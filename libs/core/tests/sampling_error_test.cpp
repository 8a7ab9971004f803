// The sampling model (core/sampling_error.h): its Jacobians against finite differences of the
// projections themselves, closed forms for perspective and projection aliasing, the cascade a
// sample is served by, and the samples a depth read-back gives.
#include "setup_configs.h"

#include "shadowkit/core/sampling_error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit;
using namespace shadowkit::core;

namespace {

constexpr int kWidth = 640, kHeight = 360;

// Where the camera's pixel (x, y) (rows down) sees the plane through `p` with normal `n`.
Vec3 planePointAtPixel(const PerspectiveCamera& camera, Vec2 pixel, const Vec3& p, const Vec3& n) {
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5), tanX = tanY * camera.aspect;
    const Vec2 ndc(2.0 * pixel.x / kWidth - 1.0, 1.0 - 2.0 * pixel.y / kHeight);
    const Mat4 worldFromView = glm::inverse(camera.viewFromWorld());
    const Vec3 direction = Vec3(worldFromView * Vec4(ndc.x * tanX, ndc.y * tanY, -1.0, 0.0));
    const double t = glm::dot(n, p - camera.wsEye) / glm::dot(n, direction);
    return camera.wsEye + t * direction;
}

Vec2 project(const Mat4& clipFromWorld, const Vec3& ws) {
    const Vec4 c = clipFromWorld * Vec4(ws, 1.0);
    return Vec2(c) / c.w;
}

// Pixels per texel by central differences: step a pixel's width, find the surface point, see
// where the map puts it. Independent of the model's analytic derivatives.
double finiteDifferencePixelsPerTexel(const PerspectiveCamera& camera, const ShadowView& view, int mapSize,
                                      const Vec3& p, const Vec3& n) {
    const Vec2 ndc = project(camera.clipFromWorld(), p);
    const Vec2 pixel((ndc.x + 1.0) * 0.5 * kWidth, (1.0 - ndc.y) * 0.5 * kHeight);
    const double h = 1e-3;
    auto texelAt = [&](Vec2 px) {
        return (project(view.clipFromWorld, planePointAtPixel(camera, px, p, n)) * 0.5 + 0.5) * double(mapSize);
    };
    const Vec2 dx = (texelAt(pixel + Vec2(h, 0)) - texelAt(pixel - Vec2(h, 0))) / (2 * h);
    const Vec2 dy = (texelAt(pixel + Vec2(0, h)) - texelAt(pixel - Vec2(0, h))) / (2 * h);
    return pixelsPerTexel(glm::dmat2(dx, dy));
}

} // namespace

TEST(SamplingErrorTest, PixelsPerTexelIsTheLargestSingularValueOfTheInverseJacobian) {
    EXPECT_NEAR(pixelsPerTexel(glm::dmat2(1.0)), 1.0, 1e-12);
    EXPECT_NEAR(pixelsPerTexel(glm::dmat2(2.0)), 0.5, 1e-12);           // 2 texels per pixel
    EXPECT_NEAR(pixelsPerTexel(glm::dmat2(1, 0, 0, 0.25)), 4.0, 1e-12); // stretched along y
    const double c = std::cos(0.7), s = std::sin(0.7);
    EXPECT_NEAR(pixelsPerTexel(glm::dmat2(c, s, -s, c) * glm::dmat2(0.5, 0, 0, 3)), 2.0, 1e-12); // rotation-invariant
    EXPECT_TRUE(std::isinf(pixelsPerTexel(glm::dmat2(1, 1, 1, 1))));
}

TEST(SamplingErrorTest, PercentileIsTheElementAtTheFlooredIndex) {
    std::vector<double> v = {5, 1, 4, 2, 3, 10, 9, 8, 7, 6};
    EXPECT_EQ(percentileInPlace(v, 0.5), 6.0);   // index 5 of 1..10
    EXPECT_EQ(percentileInPlace(v, 0.95), 10.0); // index 9
    EXPECT_EQ(percentileInPlace(v, 1.0), 10.0);  // clamped
    EXPECT_EQ(percentileInPlace({}, 0.5), 0.0);
}

// Every technique on random configurations: the model's analytic Jacobian agrees with finite
// differences of the camera and map projections at the sample.
TEST(SamplingErrorTest, PredictionMatchesFiniteDifferencesForEveryTechnique) {
    core::testing::ConfigGenerator gen(2026);
    int compared = 0;
    for (int config = 0; config < 600; ++config) {
        ShadowSetupInputs in = gen.next();
        in.technique = allTechniques()[size_t(config) % allTechniques().size()].technique;
        in.camera.aspect = double(kWidth) / kHeight;
        auto setup = computeShadowSetup(in);
        if (!setup) continue;
        std::vector<ReceiverSample> samples;
        std::vector<Vec3> normals;
        for (int k = 0; k < 8; ++k) {
            const Vec3 p = core::testing::pointInFrustum(in.camera, gen);
            Vec3 n = gen.unitVector();
            const Vec3 toEye = glm::normalize(in.camera.wsEye - p);
            if (glm::dot(n, in.light.wsTowardsLight()) < 0.0) n = -n;
            if (std::abs(glm::dot(n, toEye)) < 0.1 || glm::dot(n, in.light.wsTowardsLight()) < 0.1) continue;
            samples.push_back({p, n});
        }
        auto model = SamplingErrorModel::create(in.camera, kWidth, kHeight, samples);
        ASSERT_TRUE(model) << model.error();
        ASSERT_EQ(model->size(), samples.size());
        std::vector<double> predicted(model->size());
        model->predict(*setup, predicted);
        const Vec3 forward = glm::normalize(in.camera.wsDirection);
        for (size_t i = 0; i < samples.size(); ++i) {
            const double depth = glm::dot(samples[i].wsPosition - in.camera.wsEye, forward);
            size_t map = 0;     // the cascade serving this depth: the first whose range ends beyond it
            if (setup->clipmap) // or the clipmap level that holds it
                map = size_t(
                    clipmapLevelHolding(*setup, depth, samples[i].wsPosition).value_or(int(setup->views.size()) - 1));
            while (map + 1 < setup->views.size() && setup->views[map].split && depth > setup->views[map].split->y)
                ++map;
            const ShadowView& view = setup->views[map];
            const Vec4 c = view.clipFromWorld * Vec4(samples[i].wsPosition, 1.0);
            if (!(std::abs(c.w) > 1e-6)) continue;
            const double reference = finiteDifferencePixelsPerTexel(in.camera, view, setup->mapSize,
                                                                    samples[i].wsPosition, samples[i].wsNormal);
            if (!std::isfinite(reference) || reference > 1e6 || reference < 1e-6) continue;
            EXPECT_NEAR(predicted[i], reference, 1e-3 * reference) // central differences in world units of 1e3 m
                << techniqueName(in.technique) << " config " << config << " sample " << i;
            ++compared;
        }
    }
    EXPECT_GT(compared, 2000);
}

// Wimmer et al. 2004 §4.1 in closed form: a camera h metres above the ground looking straight
// down sees 2 h tan(fov/2) / H metres per pixel at the image centre; an orthographic map of
// 2L metres over N texels spends 2L / N metres per texel across the light, and on the ground
// 1 / cos θ times that along the direction the sun is tilted by θ (projection aliasing).
TEST(SamplingErrorTest, PerspectiveAndProjectionAliasingInClosedForm) {
    PerspectiveCamera camera;
    camera.wsEye = Vec3(3.0, 10.0, -4.0);
    camera.wsDirection = Vec3(0.0, -1.0, 0.0);
    camera.wsUp = Vec3(0.0, 0.0, -1.0);
    camera.fovYDegrees = 60.0;
    camera.aspect = double(kWidth) / kHeight;
    camera.zNear = 0.1;
    camera.zFar = 100.0;
    const ReceiverSample below{Vec3(3.0, 0.0, -4.0), Vec3(0.0, 1.0, 0.0)};
    auto model = SamplingErrorModel::create(camera, kWidth, kHeight, std::span(&below, 1));
    ASSERT_TRUE(model);
    const double metresPerPixel = 2.0 * 10.0 * std::tan(glm::radians(30.0)) / kHeight;
    const double halfExtent = 50.0;
    for (const double tiltDegrees : {0.0, 30.0, 60.0, 80.0}) {
        const double theta = glm::radians(tiltDegrees);
        const Vec3 towardsLight(std::sin(theta), std::cos(theta), 0.0);
        ShadowSetup setup;
        setup.mapSize = 1000;
        ShadowView view;
        view.lightFromWorld = glm::lookAt(towardsLight * 100.0, Vec3(0.0), Vec3(0.0, 0.0, -1.0));
        view.clipFromLight = orthoZeroToOne(-halfExtent, halfExtent, -halfExtent, halfExtent, 1.0, 200.0);
        view.recomposeClip();
        setup.views.push_back(view);
        setEyeRelativeFromWorld(setup, camera.wsEye);
        const double metresPerTexel = 2.0 * halfExtent / setup.mapSize / std::cos(theta);
        const SamplingFigures f = model->figures(setup);
        EXPECT_NEAR(f.p50, metresPerTexel / metresPerPixel, 1e-9 * f.p50) << tiltDegrees << "°";
        EXPECT_EQ(f.undersampledFraction, 1.0);
    }
}

// Cascades: a sample is judged in the map whose split serves its view depth, as the shader
// picks it, and the figures say which map is finer where.
TEST(SamplingErrorTest, EachSampleIsServedByItsCascade) {
    PerspectiveCamera camera;
    camera.wsEye = Vec3(0.0, 2.0, 0.0);
    camera.wsDirection = Vec3(0.0, 0.0, -1.0);
    camera.aspect = double(kWidth) / kHeight;
    camera.zNear = 0.5;
    camera.zFar = 200.0;
    ShadowSetup setup;
    setup.technique = Technique::Csm;
    setup.mapSize = 1024;
    for (const double halfExtent : {10.0, 100.0}) {
        ShadowView view;
        view.lightFromWorld = glm::lookAt(Vec3(0.0, 100.0, 0.0), Vec3(0.0), Vec3(0.0, 0.0, -1.0));
        view.clipFromLight = orthoZeroToOne(-halfExtent, halfExtent, -halfExtent, halfExtent, 1.0, 200.0);
        view.recomposeClip();
        view.split = halfExtent < 50.0 ? Vec2(0.5, 20.0) : Vec2(20.0, 200.0);
        setup.views.push_back(view);
    }
    setEyeRelativeFromWorld(setup, camera.wsEye);
    const std::vector<ReceiverSample> samples = {{Vec3(0.0, 0.0, -19.0), Vec3(0.0, 1.0, 0.0)},
                                                 {Vec3(0.0, 0.0, -21.0), Vec3(0.0, 1.0, 0.0)}};
    auto model = SamplingErrorModel::create(camera, kWidth, kHeight, samples);
    ASSERT_TRUE(model);
    std::vector<double> ppt(2);
    model->predict(setup, ppt);
    // Each sample as the map that serves it alone would judge it: the near one in front of
    // the split at 20 m, the coarse one behind it.
    for (size_t map = 0; map < 2; ++map) {
        ShadowSetup single = setup;
        single.views.clear();
        single.views.push_back(setup.views[map]);
        single.views[0].split.reset();
        std::vector<double> alone(2);
        model->predict(single, alone);
        EXPECT_DOUBLE_EQ(ppt[map], alone[map]) << "map " << map;
    }
    EXPECT_GT(ppt[1] / ppt[0], 5.0); // ten times the metres per texel, against a little more footprint behind
}

// The search's shortcuts: objective() is samplingObjective(figures()) exactly, and a subsample
// keeps every k-th sample with the prediction it had in the whole model.
TEST(SamplingErrorTest, TheObjectiveAndASubsampleAgreeWithTheWholeModel) {
    core::testing::ConfigGenerator gen(7);
    int checked = 0;
    for (int config = 0; config < 60; ++config) {
        ShadowSetupInputs in = gen.next();
        in.technique = allTechniques()[size_t(config) % allTechniques().size()].technique;
        auto setup = computeShadowSetup(in);
        if (!setup) continue;
        std::vector<ReceiverSample> samples;
        for (int k = 0; k < 97; ++k)
            samples.push_back({core::testing::pointInFrustum(in.camera, gen), gen.unitVector()});
        auto model = SamplingErrorModel::create(in.camera, kWidth, kHeight, samples);
        ASSERT_TRUE(model);
        if (model->size() < 20) continue;
        EXPECT_EQ(model->objective(*setup), samplingObjective(model->figures(*setup))) << "config " << config;
        std::vector<double> whole(model->size());
        model->predict(*setup, whole);
        for (const size_t count : {size_t(1), size_t(10), model->size() - 1, model->size(), model->size() + 5}) {
            const SamplingErrorModel sub = model->subsampled(count);
            ASSERT_EQ(sub.size(), std::min(count, model->size()));
            std::vector<double> part(sub.size());
            sub.predict(*setup, part);
            for (size_t k = 0; k < sub.size(); ++k)
                ASSERT_EQ(part[k], whole[k * model->size() / sub.size()]) << "config " << config;
        }
        ++checked;
    }
    EXPECT_GT(checked, 30);
}

// A read-back of the ground plane y = 0 as `camera` sees it at width × height: view depth where
// a pixel's ray meets the ground (0 in the sky), every normal up.
RasterBuffers groundSeenBy(const PerspectiveCamera& camera, int width, int height) {
    RasterBuffers raster;
    raster.width = width;
    raster.height = height;
    const size_t n = size_t(width) * size_t(height);
    raster.viewDepth.assign(n, 0.0f);
    raster.wsNormal.assign(n, glm::vec3(0.0f, 1.0f, 0.0f));
    const Vec3 forward = glm::normalize(camera.wsDirection);
    const Mat4 worldFromView = glm::inverse(camera.viewFromWorld());
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double ndcX = 2.0 * (x + 0.5) / width - 1.0, ndcY = 1.0 - 2.0 * (y + 0.5) / height;
            const Vec3 d = Vec3(worldFromView * Vec4(ndcX * tanY * camera.aspect, ndcY * tanY, -1.0, 0.0));
            if (d.y >= 0.0) continue; // sky
            const double t = -camera.wsEye.y / d.y;
            raster.viewDepth[raster.index(x, y)] = float(t * glm::dot(d, forward));
        }
    return raster;
}

PerspectiveCamera groundCamera() {
    PerspectiveCamera camera;
    camera.wsEye = Vec3(5.0, 3.0, 7.0);
    camera.wsDirection = Vec3(0.3, -0.4, -1.0);
    camera.aspect = 2.0;
    return camera;
}

// The samples a depth and normal read-back gives lie on the surface it saw, face the light,
// and are spread evenly up to the number asked for.
TEST(SamplingErrorTest, ReceiverSamplesFromADepthReadBackLieOnTheSurface) {
    const PerspectiveCamera camera = groundCamera();
    RasterBuffers raster = groundSeenBy(camera, 64, 32);
    const Vec3 forward = glm::normalize(camera.wsDirection);
    size_t ground = 0;
    for (int y = 0; y < raster.height; ++y)
        for (int x = 0; x < raster.width; ++x) {
            if (!(raster.viewDepth[raster.index(x, y)] > 0.0f)) continue; // sky
            if (x % 2)
                raster.wsNormal[raster.index(x, y)] = glm::vec3(0.0f, -1.0f, 0.0f); // faces away from the sun
            else
                ++ground;
        }
    const auto sun = DirectionalLight::fromSunAngles(40.0, 10.0);
    ASSERT_TRUE(sun);
    const std::vector<ReceiverSample> all = receiverSamples(raster, camera, *sun, 100000);
    EXPECT_EQ(all.size(), ground);
    for (const ReceiverSample& s : all) {
        EXPECT_NEAR(s.wsPosition.y, 0.0, 1e-4 * glm::length(s.wsPosition - camera.wsEye));
        EXPECT_GT(glm::dot(s.wsNormal, sun->wsTowardsLight()), 0.0);
    }
    const std::vector<ReceiverSample> few = receiverSamples(raster, camera, *sun, 50);
    ASSERT_EQ(few.size(), 50u);
    // Evenly over the image: both halves of the rows are represented.
    const auto nearHalf = std::count_if(few.begin(), few.end(), [&](const ReceiverSample& s) {
        return glm::dot(s.wsPosition - camera.wsEye, forward) < 8.0;
    });
    EXPECT_GT(nearHalf, 5);
    EXPECT_LT(nearHalf, 45);
    EXPECT_TRUE(receiverSamples(raster, camera, *sun, 0).empty());
}

// A face along the sun's rays, its normal off by float rounding (N·L of a few 1e-7), is no
// receiver: eval neither scores nor lights it (core::facesLight), and the model must predict
// the pixels eval measures. Sampled, such a face has a texel stretched along it without bound —
// a glasshouse's walls, straight across the sun, once put `auto`'s predicted p95 at 3e5 pixels
// per texel where eval measured 0.8.
TEST(SamplingErrorTest, AFaceAlongTheSunsRaysIsNotAReceiver) {
    const PerspectiveCamera camera = groundCamera();
    RasterBuffers raster = groundSeenBy(camera, 64, 32);
    const auto sun = DirectionalLight::fromSunAngles(40.0, 10.0);
    ASSERT_TRUE(sun);
    const Vec3 towardsSun = sun->wsTowardsLight();
    // A wall's normal: across the sun (horizontal, at right angles to its azimuth), tilted
    // towards it by float rounding.
    const Vec3 across = glm::normalize(glm::cross(towardsSun, Vec3(0.0, 1.0, 0.0)));
    const glm::vec3 wall = glm::vec3(glm::normalize(across + 4e-7 * towardsSun));
    const double wallFacing = glm::dot(Vec3(wall), towardsSun);
    ASSERT_GT(wallFacing, 0.0);
    ASSERT_LT(wallFacing, kFacingCosine);
    size_t ground = 0;
    for (int y = 0; y < raster.height; ++y)
        for (int x = 0; x < raster.width; ++x) {
            if (!(raster.viewDepth[raster.index(x, y)] > 0.0f)) continue; // sky
            if (x % 3 == 0)
                raster.wsNormal[raster.index(x, y)] = wall;
            else
                ++ground;
        }
    const std::vector<ReceiverSample> samples = receiverSamples(raster, camera, *sun, 100000);
    EXPECT_EQ(samples.size(), ground);
    for (const ReceiverSample& s : samples) EXPECT_TRUE(facesLight(s.wsNormal, towardsSun));

    // What it would have cost: the wall's one sample predicted at thousands of pixels per texel.
    ShadowSetupInputs inputs;
    inputs.camera = camera;
    inputs.light = *sun;
    inputs.wsSceneBounds = Aabb::fromMinMax(Vec3(-40.0, -1.0, -60.0), Vec3(40.0, 4.0, 10.0));
    inputs.technique = Technique::Focused;
    const auto setup = computeShadowSetup(inputs);
    ASSERT_TRUE(setup) << setup.error();
    const ReceiverSample onTheWall{samples.front().wsPosition, Vec3(wall)};
    auto walled = SamplingErrorModel::create(camera, 1280, 640, std::span(&onTheWall, 1));
    ASSERT_TRUE(walled) << walled.error();
    EXPECT_GT(walled->figures(*setup).p50, 1000.0);
    auto model = SamplingErrorModel::create(camera, 1280, 640, samples);
    ASSERT_TRUE(model) << model.error();
    EXPECT_LT(model->figures(*setup).p95, 100.0);
}

TEST(SamplingErrorTest, BadInputsAreErrorsAndEmptySetsAreDefined) {
    PerspectiveCamera camera;
    EXPECT_FALSE(SamplingErrorModel::create(camera, 0, 100, {}));
    EXPECT_FALSE(SamplingErrorModel::create(camera, 100, -1, {}));
    camera.zFar = camera.zNear;
    EXPECT_FALSE(SamplingErrorModel::create(camera, 100, 100, {}));
    camera = PerspectiveCamera{};
    // A sample behind the eye and one with a zero normal are dropped; no samples, zero figures.
    const std::vector<ReceiverSample> samples = {{camera.wsEye + Vec3(0, 0, 5), Vec3(0, 1, 0)},
                                                 {Vec3(0, 0, -5), Vec3(0.0)}};
    auto model = SamplingErrorModel::create(camera, 100, 100, samples);
    ASSERT_TRUE(model);
    EXPECT_EQ(model->size(), 0u);
    EXPECT_FALSE(model->viewDepthRange());
    const SamplingFigures f = model->figures(ShadowSetup{});
    EXPECT_EQ(f.samples, 0u);
    EXPECT_EQ(f.p95, 0.0);
}
