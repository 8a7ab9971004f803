// The OGRE adapter's texture cameras, as OGRE holds them, against shadowkit::core's own set-up:
// OGRE's row-major, column-vector float matrices and OpenGL-style projection converted so that
// every point of the focus body lands on the core's texel and depth. OGRE needs no render
// system for this: a Root, a scene manager, cameras and a light.
#include "shadowkit/ogre/shadow_camera_setup.h"

#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/output_conventions.h"

#include <OgreCamera.h>
#include <OgreDefaultHardwareBufferManager.h>
#include <OgreLight.h>
#include <OgreLogManager.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>

namespace {

namespace core = shadowkit::core;
using shadowkit::ogreadapter::ShadowCameraSetup;

const Ogre::AxisAlignedBox kForestBox(-512, -4, -512, 512, 50, 512);

// One OGRE Root for the test binary: a silent log, no plugins, no render system.
class OgreScene : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_log = std::make_unique<Ogre::LogManager>();
        s_log->createLog("shadowkit_ogre_tests.log", true, false, true); // default, not to stdout, no file
        s_root = std::make_unique<Ogre::Root>("", "", "");
        // Cameras keep vertex data for their debug outline: buffers in memory stand in for a
        // render system's.
        s_buffers = std::make_unique<Ogre::DefaultHardwareBufferManager>();
        Ogre::MaterialManager::getSingleton().initialise(); // the default material a camera takes
    }
    static void TearDownTestSuite() {
        s_root.reset();
        s_buffers.reset();
        s_log.reset();
    }
    void SetUp() override { m_sm = s_root->createSceneManager(); }
    void TearDown() override { s_root->destroySceneManager(m_sm); }

    // A camera at wsEye looking along `forward` with OGRE's own projection.
    Ogre::Camera* camera(const core::Vec3& wsEye, const core::Vec3& forward, double fovY, double aspect, double zNear,
                         double zFar) {
        Ogre::Camera* cam = m_sm->createCamera("camera" + std::to_string(m_cameras++));
        Ogre::SceneNode* node = m_sm->getRootSceneNode()->createChildSceneNode();
        node->attachObject(cam);
        node->setPosition(Ogre::Vector3(Ogre::Real(wsEye.x), Ogre::Real(wsEye.y), Ogre::Real(wsEye.z)));
        node->setFixedYawAxis(true);
        node->setDirection(Ogre::Vector3(Ogre::Real(forward.x), Ogre::Real(forward.y), Ogre::Real(forward.z)),
                           Ogre::Node::TS_WORLD);
        cam->setFOVy(Ogre::Radian(Ogre::Degree(Ogre::Real(fovY))));
        cam->setAspectRatio(Ogre::Real(aspect));
        cam->setNearClipDistance(Ogre::Real(zNear));
        cam->setFarClipDistance(Ogre::Real(zFar));
        return cam;
    }
    Ogre::Light* sun(const core::Vec3& travel) {
        Ogre::Light* light = m_sm->createLight();
        light->setType(Ogre::Light::LT_DIRECTIONAL);
        Ogre::SceneNode* node = m_sm->getRootSceneNode()->createChildSceneNode();
        node->attachObject(light);
        node->setDirection(Ogre::Vector3(Ogre::Real(travel.x), Ogre::Real(travel.y), Ogre::Real(travel.z)),
                           Ogre::Node::TS_WORLD);
        m_sm->getRootSceneNode()->_update(true, false);
        return light;
    }

    Ogre::Light* spot(const core::Vec3& wsPosition, const core::Vec3& wsDirection, double coneDegrees, double range) {
        Ogre::Light* light = m_sm->createLight();
        light->setType(Ogre::Light::LT_SPOTLIGHT);
        light->setSpotlightOuterAngle(Ogre::Degree(Ogre::Real(coneDegrees)));
        light->setSpotlightInnerAngle(Ogre::Degree(Ogre::Real(0.8 * coneDegrees)));
        light->setAttenuation(Ogre::Real(range), 1.0f, 0.0f, 0.0f);
        Ogre::SceneNode* node = m_sm->getRootSceneNode()->createChildSceneNode();
        node->attachObject(light);
        node->setPosition(Ogre::Vector3(Ogre::Real(wsPosition.x), Ogre::Real(wsPosition.y), Ogre::Real(wsPosition.z)));
        node->setDirection(
            Ogre::Vector3(Ogre::Real(wsDirection.x), Ogre::Real(wsDirection.y), Ogre::Real(wsDirection.z)),
            Ogre::Node::TS_WORLD);
        m_sm->getRootSceneNode()->_update(true, false);
        return light;
    }

    Ogre::Light* point(const core::Vec3& wsPosition, double range) {
        Ogre::Light* light = m_sm->createLight();
        light->setType(Ogre::Light::LT_POINT);
        light->setAttenuation(Ogre::Real(range), 1.0f, 0.0f, 0.0f);
        Ogre::SceneNode* node = m_sm->getRootSceneNode()->createChildSceneNode();
        node->attachObject(light);
        node->setPosition(Ogre::Vector3(Ogre::Real(wsPosition.x), Ogre::Real(wsPosition.y), Ogre::Real(wsPosition.z)));
        m_sm->getRootSceneNode()->_update(true, false);
        return light;
    }

    // A triangle of geometry spanning x and z in [−50, 50], y in [0, 20], on a node of its own.
    Ogre::SceneNode* geometry() {
        Ogre::ManualObject* box = m_sm->createManualObject();
        box->begin("BaseWhite", Ogre::RenderOperation::OT_TRIANGLE_LIST);
        box->position(-50, 0, -50);
        box->position(50, 0, -50);
        box->position(0, 20, 50);
        box->triangle(0, 1, 2);
        box->end();
        Ogre::SceneNode* node = m_sm->getRootSceneNode()->createChildSceneNode();
        node->attachObject(box);
        return node;
    }

    static std::unique_ptr<Ogre::LogManager> s_log;
    static std::unique_ptr<Ogre::Root> s_root;
    static std::unique_ptr<Ogre::DefaultHardwareBufferManager> s_buffers;
    Ogre::SceneManager* m_sm = nullptr;
    int m_cameras = 0;
};
std::unique_ptr<Ogre::LogManager> OgreScene::s_log;
std::unique_ptr<Ogre::Root> OgreScene::s_root;
std::unique_ptr<Ogre::DefaultHardwareBufferManager> OgreScene::s_buffers;

core::Vec3 unitVector(std::mt19937& rng) {
    std::normal_distribution<double> n;
    return glm::normalize(core::Vec3(n(rng), n(rng), n(rng)));
}

// The adapter set for `technique` over the forest's box.
void setUpForTheForest(ShadowCameraSetup& setup, core::Technique technique) {
    core::ShadowSetupInputs options;
    options.technique = technique;
    ASSERT_TRUE(setup.setInputs(options));
    setup.setSceneBounds(kForestBox);
}

// A random eye over the forest, a view direction not along the vertical and a sun above the
// horizon (its direction of travel, unit).
struct RandomView {
    core::Vec3 wsEye, forward, sunTravel;
};
RandomView randomView(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    RandomView v;
    v.wsEye = core::Vec3(-300.0 + 600.0 * u(rng), 2.0 + 40.0 * u(rng), -300.0 + 600.0 * u(rng));
    v.forward = unitVector(rng);
    if (std::abs(v.forward.y) > 0.95) v.forward = glm::normalize(core::Vec3(1.0, v.forward.y, 0.0));
    v.sunTravel = unitVector(rng);
    v.sunTravel.y = -0.2 - 0.8 * std::abs(v.sunTravel.y);
    v.sunTravel = glm::normalize(v.sunTravel);
    return v;
}

// A camera's clip-from-world matrix as OGRE holds it (row-major), in double.
core::Mat4 clipFromWorldOf(const Ogre::Camera& camera) {
    core::Mat4 view(1.0), projection(1.0);
    const Ogre::Affine3& a = camera.getViewMatrix();
    const Ogre::Matrix4& o = camera.getProjectionMatrix();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) view[c][r] = a[r][c], projection[c][r] = o[r][c];
    return projection * view;
}

// A world point through a texture camera as OGRE holds it, in double: (u, v) in texels as
// OpenGL's viewport maps clip x, y, and the depth in [0, 1].
core::Vec3 texelOf(const Ogre::Camera& texCam, const core::Vec3& p, int texels) {
    const core::Vec4 clip = clipFromWorldOf(texCam) * core::Vec4(p, 1.0);
    return {(0.5 * clip.x / clip.w + 0.5) * texels, (0.5 * clip.y / clip.w + 0.5) * texels,
            0.5 * clip.z / clip.w + 0.5};
}

TEST_F(OgreScene, TextureCamerasMapTheFocusBodyToTheCoresTexelsForRandomCamerasAndSuns) {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const core::Technique techniques[] = {core::Technique::Tsm,     core::Technique::Lispsm,   core::Technique::Psm,
                                          core::Technique::Focused, core::Technique::Standard, core::Technique::Csm};
    int compared = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const core::Technique technique = techniques[trial % 6];
        const RandomView v = randomView(rng);
        Ogre::Camera* cam =
            camera(v.wsEye, v.forward, 40.0 + 40.0 * u(rng), 1.0 + u(rng), 0.3 + u(rng), 200.0 + 400.0 * u(rng));
        Ogre::Light* light = sun(v.sunTravel);

        ShadowCameraSetup setup;
        core::ShadowSetupInputs options;
        options.technique = technique;
        ASSERT_TRUE(setup.setInputs(options));
        setup.setSceneBounds(kForestBox);

        // The core's own set-up for the camera and sun as OGRE holds them (float), in double.
        core::ShadowSetupInputs in = options;
        core::Mat4 view(1.0), projection(1.0);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                view[c][r] = cam->getViewMatrix()[r][c];
                projection[c][r] = cam->getProjectionMatrix()[r][c];
            }
        auto engineCamera = core::cameraFromMatrices({view, projection, core::ClipDepthRange::MinusOneToOne});
        ASSERT_TRUE(engineCamera) << engineCamera.error();
        in.camera = *engineCamera;
        const Ogre::Vector3 travel = light->getDerivedDirection();
        in.light = core::DirectionalLight::fromDirection({travel.x, travel.y, travel.z}).value();
        in.wsSceneBounds = core::Aabb::fromMinMax(core::Vec3(-512, -4, -512), core::Vec3(512, 50, 512));
        in.depthLayout = core::DepthLayout::Hyperbolic;
        auto computed = core::computeShadowSetup(in);
        ASSERT_TRUE(computed) << computed.error();
        const core::ShadowSetup& expected = *computed;

        for (size_t iteration = 0; iteration < expected.views.size(); ++iteration) {
            Ogre::Camera* texCam =
                m_sm->createCamera("texture" + std::to_string(trial) + "-" + std::to_string(iteration));
            setup.getShadowCamera(m_sm, cam, nullptr, light, texCam, iteration);
            ASSERT_TRUE(setup.lastSetup()) << setup.lastError();
            const core::EngineShadowView gl =
                core::toEngineView(expected.views[iteration], expected, core::OutputConventions::openGL());
            core::ConvexBody::Points points = expected.body.vertices();
            if (points.empty()) // `standard` has no body: the scene box's corners
                for (int corner = 0; corner < 8; ++corner)
                    points.push_back(
                        core::Vec3(corner & 1 ? 512 : -512, corner & 2 ? 50 : -4, corner & 4 ? 512 : -512));
            for (const core::Vec3& p : points) {
                const core::Vec4 t = gl.textureFromWorld * core::Vec4(p, 1.0);
                if (t.w <= 0.0 || std::abs(t.x / t.w - 0.5) > 0.5 || std::abs(t.y / t.w - 0.5) > 0.5)
                    continue; // another cascade's
                const core::Vec3 texel = texelOf(*texCam, p, in.mapSize);
                // OGRE holds the matrices in float (7 digits): their rounding moves a point by
                // up to 2e-3 of a texel of a 2048² map here; a wrong convention moves it by
                // hundreds (OSG's double matrices are held to 1e-4).
                EXPECT_NEAR(texel.x, t.x / t.w * in.mapSize, 5e-3) << core::techniqueName(technique);
                EXPECT_NEAR(texel.y, t.y / t.w * in.mapSize, 5e-3) << core::techniqueName(technique);
                EXPECT_NEAR(texel.z, t.z / t.w, 1e-5) << core::techniqueName(technique);
            }
        }
        ++compared;
    }
    EXPECT_EQ(compared, 60);
}

TEST_F(OgreScene, CastersNearerTheSunThanTheMapsNearPlaneSurviveOgresCulling) {
    // OGRE culls the casters it draws into a texture against its camera's frustum, near plane
    // included, before any shader could clamp them (OGRE 1.12 has no depth clamp): a tree
    // outside the view, between the sun and the ground the camera sees, must still be drawn. So
    // every point of the scene box on the way from a receiver of a map (a point of the focus
    // body inside it) to the sun must lie inside that map's texture camera's frustum — the
    // core's near plane must reach the box's side towards the sun, for every technique and
    // cascade (it does, to within a thousandth of the depth range: a spot's does not, and the
    // adapter moves that one).
    std::mt19937 rng(91);
    const core::Technique techniques[] = {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Psm,
                                          core::Technique::Focused, core::Technique::Csm};
    const core::Aabb box = core::Aabb::fromMinMax(core::Vec3(-512, -4, -512), core::Vec3(512, 50, 512));
    int casters = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const core::Technique technique = techniques[trial % 5];
        const RandomView v = randomView(rng);
        const core::Vec3 sunTravel = v.sunTravel;
        Ogre::Camera* cam = camera(v.wsEye, v.forward, 60.0, 16.0 / 9.0, 0.3, 400.0);
        Ogre::Light* light = sun(sunTravel);
        ShadowCameraSetup setup;
        setUpForTheForest(setup, technique);
        for (size_t iteration = 0;; ++iteration) {
            Ogre::Camera* texCam =
                m_sm->createCamera("caster" + std::to_string(trial) + "-" + std::to_string(iteration));
            setup.getShadowCamera(m_sm, cam, nullptr, light, texCam, iteration);
            ASSERT_TRUE(setup.lastSetup()) << setup.lastError();
            const core::ShadowSetup& used = *setup.lastSetup();
            const core::EngineShadowView gl =
                core::toEngineView(used.views[iteration], used, core::OutputConventions::openGL());
            for (const core::Vec3& p : used.body.vertices()) {
                const core::Vec4 t = gl.textureFromWorld * core::Vec4(p, 1.0);
                if (t.w <= 0.0 || std::abs(t.x / t.w - 0.5) > 0.499 || std::abs(t.y / t.w - 0.5) > 0.499 ||
                    std::abs(t.z / t.w - 0.5) > 0.499)
                    continue; // another cascade's
                // Towards the sun to the scene box's side: the farthest caster there can be.
                double exit = std::numeric_limits<double>::infinity();
                for (int axis = 0; axis < 3; ++axis)
                    if (std::abs(sunTravel[axis]) > 1e-9) {
                        const double wall = sunTravel[axis] < 0.0 ? box.max[axis] : box.min[axis];
                        exit = std::min(exit, (p[axis] - wall) / sunTravel[axis]);
                    }
                for (const double share : {0.25, 0.5, 0.99}) {
                    const core::Vec3 caster = p - sunTravel * (share * exit);
                    const Ogre::Vector3 at(Ogre::Real(caster.x), Ogre::Real(caster.y), Ogre::Real(caster.z));
                    EXPECT_TRUE(texCam->isVisible(Ogre::AxisAlignedBox(at - 0.05f, at + 0.05f)))
                        << core::techniqueName(technique) << ": a caster " << share * exit
                        << " m towards the sun from a receiver is culled";
                    ++casters;
                }
            }
            if (iteration + 1 >= used.views.size()) break;
        }
    }
    EXPECT_GE(casters, 300);
}

// Whether a world point lies inside the camera's view, up to `shadowDistance` along it.
// A world point through the adapter's texture camera lands inside its 2048² map on the core's
// own texel for it (gl: the core's set-up in OpenGL's conventions) within `tolerance` texels, its
// depth at most the map's far end; the texel, for the caller's own checks.
core::Vec3 expectInTheMapOnTheCoresTexel(const Ogre::Camera& texCam, const core::EngineShadowView& gl,
                                         const core::Vec3& p, double tolerance) {
    const core::Vec3 texel = texelOf(texCam, p, 2048);
    const core::Vec4 t = gl.textureFromWorld * core::Vec4(p, 1.0);
    EXPECT_NEAR(texel.x, t.x / t.w * 2048, tolerance);
    EXPECT_NEAR(texel.y, t.y / t.w * 2048, tolerance);
    EXPECT_GE(texel.x, -1e-3);
    EXPECT_LE(texel.x, 2048 + 1e-3);
    EXPECT_GE(texel.y, -1e-3);
    EXPECT_LE(texel.y, 2048 + 1e-3);
    EXPECT_LE(texel.z, 1.0);
    return texel;
}

bool inView(const Ogre::Camera& cam, const core::Vec3& p, double shadowDistance) {
    const Ogre::Vector3 eye = cam.getViewMatrix() * Ogre::Vector3(Ogre::Real(p.x), Ogre::Real(p.y), Ogre::Real(p.z));
    return cam.isVisible(Ogre::Vector3(Ogre::Real(p.x), Ogre::Real(p.y), Ogre::Real(p.z))) && -eye.z <= shadowDistance;
}

TEST_F(OgreScene, SpotLightMapsHoldWhatTheCameraSeesOfTheConeInTheCoresTexels) {
    // Lamps over the forest floor, cameras among them. Every point the camera sees inside a
    // lamp's cone and range — found by sampling, not from the set-up — must land in the spot
    // map (texel in [0, N], depth in [0, 1]) on the core's texel, and the map must spend at
    // least the texels per metre OGRE's own spot camera spends (1.2 × the cone): it is the cone,
    // or the part of it the camera sees. A caster halfway between the lamp and those receivers
    // must survive OGRE's culling against the texture camera (no depth clamp in OGRE 1.12).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Ogre::AxisAlignedBox box(-60, 0, -60, 60, 20, 60);
    int maps = 0, narrowed = 0, seenInMaps = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const core::Vec3 wsLamp(-30.0 + 60.0 * u(rng), 3.0 + 12.0 * u(rng), -30.0 + 60.0 * u(rng));
        core::Vec3 aim = unitVector(rng);
        aim.y = -0.3 - std::abs(aim.y);
        const double cone = 20.0 + 100.0 * u(rng), range = 15.0 + 45.0 * u(rng);
        const core::Vec3 wsEye(-40.0 + 80.0 * u(rng), 1.7 + 10.0 * u(rng), -40.0 + 80.0 * u(rng));
        core::Vec3 forward = unitVector(rng);
        forward.y = -0.1 - 0.4 * std::abs(forward.y);
        Ogre::Camera* cam = camera(wsEye, glm::normalize(forward), 60.0, 16.0 / 9.0, 0.3, 300.0);
        Ogre::Light* lamp = spot(wsLamp, glm::normalize(aim), cone, range);
        ShadowCameraSetup setup;
        setup.setSceneBounds(box);
        Ogre::Camera* texCam = m_sm->createCamera("spotmap" + std::to_string(m_cameras++));
        m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(texCam);
        setup.getShadowCamera(m_sm, cam, nullptr, lamp, texCam, 0);
        ASSERT_TRUE(setup.lastSpotSetup()) << setup.lastSpotError();
        const core::ShadowSetup& core = *setup.lastSpotSetup();
        if (core.views.empty()) {
            EXPECT_FALSE(texCam->isCustomProjectionMatrixEnabled()); // OGRE's own camera
            continue;
        }
        ASSERT_TRUE(texCam->isCustomProjectionMatrixEnabled());
        ++maps;
        const core::EngineShadowView gl = core::toEngineView(core.views[0], core, core::OutputConventions::openGL());
        const double halfCone = 0.5 * glm::radians(double(lamp->getSpotlightOuterAngle().valueDegrees()));
        const core::Vec3 axis(lamp->getDerivedDirection().x, lamp->getDerivedDirection().y,
                              lamp->getDerivedDirection().z);
        // The map's tangent span against OGRE's own spot camera's, 2 tan(1.2 × half the cone).
        const core::Mat4& clipFromLight = core.views[0].clipFromLight;
        const double span = std::max(2.0 / clipFromLight[0][0], 2.0 / clipFromLight[1][1]);
        EXPECT_LE(span, 2.0 * std::tan(1.2 * halfCone) + 1e-9);
        if (span < 0.999 * 2.0 * std::tan(halfCone)) ++narrowed;
        int seen = 0;
        // Points inside the cone and range, kept where the box and the camera's view hold them.
        const core::Vec3 side =
            glm::normalize(glm::cross(axis, std::abs(axis.y) < 0.9 ? core::Vec3(0, 1, 0) : core::Vec3(1, 0, 0)));
        const core::Vec3 up = glm::cross(side, axis);
        for (int sample = 0; sample < 4000; ++sample) {
            const double a = 2.0 * u(rng) - 1.0, b = 2.0 * u(rng) - 1.0;
            if (a * a + b * b > 1.0) continue;
            const core::Vec3 ray = glm::normalize(axis + std::tan(halfCone) * (a * side + b * up));
            const core::Vec3 p = wsLamp + range * u(rng) * ray;
            const core::Vec3 toPoint = p - wsLamp;
            if (p.x < -60 || p.x > 60 || p.y < 0 || p.y > 20 || p.z < -60 || p.z > 60 || !inView(*cam, p, 300.0))
                continue;
            ++seen;
            // OGRE's float matrices hold the lamp's frame to a few micrometres (coordinates of tens
            // of metres), which near the apex is a large share of a texel; a wrong convention
            // moves points by hundreds of texels.
            const double tolerance = 5e-3 + 2e-5 / (span * glm::dot(toPoint, axis) / 2048);
            const core::Vec3 texel = expectInTheMapOnTheCoresTexel(*texCam, gl, p, tolerance);
            // Depth: in the map, or in front of it where R reaches the lamp (a caster there is
            // flattened onto the near plane).
            if (glm::dot(toPoint, axis) > 0.3) {
                EXPECT_GE(texel.z, 0.0);
            }
            // A caster on the way to the lamp, just beyond OGRE's default near distance from it
            // (the camera's near, 0.3 m, along the lamp's axis).
            const core::Vec3 caster = wsLamp + toPoint * (0.31 / glm::dot(toPoint, axis));
            const Ogre::Vector3 at(Ogre::Real(caster.x), Ogre::Real(caster.y), Ogre::Real(caster.z));
            EXPECT_TRUE(texCam->isVisible(Ogre::AxisAlignedBox(at - 0.005f, at + 0.005f)));
        }
        seenInMaps += seen;
    }
    EXPECT_GE(maps, 10);
    EXPECT_GE(seenInMaps, 1000);
    EXPECT_GE(narrowed, 3); // the camera sees part of the cone: the map narrows to it
}

// A point of the camera's view (worldFromClip), drawn uniformly in its clip space, if it lies in the
// yard's box and within `range` of the lamp, but not within 0.3 m of it.
std::optional<core::Vec3> seenInReach(const core::Mat4& worldFromClip, const core::Vec3& wsLamp, double range,
                                      std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const core::Vec4 h = worldFromClip * core::Vec4(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1, 1.0);
    const core::Vec3 p = core::Vec3(h) / h.w;
    const double distance = glm::distance(p, wsLamp);
    if (p.x < -60 || p.x > 60 || p.y < 0 || p.y > 20 || p.z < -60 || p.z > 60 || distance > range || distance < 0.3)
        return std::nullopt;
    return p;
}

// A lamp over a 120 m yard, 3 m up to 3 + lampHeights, reaching 20–80 m, and an eye among the
// lamps looking 0.1–0.5 below level.
struct LampAndEye {
    core::Vec3 wsLamp;
    double range;
    core::Vec3 wsEye, forward;
};
LampAndEye randomLampAndEye(std::mt19937& rng, double lampHeights) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    LampAndEye out;
    out.wsLamp = core::Vec3(-50.0 + 100.0 * u(rng), 3.0 + lampHeights * u(rng), -50.0 + 100.0 * u(rng));
    out.range = 20.0 + 60.0 * u(rng);
    out.wsEye = core::Vec3(-40.0 + 80.0 * u(rng), 1.7 + 10.0 * u(rng), -40.0 + 80.0 * u(rng));
    core::Vec3 forward = unitVector(rng);
    forward.y = -0.1 - 0.4 * std::abs(forward.y);
    out.forward = glm::normalize(forward);
    return out;
}

TEST_F(OgreScene, PointLightMapsHoldWhatTheCameraSeesWhereOgresOwnNeedNot) {
    // Lamps over the forest floor, cameras among them. OGRE 1.12 gives a point light one 120°
    // map aimed from the lamp at a point ahead of the camera; the adapter aims it at what the
    // camera sees within the lamp's range. Every point the camera sees in range and in the box
    // — sampled from the view, not from the set-up — must land in the adapter's map on the
    // core's texel, wherever OGRE's own map lands it, and a caster between it and the lamp must
    // survive OGRE's culling; where that spans more than 170° from the lamp, every such point
    // inside the 170° cone the adapter then aims at the middle of it.
    std::mt19937 rng(13);
    const Ogre::AxisAlignedBox box(-60, 0, -60, 60, 20, 60);
    int maps = 0, partial = 0;
    long seen = 0, heldByAdapter = 0, heldByOgre = 0;
    double logGain = 0.0, logAreaGain = 0.0;
    for (int trial = 0; trial < 40; ++trial) {
        const auto [wsLamp, range, wsEye, forward] = randomLampAndEye(rng, 30.0);
        Ogre::Camera* cam = camera(wsEye, forward, 60.0, 16.0 / 9.0, 0.3, 60.0);
        Ogre::Light* lamp = point(wsLamp, range);
        ShadowCameraSetup setup;
        setup.setSceneBounds(box);
        Ogre::Camera* texCam = m_sm->createCamera("pointmap" + std::to_string(m_cameras++));
        Ogre::Camera* ownCam = m_sm->createCamera("ogrepointmap" + std::to_string(m_cameras++));
        m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(texCam);
        m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(ownCam);
        setup.getShadowCamera(m_sm, cam, nullptr, lamp, texCam, 0);
        Ogre::DefaultShadowCameraSetup().getShadowCamera(m_sm, cam, nullptr, lamp, ownCam, 0);
        ASSERT_TRUE(setup.lastPointSetup()) << setup.lastPointError();
        const core::ShadowSetup& core = *setup.lastPointSetup();
        if (core.views.empty()) {
            EXPECT_FALSE(texCam->isCustomProjectionMatrixEnabled());
            continue;
        }
        ASSERT_TRUE(texCam->isCustomProjectionMatrixEnabled());
        ++maps;
        const bool part = !core.fallbacks.empty(); // a map over part of what the camera sees says so
        partial += part;
        const core::EngineShadowView gl = core::toEngineView(core.views[0], core, core::OutputConventions::openGL());
        // Texels per metre gained along an axis against OGRE's 120° map: the tangent spans' ratio.
        const core::Mat4& clipFromLight = core.views[0].clipFromLight;
        const double width = 2.0 / clipFromLight[0][0], height = 2.0 / clipFromLight[1][1];
        const double span = std::max(width, height), ownSpan = 2.0 * std::tan(glm::radians(60.0));
        logGain += std::log(ownSpan / span);
        logAreaGain += std::log(ownSpan * ownSpan / (width * height));
        const core::Vec3 axis =
            -glm::normalize(core::Vec3(glm::inverse(core.views[0].lightFromWorld) * core::Vec4(0.0, 0.0, 1.0, 0.0)));
        const core::Mat4 worldFromClip = glm::inverse(clipFromWorldOf(*cam));
        for (int sample = 0; sample < 2000; ++sample) {
            const std::optional<core::Vec3> sampled = seenInReach(worldFromClip, wsLamp, range, rng);
            if (!sampled) continue;
            const core::Vec3 p = *sampled, toPoint = p - wsLamp;
            ++seen;
            const core::Vec3 own = texelOf(*ownCam, p, 2048);
            heldByOgre += own.x >= 0 && own.x <= 2048 && own.y >= 0 && own.y <= 2048;
            if (part && glm::dot(glm::normalize(toPoint), axis) < std::cos(glm::radians(85.0))) continue;
            ++heldByAdapter;
            expectInTheMapOnTheCoresTexel(*texCam, gl, p, 5e-3 + 2e-5 / (span * glm::dot(toPoint, axis) / 2048));
            // A caster on the way to the lamp, just beyond OGRE's default near distance from it
            // (the camera's near, 0.3 m, along the map's axis), survives OGRE's culling.
            const core::Vec3 caster = wsLamp + toPoint * (0.31 / glm::dot(toPoint, axis));
            const Ogre::Vector3 at(Ogre::Real(caster.x), Ogre::Real(caster.y), Ogre::Real(caster.z));
            EXPECT_TRUE(texCam->isVisible(Ogre::AxisAlignedBox(at - 0.005f, at + 0.005f)));
        }
    }
    EXPECT_GE(maps, 10);
    EXPECT_GE(partial, 1); // some lamps stand among what the camera sees
    EXPECT_GE(seen, 5000);
    EXPECT_GT(heldByAdapter, heldByOgre); // OGRE's fixed 120° aim leaves more of what the camera sees out
    std::printf("%d point lights mapped, %d of them over part of what the camera sees; of %ld points seen in "
                "range, the adapter's maps held %ld, OGRE's own %ld; against OGRE's map, geometric means: texels "
                "per metre on the coarser axis x%.2f, texels x%.2f\n",
                maps, partial, seen, heldByAdapter, heldByOgre, std::exp(logGain / std::max(maps, 1)),
                std::exp(logAreaGain / std::max(maps, 1)));
}

TEST_F(OgreScene, BadSpotsKeepOgresCameraAndALampAmongTheViewGetsAnAimedMap) {
    // A spot of more than the core's 170°: said in the log once, and OGRE's own camera draws it.
    // A point light among what the camera sees: the adapter's 170° map aimed at the middle of it,
    // saying it holds only part.
    Ogre::Camera* cam = camera(core::Vec3(0, 2, 10), core::Vec3(0, -0.2, -1), 60.0, 1.5, 0.3, 300.0);
    Ogre::Light* wide = spot(core::Vec3(0, 6, 0), core::Vec3(0, -1, 0), 175.0, 30.0);
    ShadowCameraSetup setup;
    setup.setSceneBounds(Ogre::AxisAlignedBox(-60, 0, -60, 60, 20, 60));
    Ogre::Camera* texCam = m_sm->createCamera("wide" + std::to_string(m_cameras++));
    m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(texCam);
    setup.getShadowCamera(m_sm, cam, nullptr, wide, texCam, 0);
    EXPECT_FALSE(setup.lastSpotSetup());
    // Named as OGRE's user set it: the outer angle.
    EXPECT_EQ(setup.lastSpotError().rfind("spot light outer angle 175 degrees: ", 0), 0u) << setup.lastSpotError();
    EXPECT_EQ(setup.lastSpotError().find('\n'), std::string::npos);
    EXPECT_FALSE(texCam->isCustomProjectionMatrixEnabled());
    EXPECT_TRUE(setup.lastError().empty()); // the sun's error is its own

    Ogre::Light* bulb = m_sm->createLight();
    bulb->setType(Ogre::Light::LT_POINT);
    m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(bulb);
    setup.getShadowCamera(m_sm, cam, nullptr, bulb, texCam, 0);
    EXPECT_TRUE(texCam->isCustomProjectionMatrixEnabled());
    EXPECT_FALSE(setup.lastSetup());
    ASSERT_TRUE(setup.lastPointSetup()) << setup.lastPointError();
    ASSERT_FALSE(setup.lastPointSetup()->fallbacks.empty());
    EXPECT_NE(setup.lastPointSetup()->fallbacks.back().find("aimed at the middle"), std::string::npos);
}

TEST_F(OgreScene, StaysFiniteWithTheSunAlongTheViewDirection) {
    const core::Vec3 travel = glm::normalize(core::Vec3(0.3, -1.0, 0.2));
    for (const double sign : {1.0, -1.0})
        for (const core::Technique technique : {core::Technique::Tsm, core::Technique::Lispsm, core::Technique::Psm,
                                                core::Technique::Focused, core::Technique::Csm}) {
            Ogre::Camera* cam = camera(core::Vec3(10.0, 120.0, -20.0), travel * sign, 60.0, 1.5, 0.5, 500.0);
            Ogre::Light* light = sun(travel);
            ShadowCameraSetup setup;
            setUpForTheForest(setup, technique);
            Ogre::Camera* texCam = m_sm->createCamera("texture" + std::to_string(m_cameras++));
            setup.getShadowCamera(m_sm, cam, nullptr, light, texCam, 0);
            ASSERT_TRUE(setup.lastSetup()) << setup.lastError();
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) {
                    EXPECT_TRUE(std::isfinite(texCam->getProjectionMatrix()[r][c])) << core::techniqueName(technique);
                    EXPECT_TRUE(std::isfinite(texCam->getViewMatrix()[r][c])) << core::techniqueName(technique);
                }
            const core::Vec3 ground = texelOf(*texCam, core::Vec3(10.0, 0.0, -20.0), 2048);
            EXPECT_GE(ground.x, 0.0) << core::techniqueName(technique);
            EXPECT_LE(ground.x, 2048.0) << core::techniqueName(technique);
            EXPECT_GE(ground.y, 0.0) << core::techniqueName(technique);
            EXPECT_LE(ground.y, 2048.0) << core::techniqueName(technique);
        }
}

TEST_F(OgreScene, TheDefaultSceneBoxHoldsTheGeometryNotTheCameras) {
    // A 100 m box of geometry, and a camera whose own box reaches its far plane 100 km away: the
    // root node's world box takes the camera's, which made every warped map of the first OGRE
    // sample hopelessly coarse. The set-up's box must be the geometry's.
    geometry();
    Ogre::Camera* cam = camera(core::Vec3(0, 20, 0), core::Vec3(0, -0.3, -1), 60.0, 1.5, 0.5, 100000.0);
    sun(core::Vec3(0.3, -1, 0.2));
    m_sm->getRootSceneNode()->_update(true, false);
    ASSERT_GT(m_sm->getRootSceneNode()->_getWorldAABB().getSize().length(), 1000.0); // the cameras' box is in there

    const Ogre::AxisAlignedBox bounds = shadowkit::ogreadapter::sceneBounds(*m_sm->getRootSceneNode());
    EXPECT_NEAR(bounds.getMinimum().x, -50, 1e-4);
    EXPECT_NEAR(bounds.getMaximum().x, 50, 1e-4);
    EXPECT_NEAR(bounds.getMinimum().y, 0, 1e-4);
    EXPECT_NEAR(bounds.getMaximum().y, 20, 1e-4);
    EXPECT_NEAR(bounds.getMinimum().z, -50, 1e-4);
    EXPECT_NEAR(bounds.getMaximum().z, 50, 1e-4);
    (void)cam;
}

TEST_F(OgreScene, APointLightAsCubeFacesHoldsEveryPointTheCameraSeesInItsFace) {
    // With setPointLightCubeFaces, a lamp's six shadow textures are the cube faces that see
    // something of the view, then maps of nothing. Every point the camera sees in range — lamps
    // among the view too, which one map cannot hold whole — lands in the texture of its own face
    // (core::cubeFaceOf) on the core's texel; every point of the box lies outside each map of
    // nothing (behind its camera or beyond its sides), so a receiver shader that multiplies the
    // textures' terms reads them lit.
    std::mt19937 rng(17);
    const Ogre::AxisAlignedBox box(-60, 0, -60, 60, 20, 60);
    int lamps = 0, among = 0, empties = 0;
    long held = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const auto [wsLamp, range, wsEye, forward] = randomLampAndEye(rng, 15.0);
        Ogre::Camera* cam = camera(wsEye, forward, 60.0, 16.0 / 9.0, 0.3, 60.0);
        Ogre::Light* lamp = point(wsLamp, range);
        ShadowCameraSetup setup;
        setup.setSceneBounds(box);
        setup.setPointLightCubeFaces(true);
        std::vector<Ogre::Camera*> texCams;
        for (size_t iteration = 0; iteration < 6; ++iteration) {
            texCams.push_back(m_sm->createCamera("face" + std::to_string(m_cameras++)));
            m_sm->getRootSceneNode()->createChildSceneNode()->attachObject(texCams.back());
            setup.getShadowCamera(m_sm, cam, nullptr, lamp, texCams.back(), iteration);
        }
        ASSERT_TRUE(setup.lastPointSetup()) << setup.lastPointError();
        const core::ShadowSetup& cube = *setup.lastPointSetup();
        if (cube.views.empty()) continue;
        ++lamps;
        // Whether one map could hold it (the engine shots' `among` lamps).
        core::PerspectiveCamera view;
        view.wsEye = wsEye;
        view.wsDirection = forward;
        view.fovYDegrees = 60.0, view.aspect = 16.0 / 9.0, view.zNear = 0.3, view.zFar = 60.0;
        among += !core::computePointSingleMapSetup(
            core::LocalShadowInputs{
                .camera = view, .wsSceneBounds = core::Aabb::fromMinMax({-60, 0, -60}, {60, 20, 60}), .mapSize = 2048},
            core::PointLight{.wsPosition = wsLamp, .range = range});
        const core::Mat4 worldFromClip = glm::inverse(clipFromWorldOf(*cam));
        for (int sample = 0; sample < 2000; ++sample) {
            const std::optional<core::Vec3> sampled = seenInReach(worldFromClip, wsLamp, range, rng);
            if (!sampled) continue;
            const core::Vec3 p = *sampled, toPoint = p - wsLamp;
            const int face = core::cubeFaceOf(toPoint);
            size_t view = 0;
            while (view < cube.views.size() && cube.views[view].face != face) ++view;
            ASSERT_LT(view, cube.views.size()) << "a seen point's face was left out";
            const core::EngineShadowView gl =
                core::toEngineView(cube.views[view], cube, core::OutputConventions::openGL());
            expectInTheMapOnTheCoresTexel(*texCams[view], gl, p, 5e-3 + 2e-5 * 2048 / glm::length(toPoint));
            ++held;
            for (size_t nothing = cube.views.size(); nothing < 6; ++nothing) {
                const core::Vec4 c = clipFromWorldOf(*texCams[nothing]) * core::Vec4(p, 1.0);
                EXPECT_TRUE(c.w <= 0.0 || std::abs(c.x) > c.w || std::abs(c.y) > c.w) << "a map of nothing holds p";
            }
        }
        empties += int(6 - cube.views.size());
    }
    EXPECT_GE(lamps, 10);
    EXPECT_GE(among, 3);
    EXPECT_GE(empties, 10);
    EXPECT_GE(held, 5000);
    std::printf("%d point lights as cube faces (%d of them among what the camera sees, where one map holds only part): "
                "%ld points seen in range, each in its face's texture on the core's texel; %d maps of nothing\n",
                lamps, among, held, empties);
}

TEST_F(OgreScene, TheSceneIsWalkedOnceARenderHoweverManyLightsCast) {
    // A sun (four cascades) and six lamps ask for their cameras as OGRE renders the scene: one
    // walk of the scene graph for its box. A render asks for each light's texture once, so the
    // same asks again are a new render, walked again; and a box moved 30 m before it is in that
    // render's set-ups, which equal a fresh adapter's (the kept box is never stale).
    Ogre::SceneNode* boxNode = geometry();
    Ogre::Camera* cam = camera(core::Vec3(0, 20, 60), core::Vec3(0, -0.3, -1), 60.0, 1.5, 0.5, 300.0);
    Ogre::Light* sunLight = sun(core::Vec3(0.3, -1, 0.2));
    std::vector<Ogre::Light*> lamps;
    for (int i = 0; i < 6; ++i)
        lamps.push_back(i % 2 ? point(core::Vec3(-40.0 + 16.0 * i, 8.0, -10.0), 30.0)
                              : spot(core::Vec3(-40.0 + 16.0 * i, 8.0, -10.0), core::Vec3(0, -1, 0), 90.0, 30.0));
    m_sm->getRootSceneNode()->_update(true, false);
    ShadowCameraSetup setup;
    core::ShadowSetupInputs options;
    options.technique = core::Technique::Csm;
    ASSERT_TRUE(setup.setInputs(options));
    Ogre::Camera* texCam = m_sm->createCamera("walks");
    const auto frame = [&](ShadowCameraSetup& adapter) {
        for (size_t iteration = 0; iteration < 4; ++iteration)
            adapter.getShadowCamera(m_sm, cam, nullptr, sunLight, texCam, iteration);
        std::vector<core::Mat4> lampViews;
        for (Ogre::Light* lamp : lamps) {
            adapter.getShadowCamera(m_sm, cam, nullptr, lamp, texCam, 0);
            const auto& last =
                lamp->getType() == Ogre::Light::LT_POINT ? adapter.lastPointSetup() : adapter.lastSpotSetup();
            if (last && !last->views.empty()) lampViews.push_back(last->views[0].clipFromWorld);
        }
        std::vector<core::Mat4> sunViews;
        for (const core::ShadowView& view : adapter.lastSetup()->views) sunViews.push_back(view.clipFromWorld);
        return std::pair(sunViews, lampViews);
    };
    const auto first = frame(setup);
    EXPECT_EQ(setup.sceneWalks(), 1);
    EXPECT_EQ(first.second.size(), 6u);
    // The next render, in the same frame of OGRE's (an application rendering its targets itself),
    // after the box moved.
    boxNode->setPosition(0, 0, -30);
    m_sm->getRootSceneNode()->_update(true, false);
    const auto moved = frame(setup);
    EXPECT_EQ(setup.sceneWalks(), 2);
    ShadowCameraSetup fresh;
    ASSERT_TRUE(fresh.setInputs(options));
    const auto wanted = frame(fresh);
    EXPECT_EQ(moved.first, wanted.first);
    EXPECT_EQ(moved.second, wanted.second);
    EXPECT_NE(moved, first); // the maps follow the box
    // A new frame of OGRE's whose one caster was not asked for before: walked again too.
    s_root->_fireFrameRenderingQueued();
    Ogre::Light* late = point(core::Vec3(30, 8, 10), 30.0);
    const long walks = setup.sceneWalks();
    setup.getShadowCamera(m_sm, cam, nullptr, late, texCam, 0);
    EXPECT_EQ(setup.sceneWalks(), walks + 1);
    setup.getShadowCamera(m_sm, cam, nullptr, sunLight, texCam, 0); // and kept for the rest of it
    EXPECT_EQ(setup.sceneWalks(), walks + 1);
}

TEST_F(OgreScene, AutoChoosesForTheReceiversItIsHandedAsTheCoreWould) {
    // `auto` inside OGRE: without receivers the recommended technique; with them, what the
    // core's own chooser picks for the same camera, sun, box and receivers, and the texture
    // camera of that choice's set-up.
    Ogre::Camera* cam = camera(core::Vec3(0.0, 8.0, 0.0), core::Vec3(0.0, -0.25, -1.0), 60.0, 16.0 / 9.0, 0.5, 400.0);
    Ogre::Light* light = sun(core::Vec3(0.6, -0.5, 0.2));
    ShadowCameraSetup setup;
    setup.setSceneBounds(kForestBox);
    core::AutoOptions options;
    options.cascades = 1; // one shadow texture
    ASSERT_TRUE(setup.setAuto(options));
    Ogre::Camera* texCam = m_sm->createCamera("texture" + std::to_string(m_cameras++));
    setup.getShadowCamera(m_sm, cam, nullptr, light, texCam, 0);
    ASSERT_TRUE(setup.lastSetup()) << setup.lastError();
    ASSERT_TRUE(setup.lastChoice());
    EXPECT_EQ(setup.lastChoice()->inputs.technique, core::defaultTechnique());

    // The ground the camera looks at, 2 to 300 m ahead and 40 m to each side, facing up.
    std::vector<core::ReceiverSample> receivers;
    for (double z = 2.0; z < 300.0; z *= 1.08)
        for (double x = -40.0; x <= 40.0; x += 4.0) receivers.push_back({core::Vec3(x, 0.0, -z), core::Vec3(0, 1, 0)});
    ShadowCameraSetup fresh; // a chooser with no history, as the reference's
    fresh.setSceneBounds(kForestBox);
    ASSERT_TRUE(fresh.setAuto(options));
    fresh.setReceivers(receivers, 320, 180);
    fresh.getShadowCamera(m_sm, cam, nullptr, light, texCam, 0);
    ASSERT_TRUE(fresh.lastSetup()) << fresh.lastError();
    ASSERT_TRUE(fresh.lastChoice());

    const auto inputs = shadowkit::ogreadapter::inputsFor(cam->getViewMatrix(), cam->getProjectionMatrix(), INFINITY,
                                                          light->getDerivedDirection(), kForestBox, {});
    ASSERT_TRUE(inputs) << inputs.error();
    core::AutoChooser reference(options);
    const auto choice = reference.choose(*inputs, 320, 180, receivers);
    ASSERT_TRUE(choice) << choice.error();
    EXPECT_EQ(fresh.lastChoice()->inputs.technique, choice->inputs.technique);
    EXPECT_GT(fresh.lastChoice()->predicted.samples, 0u); // judged by the receivers (here LiSPSM, not TSM)
    EXPECT_EQ(fresh.lastSetup()->views.size(), 1u);
    core::ShadowSetupInputs chosen = choice->inputs;
    chosen.depthLayout = core::DepthLayout::Hyperbolic;
    const auto expected = core::computeShadowSetup(chosen);
    ASSERT_TRUE(expected) << expected.error();
    for (const core::Vec3& p : {core::Vec3(0, 0, -10), core::Vec3(20, 0, -150), core::Vec3(-30, 10, -60)}) {
        const core::Vec3 got = texelOf(*texCam, p, 2048);
        const auto want = shadowkit::ogreadapter::textureCameraOf(*expected, 0);
        Ogre::Camera* wantCam = m_sm->createCamera("want" + std::to_string(m_cameras++));
        wantCam->setCustomViewMatrix(true, want.viewMatrix);
        wantCam->setCustomProjectionMatrix(true, want.projectionMatrix);
        const core::Vec3 reference3 = texelOf(*wantCam, p, 2048);
        EXPECT_NEAR(got.x, reference3.x, 1e-3) << core::techniqueName(choice->inputs.technique);
        EXPECT_NEAR(got.y, reference3.y, 1e-3);
        EXPECT_NEAR(got.z, reference3.z, 1e-6);
    }

    core::AutoOptions invalid;
    invalid.cascades = 9;
    const core::Status refused = fresh.setAuto(invalid);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("cascades"), std::string::npos) << refused.error();
    EXPECT_EQ(refused.error().find('\n'), std::string::npos);
}

TEST_F(OgreScene, RefusesVirtualAndAnEmptySceneInOneLine) {
    ShadowCameraSetup setup;
    core::ShadowSetupInputs options;
    options.technique = core::Technique::Virtual;
    const core::Status refused = setup.setInputs(options);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("virtual"), std::string::npos);
    EXPECT_EQ(refused.error().find('\n'), std::string::npos);
    EXPECT_EQ(setup.inputs().technique, core::defaultTechnique()); // unchanged

    // An empty scene (a null box) has no set-up; getShadowCamera then gives the frame OGRE's
    // default camera, which needs a render system's viewport and is OGRE's to test.
    Ogre::Camera* cam = camera(core::Vec3(0, 20, 0), core::Vec3(0, 0, -1), 60.0, 1.5, 0.5, 500.0);
    auto empty = shadowkit::ogreadapter::setupFor(cam->getViewMatrix(), cam->getProjectionMatrix(), INFINITY,
                                                  Ogre::Vector3(0, -1, 0.3f), Ogre::AxisAlignedBox(), {});
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.error().find("scene bounds"), std::string::npos) << empty.error();
    auto infinite = shadowkit::ogreadapter::setupFor(cam->getViewMatrix(), cam->getProjectionMatrix(), INFINITY,
                                                     Ogre::Vector3(0, -1, 0.3f),
                                                     Ogre::AxisAlignedBox(Ogre::AxisAlignedBox::EXTENT_INFINITE), {});
    ASSERT_FALSE(infinite);
    auto noLight = shadowkit::ogreadapter::setupFor(cam->getViewMatrix(), cam->getProjectionMatrix(), INFINITY,
                                                    Ogre::Vector3::ZERO, kForestBox, {});
    ASSERT_FALSE(noLight);
    EXPECT_NE(noLight.error().find("light direction"), std::string::npos) << noLight.error();
}

} // namespace
