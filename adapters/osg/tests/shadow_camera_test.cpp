// The OSG adapter's shadow camera, as VDSM holds it, against shadowkit::core's own set-up:
// the conventions (OSG's row-vector matrices, OpenGL's clip depth, v = 0 at the bottom) must
// be converted so that every point of the focus body lands on the same texel and depth.
#include "shadowkit/osg/shadow_map.h"

#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/output_conventions.h"

#include <glm/gtc/type_ptr.hpp>

#include <gtest/gtest.h>
#include <osg/Light>
#include <osg/Viewport>
#include <osgShadow/ShadowedScene>
#include <osgUtil/CullVisitor>

#include <cmath>
#include <optional>
#include <random>

namespace {

namespace core = shadowkit::core;
using shadowkit::osgadapter::ShadowMap;

const ::osg::BoundingBoxd kForestBox({-512.0, -4.0, -512.0}, {512.0, 50.0, 512.0});

// The call VDSM makes each frame, made as VDSM makes it: a Frustum read from a cull visitor
// holding the camera's matrices, and the light's data from an osg::Light.
struct VdsmCall {
    ::osg::Matrixd view, projection;
    ::osg::Vec3d wsLightDirection; ///< the direction VDSM's LightData holds (float-rounded by osg::Light)
    bool ok = false;
};

VdsmCall callAsVdsm(ShadowMap& shadowMap, const ::osg::Matrixd& cameraView, const ::osg::Matrixd& cameraProjection,
                    const ::osg::Vec3d& wsLightTravel) {
    ::osg::ref_ptr<osgUtil::CullVisitor> cv = new osgUtil::CullVisitor;
    cv->setComputeNearFarMode(::osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cv->pushViewport(new ::osg::Viewport(0, 0, 1280, 720));
    cv->pushProjectionMatrix(new ::osg::RefMatrix(cameraProjection));
    cv->pushModelViewMatrix(new ::osg::RefMatrix(cameraView), ::osg::Transform::ABSOLUTE_RF);
    ShadowMap::Frustum frustum(cv.get(), 0.0, 1e30);
    ::osg::ref_ptr<::osg::Light> light = new ::osg::Light;
    light->setPosition(::osg::Vec4(-wsLightTravel, 0.0)); // OSG: towards the light, w = 0
    ::osg::ref_ptr<ShadowMap::LightData> lightData = new ShadowMap::LightData(nullptr);
    lightData->setLightData(nullptr, light.get(), ::osg::Matrixd::identity());
    VdsmCall call;
    call.wsLightDirection = lightData->lightDir;
    call.ok = shadowMap.computeShadowCameraSettings(frustum, *lightData, call.projection, call.view);
    return call;
}

// OSG's row-vector matrix as the column-vector matrix it lies in memory as.
core::Mat4 toCore(const ::osg::Matrixd& m) { return glm::make_mat4(m.ptr()); }

// The same call for a positional light: a spot (cutoff < 90°, the half-angle) or a point light.
VdsmCall callAsVdsm(osgShadow::ViewDependentShadowMap& shadowMap, const ::osg::Matrixd& cameraView,
                    const ::osg::Matrixd& cameraProjection, const ::osg::Light& light) {
    ::osg::ref_ptr<osgUtil::CullVisitor> cv = new osgUtil::CullVisitor;
    cv->setComputeNearFarMode(::osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cv->pushViewport(new ::osg::Viewport(0, 0, 1280, 720));
    cv->pushProjectionMatrix(new ::osg::RefMatrix(cameraProjection));
    cv->pushModelViewMatrix(new ::osg::RefMatrix(cameraView), ::osg::Transform::ABSOLUTE_RF);
    osgShadow::ViewDependentShadowMap::Frustum frustum(cv.get(), 0.0, 1e30);
    ::osg::ref_ptr<osgShadow::ViewDependentShadowMap::LightData> lightData =
        new osgShadow::ViewDependentShadowMap::LightData(nullptr);
    lightData->setLightData(nullptr, &light, ::osg::Matrixd::identity());
    VdsmCall call;
    call.ok = shadowMap.computeShadowCameraSettings(frustum, *lightData, call.projection, call.view);
    return call;
}

::osg::ref_ptr<::osg::Light> spotLight(const core::Vec3& wsPosition, const core::Vec3& wsDirection, double cutoff) {
    ::osg::ref_ptr<::osg::Light> light = new ::osg::Light;
    light->setPosition(::osg::Vec4(float(wsPosition.x), float(wsPosition.y), float(wsPosition.z), 1.0f));
    light->setDirection(::osg::Vec3(float(wsDirection.x), float(wsDirection.y), float(wsDirection.z)));
    light->setSpotCutoff(float(cutoff));
    return light;
}

core::Vec3 unitVector(std::mt19937& rng) {
    std::normal_distribution<double> n;
    core::Vec3 v(n(rng), n(rng), n(rng));
    return glm::normalize(v);
}

TEST(OsgShadowCamera, MapsTheFocusBodyToTheCoresTexelsForRandomCamerasAndSuns) {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const core::Technique techniques[] = {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Psm,
                                          core::Technique::Focused, core::Technique::Standard};
    int compared = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const core::Technique technique = techniques[trial % 5];
        const core::Vec3 wsEye(-300.0 + 600.0 * u(rng), 2.0 + 40.0 * u(rng), -300.0 + 600.0 * u(rng));
        core::Vec3 forward = unitVector(rng);
        if (std::abs(forward.y) > 0.95) forward = glm::normalize(core::Vec3(1.0, forward.y, 0.0));
        core::Vec3 sunTravel = unitVector(rng);
        sunTravel.y = -0.2 - 0.8 * std::abs(sunTravel.y); // above the horizon
        const double fovY = 40.0 + 40.0 * u(rng), aspect = 1.0 + u(rng), zNear = 0.3 + u(rng),
                     zFar = 200.0 + 400.0 * u(rng);
        const ::osg::Matrixd cameraView = ::osg::Matrixd::lookAt(
            ::osg::Vec3d(wsEye.x, wsEye.y, wsEye.z),
            ::osg::Vec3d(wsEye.x + forward.x, wsEye.y + forward.y, wsEye.z + forward.z), ::osg::Vec3d(0, 1, 0));
        const ::osg::Matrixd cameraProjection = ::osg::Matrixd::perspective(fovY, aspect, zNear, zFar);

        ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap;
        core::ShadowSetupInputs options;
        options.technique = technique;
        options.mapSize = 2048;
        shadowMap->setInputs(options);
        shadowMap->setSceneBounds(kForestBox);
        const VdsmCall call =
            callAsVdsm(*shadowMap, cameraView, cameraProjection, {sunTravel.x, sunTravel.y, sunTravel.z});
        ASSERT_TRUE(call.ok) << shadowMap->lastError();
        // The core's own set-up for the same camera and light, in OpenGL's conventions.
        core::ShadowSetupInputs in;
        in.technique = technique;
        in.mapSize = 2048;
        in.depthLayout = core::DepthLayout::Hyperbolic;
        // The camera as the engine holds it, read by the core's own reader of engine matrices
        // (tested against eye/direction set-ups in engine_camera_test.cpp): what is compared
        // here is the conversion to and from OSG's conventions alone.
        in.camera = core::cameraFromMatrices({glm::make_mat4(cameraView.ptr()), glm::make_mat4(cameraProjection.ptr()),
                                              core::ClipDepthRange::MinusOneToOne})
                        .value();
        // The light as OSG holds it: osg::Light keeps its position in float.
        in.light = core::DirectionalLight::fromDirection(
                       {call.wsLightDirection.x(), call.wsLightDirection.y(), call.wsLightDirection.z()})
                       .value();
        in.wsSceneBounds = core::Aabb::fromMinMax(core::Vec3(-512, -4, -512), core::Vec3(512, 50, 512));
        auto setup = core::computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        // The focus body's corners; `standard` has none and maps the scene box.
        core::ConvexBody::Points points = setup->body.vertices();
        if (points.empty())
            for (int corner = 0; corner < 8; ++corner)
                points.push_back(core::Vec3(corner & 1 ? kForestBox.xMax() : kForestBox.xMin(),
                                            corner & 2 ? kForestBox.yMax() : kForestBox.yMin(),
                                            corner & 4 ? kForestBox.zMax() : kForestBox.zMin()));
        if (points.empty()) continue; // the view missed the scene
        const core::EngineShadowView expected =
            core::toEngineView(setup->views[0], *setup, core::OutputConventions::openGL());

        for (const core::Vec3& p : points) {
            // OSG: the point through view · projection (row vectors, divided by w), then
            // OpenGL's viewport and depth range, as VDSM's texgen bias does.
            const ::osg::Vec3d ndc = ::osg::Vec3d(p.x, p.y, p.z) * call.view * call.projection;
            const core::Vec4 t = expected.textureFromWorld * core::Vec4(p, 1.0);
            const double texels = in.mapSize;
            EXPECT_NEAR((0.5 * ndc.x() + 0.5) * texels, t.x / t.w * texels, 1e-4) << core::techniqueName(technique);
            EXPECT_NEAR((0.5 * ndc.y() + 0.5) * texels, t.y / t.w * texels, 1e-4) << core::techniqueName(technique);
            EXPECT_NEAR(0.5 * ndc.z() + 0.5, t.z / t.w, 1e-7) << core::techniqueName(technique);
        }
        // The view matrix is the light's rigid frame: OSG culls casters in its light space.
        for (int r = 0; r < 3; ++r) {
            const ::osg::Vec3d axis(call.view(0, r), call.view(1, r), call.view(2, r));
            EXPECT_NEAR(axis.length(), 1.0, 1e-9);
        }
        ++compared;
    }
    EXPECT_GE(compared, 55);
}

TEST(OsgShadowCamera, StaysFiniteWithTheSunAlongTheViewDirection) {
    // The case engines' own LiSPSM meets with NaN matrices: the view looking straight along
    // the light (and straight against it).
    for (const double sign : {1.0, -1.0}) {
        for (const core::Technique technique : {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Psm,
                                                core::Technique::Focused, core::Technique::Standard}) {
            const ::osg::Vec3d travel = ::osg::Vec3d(0.3, -1.0, 0.2) / ::osg::Vec3d(0.3, -1.0, 0.2).length();
            const ::osg::Vec3d eye(10.0, 120.0, -20.0);
            const ::osg::Matrixd cameraView = ::osg::Matrixd::lookAt(eye, eye + travel * sign, {0.0, 0.0, 1.0});
            ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap;
            core::ShadowSetupInputs options;
            options.technique = technique;
            shadowMap->setInputs(options);
            shadowMap->setSceneBounds(kForestBox);
            const VdsmCall call =
                callAsVdsm(*shadowMap, cameraView, ::osg::Matrixd::perspective(60.0, 1.5, 0.5, 500.0), travel);
            ASSERT_TRUE(call.ok) << shadowMap->lastError();
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) {
                    EXPECT_TRUE(std::isfinite(call.view(r, c))) << core::techniqueName(technique);
                    EXPECT_TRUE(std::isfinite(call.projection(r, c))) << core::techniqueName(technique);
                }
            // The ground under the eye is on the map.
            const ::osg::Vec3d ground = ::osg::Vec3d(eye.x(), 0.0, eye.z()) * call.view * call.projection;
            EXPECT_LE(std::abs(ground.x()), 1.0) << core::techniqueName(technique) << " sign " << sign;
            EXPECT_LE(std::abs(ground.y()), 1.0) << core::techniqueName(technique) << " sign " << sign;
        }
    }
}

TEST(OsgShadowCamera, AutoChoosesForTheReceiversItIsHandedAsTheCoreWould) {
    // `auto` inside OSG: without receivers the recommended technique; with them, what the core's
    // own chooser picks for the same camera, sun, box and receivers, and that choice's camera.
    const ::osg::Matrixd view =
        ::osg::Matrixd::lookAt(::osg::Vec3d(0, 8, 0), ::osg::Vec3d(0, 7.75, -1), ::osg::Vec3d(0, 1, 0));
    const ::osg::Matrixd projection = ::osg::Matrixd::perspective(60.0, 16.0 / 9.0, 0.5, 400.0);
    const ::osg::Vec3d sunTravel(0.6, -0.5, 0.2);
    core::AutoOptions options;
    options.cascades = 1;
    ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap;
    shadowMap->setSceneBounds(kForestBox);
    ASSERT_TRUE(shadowMap->setAuto(options));
    ASSERT_TRUE(callAsVdsm(*shadowMap, view, projection, sunTravel).ok) << shadowMap->lastError();
    ASSERT_TRUE(shadowMap->lastChoice());
    EXPECT_EQ(shadowMap->lastChoice()->inputs.technique, core::defaultTechnique());

    // The ground the camera looks at, 2 to 300 m ahead and 40 m to each side, facing up.
    std::vector<core::ReceiverSample> receivers;
    for (double z = 2.0; z < 300.0; z *= 1.08)
        for (double x = -40.0; x <= 40.0; x += 4.0) receivers.push_back({core::Vec3(x, 0.0, -z), core::Vec3(0, 1, 0)});
    ::osg::ref_ptr<ShadowMap> fresh = new ShadowMap; // no history, as the reference's
    fresh->setSceneBounds(kForestBox);
    ASSERT_TRUE(fresh->setAuto(options));
    fresh->setReceivers(receivers, 320, 180);
    const VdsmCall call = callAsVdsm(*fresh, view, projection, sunTravel);
    ASSERT_TRUE(call.ok) << fresh->lastError();
    ASSERT_TRUE(fresh->lastChoice());
    EXPECT_GT(fresh->lastChoice()->predicted.samples, 0u); // judged by the receivers

    core::ShadowSetupInputs base;
    base.mapSize = 2048; // ShadowSettings' default texture size, as VDSM hands it
    const auto inputs =
        shadowkit::osgadapter::inputsFor(view, projection, INFINITY, call.wsLightDirection, kForestBox, base);
    ASSERT_TRUE(inputs) << inputs.error();
    core::AutoChooser reference(options);
    const auto choice = reference.choose(*inputs, 320, 180, receivers);
    ASSERT_TRUE(choice) << choice.error();
    EXPECT_EQ(fresh->lastChoice()->inputs.technique, choice->inputs.technique);
    core::ShadowSetupInputs chosen = choice->inputs;
    chosen.depthLayout = core::DepthLayout::Hyperbolic;
    const auto expected = shadowkit::osgadapter::shadowCameraOf(chosen);
    ASSERT_TRUE(expected) << expected.error();
    for (const ::osg::Vec3d p : {::osg::Vec3d(0, 0, -10), ::osg::Vec3d(20, 0, -150), ::osg::Vec3d(-30, 10, -60)}) {
        const ::osg::Vec3d got = p * call.view * call.projection;
        const ::osg::Vec3d want = p * expected->viewMatrix * expected->projectionMatrix;
        EXPECT_NEAR(got.x() * 1024.0, want.x() * 1024.0, 1e-4) << core::techniqueName(choice->inputs.technique);
        EXPECT_NEAR(got.y() * 1024.0, want.y() * 1024.0, 1e-4);
        EXPECT_NEAR(got.z(), want.z(), 1e-7);
    }

    core::AutoOptions cascades;
    cascades.cascades = 4;
    const core::Status refused = fresh->setAuto(cascades);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("auto.cascades"), std::string::npos) << refused.error();
    EXPECT_EQ(refused.error().find('\n'), std::string::npos);
}

// A world point through the adapter's shadow camera (clipFromWorld, as OSG draws the map) lands
// inside the map, in texture coordinates, on the core's own texel for it (gl: the core's set-up
// in OpenGL's conventions), its depth at most the map's far end.
void expectInTheMapOnTheCoresTexel(const core::Mat4& clipFromWorld, const core::EngineShadowView& gl,
                                   const core::Vec3& p) {
    const core::Vec4 m = clipFromWorld * core::Vec4(p, 1.0);
    ASSERT_GT(m.w, 0.0);
    const core::Vec3 texel(0.5 * m.x / m.w + 0.5, 0.5 * m.y / m.w + 0.5, 0.5 * m.z / m.w + 0.5);
    const core::Vec4 t = gl.textureFromWorld * core::Vec4(p, 1.0);
    EXPECT_NEAR(texel.x, t.x / t.w, 1e-7);
    EXPECT_NEAR(texel.y, t.y / t.w, 1e-7);
    EXPECT_GE(texel.x, -1e-9);
    EXPECT_LE(texel.x, 1.0 + 1e-9);
    EXPECT_GE(texel.y, -1e-9);
    EXPECT_LE(texel.y, 1.0 + 1e-9);
    EXPECT_LE(texel.z, 1.0);
}

TEST(OsgShadowCamera, SpotLightMapsHoldWhatTheCameraSeesOfTheConeInTheCoresTexels) {
    // Lamps over a yard, cameras among them. Every point the camera sees inside a lamp's cone
    // within the scene box — found by sampling, not from the set-up — must land in the spot map
    // (texel in [0, N], depth in [0, 1]) on the core's texel, and the map must spend at least
    // the texels per metre OSG's own spot camera spends (the whole cone, 2 × the cutoff): it is
    // the cone, or the part of it the camera sees.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const ::osg::BoundingBoxd box({-60.0, 0.0, -60.0}, {60.0, 20.0, 60.0});
    int maps = 0, narrowed = 0, seenInMaps = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const core::Vec3 wsLamp(-30.0 + 60.0 * u(rng), 3.0 + 12.0 * u(rng), -30.0 + 60.0 * u(rng));
        core::Vec3 aim = unitVector(rng);
        aim.y = -0.3 - std::abs(aim.y);
        aim = glm::normalize(aim);
        const double cutoff = 10.0 + 50.0 * u(rng);
        const core::Vec3 wsEye(-40.0 + 80.0 * u(rng), 1.7 + 10.0 * u(rng), -40.0 + 80.0 * u(rng));
        core::Vec3 forward = unitVector(rng);
        forward.y = -0.1 - 0.4 * std::abs(forward.y);
        forward = glm::normalize(forward);
        const ::osg::Matrixd view = ::osg::Matrixd::lookAt(
            ::osg::Vec3d(wsEye.x, wsEye.y, wsEye.z),
            ::osg::Vec3d(wsEye.x + forward.x, wsEye.y + forward.y, wsEye.z + forward.z), ::osg::Vec3d(0, 1, 0));
        const ::osg::Matrixd projection = ::osg::Matrixd::perspective(60.0, 16.0 / 9.0, 0.3, 300.0);
        ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap;
        shadowMap->setSceneBounds(box);
        const auto light = spotLight(wsLamp, aim, cutoff);
        const VdsmCall call = callAsVdsm(*shadowMap, view, projection, *light);
        ASSERT_TRUE(shadowMap->lastSpotSetup()) << shadowMap->lastSpotError();
        const core::ShadowSetup& setup = *shadowMap->lastSpotSetup();
        EXPECT_EQ(call.ok, !setup.views.empty());
        if (setup.views.empty()) continue;
        ++maps;
        const core::EngineShadowView gl = core::toEngineView(setup.views[0], setup, core::OutputConventions::openGL());
        const core::Mat4& clipFromLight = setup.views[0].clipFromLight;
        const double span = std::max(2.0 / clipFromLight[0][0], 2.0 / clipFromLight[1][1]);
        const double halfCone = glm::radians(double(light->getSpotCutoff()));
        EXPECT_LE(span, 2.0 * std::tan(halfCone) * (1.0 + 1e-9));
        if (span < 0.999 * 2.0 * std::tan(halfCone)) ++narrowed;

        const core::Vec3 axis(light->getDirection().x(), light->getDirection().y(), light->getDirection().z());
        const core::Vec3 side =
            glm::normalize(glm::cross(axis, std::abs(axis.y) < 0.9 ? core::Vec3(0, 1, 0) : core::Vec3(1, 0, 0)));
        const core::Vec3 up = glm::cross(side, glm::normalize(axis));
        const core::Mat4 clipFromWorld = toCore(call.projection) * toCore(call.view);
        const core::Mat4 clipFromView = toCore(projection) * toCore(view);
        for (int sample = 0; sample < 4000; ++sample) {
            const double a = 2.0 * u(rng) - 1.0, b = 2.0 * u(rng) - 1.0;
            if (a * a + b * b > 1.0) continue;
            const core::Vec3 ray = glm::normalize(glm::normalize(axis) + std::tan(halfCone) * (a * side + b * up));
            const core::Vec3 p = wsLamp + 100.0 * u(rng) * ray;
            if (p.x < -60 || p.x > 60 || p.y < 0 || p.y > 20 || p.z < -60 || p.z > 60) continue;
            const core::Vec4 c = clipFromView * core::Vec4(p, 1.0);
            if (c.w <= 0.0 || std::abs(c.x) > c.w || std::abs(c.y) > c.w || std::abs(c.z) > c.w) continue;
            ++seenInMaps;
            expectInTheMapOnTheCoresTexel(clipFromWorld, gl, p);
        }
    }
    EXPECT_GE(maps, 10);
    EXPECT_GE(seenInMaps, 1000);
    EXPECT_GE(narrowed, 3); // the camera sees part of the cone: the map narrows to it
}

// A lamp over a 120 m yard, 3–33 m up, and a camera among the lamps looking 0.1–0.5 below
// level, its projection reaching zFar, as OSG holds them.
struct LampAndView {
    core::Vec3 wsLamp;
    ::osg::Matrixd view, projection;
};
LampAndView randomLampAndView(std::mt19937& rng, double zFar) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    LampAndView out;
    out.wsLamp = core::Vec3(-50.0 + 100.0 * u(rng), 3.0 + 30.0 * u(rng), -50.0 + 100.0 * u(rng));
    const core::Vec3 wsEye(-40.0 + 80.0 * u(rng), 1.7 + 10.0 * u(rng), -40.0 + 80.0 * u(rng));
    core::Vec3 forward = unitVector(rng);
    forward.y = -0.1 - 0.4 * std::abs(forward.y);
    forward = glm::normalize(forward);
    out.view = ::osg::Matrixd::lookAt(::osg::Vec3d(wsEye.x, wsEye.y, wsEye.z),
                                      ::osg::Vec3d(wsEye.x + forward.x, wsEye.y + forward.y, wsEye.z + forward.z),
                                      ::osg::Vec3d(0, 1, 0));
    out.projection = ::osg::Matrixd::perspective(60.0, 16.0 / 9.0, 0.3, zFar);
    return out;
}

// A point of the camera's view (worldFromClip), drawn uniformly in its clip space, if it lies in
// the yard's box.
std::optional<core::Vec3> seenInYard(const core::Mat4& worldFromClip, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const core::Vec4 h = worldFromClip * core::Vec4(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1, 1.0);
    const core::Vec3 p = core::Vec3(h) / h.w;
    if (p.x < -60 || p.x > 60 || p.y < 0 || p.y > 20 || p.z < -60 || p.z > 60) return std::nullopt;
    return p;
}

// The adapter beside a plain ViewDependentShadowMap, each in a shadowed scene of its own (VDSM
// reads its settings there), the adapter's scene box `wsBounds`.
struct OursBesideOsgs {
    ::osg::ref_ptr<ShadowMap> ours = new ShadowMap;
    ::osg::ref_ptr<osgShadow::ViewDependentShadowMap> osgs = new osgShadow::ViewDependentShadowMap;
    ::osg::ref_ptr<osgShadow::ShadowedScene> oursScene = new osgShadow::ShadowedScene(ours.get());
    ::osg::ref_ptr<osgShadow::ShadowedScene> osgsScene = new osgShadow::ShadowedScene(osgs.get());
    explicit OursBesideOsgs(const ::osg::BoundingBoxd& wsBounds) { ours->setSceneBounds(wsBounds); }
    // A light the adapter leaves to OSG gets exactly the camera a plain VDSM computes.
    void expectOsgsOwnCamera(const ::osg::Matrixd& view, const ::osg::Matrixd& projection,
                             const ::osg::Light& light) const {
        const VdsmCall got = callAsVdsm(*ours, view, projection, light);
        const VdsmCall want = callAsVdsm(*osgs, view, projection, light);
        EXPECT_EQ(got.ok, want.ok);
        EXPECT_EQ(got.view, want.view);
        EXPECT_EQ(got.projection, want.projection);
    }
};

TEST(OsgShadowCamera, PointLightMapsHoldWhatTheCameraSeesWhereOsgsOwnNeedNot) {
    // Lamps over a yard and cameras among them. OSG aims a point light's map along the light's
    // direction (here OSG's default, −Z) and widens it to the view frustum's corners, at most
    // 160°; the adapter aims it at what the camera sees within reach. Every point the camera
    // sees inside the box — sampled from the view, not from the set-up — must land in the
    // adapter's map on the core's texel, wherever OSG's own map lands it; where that spans
    // more than 170° from the lamp, every such point inside the 170° cone the adapter then
    // aims at the middle of it, and the set-up says that it holds only part.
    std::mt19937 rng(11);
    const ::osg::BoundingBoxd box({-60.0, 0.0, -60.0}, {60.0, 20.0, 60.0});
    int maps = 0, partial = 0, ownMaps = 0;
    long seen = 0, heldByAdapter = 0, heldByOsg = 0;
    double logGain = 0.0, logAreaGain = 0.0;
    for (int trial = 0; trial < 40; ++trial) {
        const auto [wsLamp, view, projection] = randomLampAndView(rng, 40.0);
        const OursBesideOsgs beside(box);
        ShadowMap* shadowMap = beside.ours.get();
        ::osg::ref_ptr<::osg::Light> bulb = new ::osg::Light;
        bulb->setPosition(::osg::Vec4(float(wsLamp.x), float(wsLamp.y), float(wsLamp.z), 1.0f));
        const VdsmCall call = callAsVdsm(*shadowMap, view, projection, *bulb);
        const VdsmCall own = callAsVdsm(*beside.osgs, view, projection, *bulb);
        ASSERT_TRUE(shadowMap->lastPointSetup()) << shadowMap->lastPointError();
        const core::ShadowSetup& setup = *shadowMap->lastPointSetup();
        EXPECT_EQ(call.ok, !setup.views.empty());
        if (setup.views.empty()) continue;
        ++maps;
        // A map over part of what the camera sees says so; it holds what lies in its cone.
        const bool part = !setup.fallbacks.empty();
        partial += part;
        const core::Vec3 wsAxis =
            -glm::normalize(core::Vec3(glm::inverse(setup.views[0].lightFromWorld) * core::Vec4(0, 0, 1, 0)));
        const core::EngineShadowView gl = core::toEngineView(setup.views[0], setup, core::OutputConventions::openGL());
        const core::Mat4 clipFromWorld = toCore(call.projection) * toCore(call.view);
        const core::Mat4 ownClipFromWorld = toCore(own.projection) * toCore(own.view);
        const core::Mat4 worldFromClip = glm::inverse(toCore(projection) * toCore(view));
        // Texels per metre gained along each axis: the ratio of the tangent spans (same map size).
        const core::Mat4& clipFromLight = setup.views[0].clipFromLight;
        const double width = 2.0 / clipFromLight[0][0], height = 2.0 / clipFromLight[1][1];
        if (own.ok) {
            const double ownSpan = 2.0 / own.projection(0, 0);
            logGain += std::log(ownSpan / std::max(width, height));
            logAreaGain += std::log(ownSpan * ownSpan / (width * height));
            ++ownMaps;
        }
        for (int sample = 0; sample < 2000; ++sample) {
            const std::optional<core::Vec3> sampled = seenInYard(worldFromClip, rng);
            if (!sampled) continue;
            const core::Vec3 p = *sampled;
            if (glm::distance(p, wsLamp) < 1e-3) continue;
            ++seen;
            const core::Vec4 o = ownClipFromWorld * core::Vec4(p, 1.0);
            heldByOsg += own.ok && o.w > 0.0 && std::abs(o.x) <= o.w && std::abs(o.y) <= o.w;
            if (part && glm::dot(glm::normalize(p - wsLamp), wsAxis) < std::cos(glm::radians(85.0))) continue;
            ++heldByAdapter;
            expectInTheMapOnTheCoresTexel(clipFromWorld, gl, p);
        }
    }
    EXPECT_GE(maps, 10);
    EXPECT_GE(partial, 1); // some lamps stand among what the camera sees
    EXPECT_GE(seen, 5000);
    EXPECT_GT(heldByAdapter, heldByOsg); // OSG's fixed aim leaves more of what the camera sees out
    std::printf("%d point lights mapped, %d of them over part of what the camera sees; of %ld points seen, the "
                "adapter's maps held %ld, OSG's own %ld; against OSG's map, geometric means: texels per metre on "
                "the coarser axis x%.2f, texels x%.2f\n",
                maps, partial, seen, heldByAdapter, heldByOsg, std::exp(logGain / std::max(ownMaps, 1)),
                std::exp(logAreaGain / std::max(ownMaps, 1)));
}

TEST(OsgShadowCamera, AnAttenuatedLampsMapEndsWhereItsLightFadesOut) {
    // OSG's lights have attenuation, not a range. A lamp given one that fades it out at r metres
    // (setReach) gets a map over what the camera sees within r — every point it lights by at
    // least the cutoff, found from the lighting equation with OSG's own coefficients, lands on
    // the core's texel — not over all the camera sees of the box, as the same lamp without
    // fall-off does: its map spends its texels on a smaller solid angle and leaves out points
    // beyond r.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const ::osg::BoundingBoxd box({-60.0, 0.0, -60.0}, {60.0, 20.0, 60.0});
    int maps = 0, compared = 0;
    long lit = 0, beyond = 0, beyondOutside = 0;
    double logAreaGain = 0.0;
    for (int trial = 0; trial < 40; ++trial) {
        const auto [wsLamp, view, projection] = randomLampAndView(rng, 80.0);
        const double range = 10.0 + 30.0 * u(rng);
        ::osg::ref_ptr<::osg::Light> bulb = new ::osg::Light, plainBulb = new ::osg::Light;
        for (::osg::Light* light : {bulb.get(), plainBulb.get()})
            light->setPosition(::osg::Vec4(float(wsLamp.x), float(wsLamp.y), float(wsLamp.z), 1.0f));
        shadowkit::osgadapter::setReach(*bulb, range);
        ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap, unattenuated = new ShadowMap;
        ::osg::ref_ptr<osgShadow::ShadowedScene> ours = new osgShadow::ShadowedScene(shadowMap.get());
        ::osg::ref_ptr<osgShadow::ShadowedScene> plain = new osgShadow::ShadowedScene(unattenuated.get());
        shadowMap->setSceneBounds(box);
        unattenuated->setSceneBounds(box);
        const VdsmCall call = callAsVdsm(*shadowMap, view, projection, *bulb);
        const VdsmCall whole = callAsVdsm(*unattenuated, view, projection, *plainBulb);
        ASSERT_TRUE(shadowMap->lastPointSetup()) << shadowMap->lastPointError();
        const core::ShadowSetup& setup = *shadowMap->lastPointSetup();
        if (setup.views.empty()) continue;
        ++maps;
        const bool part = !setup.fallbacks.empty();
        const core::Mat4& clipFromLight = setup.views[0].clipFromLight;
        if (whole.ok && !part && unattenuated->lastPointSetup()->fallbacks.empty()) {
            const core::Mat4& wholeClipFromLight = unattenuated->lastPointSetup()->views[0].clipFromLight;
            logAreaGain += std::log(clipFromLight[0][0] * clipFromLight[1][1] /
                                    (wholeClipFromLight[0][0] * wholeClipFromLight[1][1]));
            ++compared;
        }
        const core::Vec3 wsAxis =
            -glm::normalize(core::Vec3(glm::inverse(setup.views[0].lightFromWorld) * core::Vec4(0, 0, 1, 0)));
        const core::EngineShadowView gl = core::toEngineView(setup.views[0], setup, core::OutputConventions::openGL());
        const core::Mat4 clipFromWorld = toCore(call.projection) * toCore(call.view);
        const core::Mat4 worldFromClip = glm::inverse(toCore(projection) * toCore(view));
        for (int sample = 0; sample < 2000; ++sample) {
            const std::optional<core::Vec3> sampled = seenInYard(worldFromClip, rng);
            if (!sampled) continue;
            const core::Vec3 p = *sampled;
            const double d = glm::distance(p, wsLamp);
            if (d < 1e-3) continue;
            // What the fixed-function pipeline lights a white surface facing the lamp with at p.
            const double shade =
                bulb->getDiffuse()[0] / (bulb->getConstantAttenuation() + bulb->getLinearAttenuation() * d +
                                         bulb->getQuadraticAttenuation() * d * d);
            if (shade < core::kDefaultReachCutoff) {
                ++beyond;
                const core::Vec4 m = clipFromWorld * core::Vec4(p, 1.0);
                beyondOutside += !(m.w > 0.0 && std::abs(m.x) <= m.w && std::abs(m.y) <= m.w && m.z <= m.w);
                continue;
            }
            if (part && glm::dot(glm::normalize(p - wsLamp), wsAxis) < std::cos(glm::radians(85.0))) continue;
            ++lit;
            expectInTheMapOnTheCoresTexel(clipFromWorld, gl, p);
        }
    }
    EXPECT_GE(maps, 10);
    EXPECT_GE(compared, 5);
    EXPECT_GE(lit, 3000);
    // The map leaves out most of what the camera sees beyond the lamp's reach ...
    EXPECT_GT(beyondOutside, beyond / 2);
    // ... and spends the same texels on a smaller solid angle than the lamp without fall-off.
    EXPECT_GT(logAreaGain / std::max(compared, 1), std::log(1.5)); // measured: x2.01
    std::printf("%d attenuated point lights mapped; %ld points seen lit all on the core's texel; of %ld seen beyond "
                "reach %ld outside the map; against the same lamps without fall-off (%d), texels x%.2f\n",
                maps, lit, beyond, beyondOutside, compared, std::exp(logAreaGain / std::max(compared, 1)));
}

TEST(OsgShadowCamera, ALampThatNeverShowsHasNoMapAndBadAttenuationKeepsOsgsCamera) {
    const ::osg::Matrixd view =
        ::osg::Matrixd::lookAt(::osg::Vec3d(0, 20, 40), ::osg::Vec3d(0, 19.5, 39), ::osg::Vec3d(0, 1, 0));
    const ::osg::Matrixd projection = ::osg::Matrixd::perspective(60.0, 1.5, 0.3, 300.0);
    const OursBesideOsgs beside(::osg::BoundingBoxd({-60.0, 0.0, -60.0}, {60.0, 20.0, 60.0}));
    ShadowMap* shadowMap = beside.ours.get();
    // Black: it lights nothing, so nothing needs its shadow.
    ::osg::ref_ptr<::osg::Light> black = new ::osg::Light;
    black->setPosition(::osg::Vec4(0.0f, 30.0f, -20.0f, 1.0f));
    black->setDiffuse(::osg::Vec4(0, 0, 0, 1));
    black->setSpecular(::osg::Vec4(0, 0, 0, 1));
    black->setQuadraticAttenuation(0.01f);
    EXPECT_FALSE(callAsVdsm(*shadowMap, view, projection, *black).ok);
    ASSERT_TRUE(shadowMap->lastPointSetup()) << shadowMap->lastPointError();
    EXPECT_TRUE(shadowMap->lastPointSetup()->views.empty());
    // A negative term is the user's error: said in one line, naming it; OSG's own camera.
    ::osg::ref_ptr<::osg::Light> odd = new ::osg::Light;
    odd->setPosition(::osg::Vec4(0.0f, 30.0f, -20.0f, 1.0f));
    odd->setLinearAttenuation(-0.5f);
    beside.expectOsgsOwnCamera(view, projection, *odd);
    EXPECT_FALSE(shadowMap->lastPointSetup());
    EXPECT_EQ(shadowMap->lastPointError().rfind("light 0's linear attenuation -0.5: must be", 0), 0u)
        << shadowMap->lastPointError();
    EXPECT_EQ(shadowMap->lastPointError().find('\n'), std::string::npos);
    // The cutoff is checked where it is set, the last kept.
    EXPECT_FALSE(shadowMap->setReachCutoff(0.0));
    EXPECT_FALSE(shadowMap->setReachCutoff(1.5));
    EXPECT_EQ(shadowMap->reachCutoff(), core::kDefaultReachCutoff);
    EXPECT_TRUE(shadowMap->setReachCutoff(0.01));
    EXPECT_EQ(shadowMap->reachCutoff(), 0.01);
}

TEST(OsgShadowCamera, BadSpotsKeepOsgsCameraAndALampAmongTheViewGetsAnAimedMap) {
    // A spot of more than the core's 170° (said once): OSG's own camera, exactly what a plain
    // ViewDependentShadowMap computes for the same call. A point light among what the camera
    // sees: the adapter's 170° map aimed at the middle of it, saying it holds only part.
    const ::osg::Matrixd view =
        ::osg::Matrixd::lookAt(::osg::Vec3d(0, 2, 10), ::osg::Vec3d(0, 1.8, 9), ::osg::Vec3d(0, 1, 0));
    const ::osg::Matrixd projection = ::osg::Matrixd::perspective(60.0, 1.5, 0.3, 300.0);
    const OursBesideOsgs beside(::osg::BoundingBoxd({-60.0, 0.0, -60.0}, {60.0, 20.0, 60.0}));
    ShadowMap* shadowMap = beside.ours.get();
    const auto wide = spotLight(core::Vec3(0, 6, 0), core::Vec3(0, -1, 0), 87.5);
    beside.expectOsgsOwnCamera(view, projection, *wide);
    // Named as OSG's user set it: the cutoff, not the core's cone.
    EXPECT_EQ(shadowMap->lastSpotError().rfind("spot light cutoff 87.5 degrees: ", 0), 0u)
        << shadowMap->lastSpotError();
    EXPECT_EQ(shadowMap->lastSpotError().find('\n'), std::string::npos);
    EXPECT_FALSE(shadowMap->lastSpotSetup());

    ::osg::ref_ptr<::osg::Light> bulb = new ::osg::Light;
    bulb->setPosition(::osg::Vec4(0.0f, 6.0f, 0.0f, 1.0f));
    EXPECT_TRUE(callAsVdsm(*shadowMap, view, projection, *bulb).ok);
    ASSERT_TRUE(shadowMap->lastPointSetup()) << shadowMap->lastPointError();
    EXPECT_EQ(shadowMap->lastPointSetup()->views.size(), 1u);
    ASSERT_FALSE(shadowMap->lastPointSetup()->fallbacks.empty());
    EXPECT_NE(shadowMap->lastPointSetup()->fallbacks.back().find("aimed at the middle"), std::string::npos);
    EXPECT_TRUE(shadowMap->lastError().empty()); // the sun's error is its own
}

TEST(OsgShadowCamera, RefusesManyMapTechniquesAndAnEmptySceneInOneLine) {
    const ::osg::Matrixd view =
        ::osg::Matrixd::lookAt(::osg::Vec3d(0, 20, 0), ::osg::Vec3d(0, 20, -1), ::osg::Vec3d(0, 1, 0));
    const ::osg::Matrixd projection = ::osg::Matrixd::perspective(60.0, 1.5, 0.5, 500.0);
    core::ShadowSetupInputs options;
    options.technique = core::Technique::Csm;
    auto csm = shadowkit::osgadapter::shadowCameraFor(view, projection, INFINITY, {0, -1, 0.3}, kForestBox, options);
    ASSERT_FALSE(csm);
    EXPECT_NE(csm.error().find("csm"), std::string::npos) << csm.error();
    EXPECT_EQ(csm.error().find('\n'), std::string::npos);

    options.technique = core::Technique::Tsm;
    auto empty = shadowkit::osgadapter::shadowCameraFor(view, projection, INFINITY, {0, -1, 0.3}, ::osg::BoundingBoxd(),
                                                        options);
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.error().find("scene bounds"), std::string::npos) << empty.error();

    // Through VDSM's call the frame goes without shadows, and says why.
    ::osg::ref_ptr<ShadowMap> shadowMap = new ShadowMap;
    options.technique = core::Technique::Virtual;
    shadowMap->setInputs(options);
    shadowMap->setSceneBounds(kForestBox);
    EXPECT_FALSE(callAsVdsm(*shadowMap, view, projection, {0, -1, 0.3}).ok);
    EXPECT_NE(shadowMap->lastError().find("virtual"), std::string::npos);
    EXPECT_FALSE(shadowMap->lastSetup());
}

} // namespace
