// The OGRE adapter's one idea: a texture-shadow camera from shadowkit::core, the sun's, a
// spot light's or a point light's (shadow_camera_setup.h).
#include "shadowkit/ogre/shadow_camera_setup.h"

#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/output_conventions.h"

#include <OgreCamera.h>
#include <OgreFrustum.h>
#include <OgreLight.h>
#include <OgreLogManager.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace shadowkit::ogreadapter {

namespace {

// OGRE's m[row][column] for column vectors is glm's m[column][row]: one transpose, in double.
template <class OgreMatrix>
core::Mat4 toCore(const OgreMatrix& m) {
    core::Mat4 out(1.0);
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) out[column][row] = double(m[row][column]);
    return out;
}

core::Vec3 toCore(const Ogre::Vector3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// The camera and scene box every set-up reads, converted and checked: a local light's inputs.
core::Result<core::LocalShadowInputs> viewInputsFor(const Ogre::Affine3& viewFromWorld,
                                                    const Ogre::Matrix4& clipFromView, double shadowDistance,
                                                    const Ogre::AxisAlignedBox& wsSceneBounds) {
    if (!wsSceneBounds.isFinite() || wsSceneBounds.isNull())
        return core::Error{"scene bounds: empty or infinite (nothing in the scene, or an infinite object in it)",
                           "scene_bounds"};
    // OGRE's standard projection: OpenGL's clip depth, a right-handed view looking down −Z.
    core::EngineCamera engine{toCore(viewFromWorld), toCore(clipFromView), core::ClipDepthRange::MinusOneToOne};
    engine.shadowDistance = shadowDistance;
    auto camera = core::cameraFromMatrices(engine);
    if (!camera) return camera.errorInfo();
    core::LocalShadowInputs out;
    out.camera = *camera;
    out.wsSceneBounds = core::Aabb::fromMinMax(toCore(wsSceneBounds.getMinimum()), toCore(wsSceneBounds.getMaximum()));
    return out;
}

} // namespace

core::Status checkTechnique(core::Technique technique) {
    if (technique == core::Technique::Virtual)
        return core::Error{"technique virtual: OGRE draws a fixed number of shadow textures per light, not pages; use "
                           "tsm, lispsm, psm, focused, standard or csm",
                           "technique"};
    return core::Ok{};
}

core::Result<core::ShadowSetupInputs> inputsFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                                double shadowDistance, const Ogre::Vector3& wsLightDirection,
                                                const Ogre::AxisAlignedBox& wsSceneBounds,
                                                core::ShadowSetupInputs options) {
    auto view = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!view) return view.errorInfo();
    auto light = core::DirectionalLight::fromDirection(toCore(wsLightDirection));
    if (!light) return light.errorInfo();
    options.camera = view->camera;
    options.light = *light;
    options.wsSceneBounds = view->wsSceneBounds;
    // OGRE's casters write the rasteriser's depth; TSM's linear depth would need our shader.
    options.depthLayout = core::DepthLayout::Hyperbolic;
    return options;
}

core::Result<core::ShadowSetup> setupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                         double shadowDistance, const Ogre::Vector3& wsLightDirection,
                                         const Ogre::AxisAlignedBox& wsSceneBounds, core::ShadowSetupInputs options) {
    if (auto usable = checkTechnique(options.technique); !usable) return usable.errorInfo();
    auto inputs = inputsFor(viewFromWorld, clipFromView, shadowDistance, wsLightDirection, wsSceneBounds, options);
    if (!inputs) return inputs.errorInfo();
    auto setup = core::computeShadowSetup(*inputs);
    if (!setup) return setup.errorInfo();
    if (setup->views.empty()) return core::Error{"the set-up has no shadow map for this view", "technique"};
    return setup;
}

core::Result<core::ShadowSetup> spotSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                             double shadowDistance, const Ogre::Vector3& wsPosition,
                                             const Ogre::Vector3& wsDirection, Ogre::Radian outerAngle, double range,
                                             const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize) {
    auto inputs = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!inputs) return inputs.errorInfo();
    inputs->mapSize = mapSize;
    core::SpotLight spot;
    spot.wsPosition = toCore(wsPosition);
    spot.wsDirection = toCore(wsDirection);
    spot.coneDegrees = double(outerAngle.valueDegrees()); // OGRE's spot angles are full angles
    spot.range = range;
    auto setup = core::computeSpotShadowSetup(*inputs, spot);
    // The core names its own field ("spot.cone"); an OGRE user set the outer angle.
    if (!setup && setup.errorInfo().field == "spot.cone") {
        char message[160];
        std::snprintf(message, sizeof message,
                      "spot light outer angle %g degrees: shadowkit's spot maps take an outer angle in (0, 170]",
                      spot.coneDegrees);
        return core::Error{message, "spot.cone"};
    }
    return setup;
}

namespace {
// A point light's set-up by `compute` (one map, or the cube) for OGRE's camera.
core::Result<core::ShadowSetup>
pointLightSetup(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView, double shadowDistance,
                const Ogre::Vector3& wsPosition, double range, const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize,
                core::Result<core::ShadowSetup> (*compute)(const core::LocalShadowInputs&, const core::PointLight&)) {
    auto inputs = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!inputs) return inputs.errorInfo();
    inputs->mapSize = mapSize;
    return compute(*inputs, core::PointLight{.wsPosition = toCore(wsPosition), .range = range});
}
} // namespace

core::Result<core::ShadowSetup> pointSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                              double shadowDistance, const Ogre::Vector3& wsPosition, double range,
                                              const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize) {
    return pointLightSetup(viewFromWorld, clipFromView, shadowDistance, wsPosition, range, wsSceneBounds, mapSize,
                           core::computePointSingleOrAimedMapSetup);
}

core::Result<core::ShadowSetup> cubeSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                             double shadowDistance, const Ogre::Vector3& wsPosition, double range,
                                             const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize) {
    return pointLightSetup(viewFromWorld, clipFromView, shadowDistance, wsPosition, range, wsSceneBounds, mapSize,
                           core::computePointShadowSetup);
}

Ogre::AxisAlignedBox sceneBounds(const Ogre::SceneNode& node) {
    Ogre::AxisAlignedBox bounds;
    // By class, not by type flags: an object made without a factory (a ManualObject of its
    // own) reports every flag.
    for (const Ogre::MovableObject* object : node.getAttachedObjects()) {
        const bool geometry = !dynamic_cast<const Ogre::Frustum*>(object) && !dynamic_cast<const Ogre::Light*>(object);
        if (geometry && object->isVisible()) bounds.merge(object->getWorldBoundingBox(true));
    }
    for (const Ogre::Node* child : node.getChildren())
        if (const auto* sceneNode = dynamic_cast<const Ogre::SceneNode*>(child)) bounds.merge(sceneBounds(*sceneNode));
    return bounds;
}

TextureCamera textureCameraOf(const core::ShadowSetup& setup, size_t view) {
    const core::ShadowView& v = setup.views[view];
    const core::EngineShadowView gl = core::toEngineView(v, setup, core::OutputConventions::openGL());
    const core::Mat4 clipFromLight = gl.clipFromWorld * glm::inverse(v.lightFromWorld);
    double rows[12];
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column) rows[row * 4 + column] = v.lightFromWorld[column][row];
    TextureCamera out{Ogre::Affine3(rows), Ogre::Matrix4()};
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column)
            out.projectionMatrix[row][column] = Ogre::Real(clipFromLight[column][row]);
    return out;
}

core::Status ShadowCameraSetup::setInputs(const core::ShadowSetupInputs& inputs) {
    if (auto usable = checkTechnique(inputs.technique); !usable) return usable;
    m_inputs = inputs;
    return core::Ok{};
}

core::Status ShadowCameraSetup::setAuto(const core::AutoOptions& options) {
    if (auto valid = core::validate(options); !valid) return valid;
    m_chooser.emplace(options);
    m_lastChoice.reset();
    return core::Ok{};
}

void ShadowCameraSetup::setReceivers(std::vector<core::ReceiverSample> receivers, int width, int height) {
    m_receivers = std::move(receivers);
    m_receiverWidth = width, m_receiverHeight = height;
}

core::Result<core::ShadowSetup> ShadowCameraSetup::setupOf(const core::ShadowSetupInputs& frame) const {
    core::ShadowSetupInputs inputs = frame;
    if (m_chooser) {
        auto choice =
            m_chooser->choose(frame, std::max(m_receiverWidth, 1), std::max(m_receiverHeight, 1), m_receivers);
        if (!choice) return choice.errorInfo();
        m_lastChoice = *choice;
        inputs = choice->inputs;
        inputs.depthLayout = core::DepthLayout::Hyperbolic; // what OGRE's rasteriser writes
    }
    auto setup = core::computeShadowSetup(inputs);
    if (!setup) return setup.errorInfo();
    if (setup->views.empty()) return core::Error{"the set-up has no shadow map for this view", "technique"};
    return setup;
}

Ogre::AxisAlignedBox ShadowCameraSetup::boundsOf(const Ogre::SceneManager* sm, const Ogre::Light* light,
                                                 size_t iteration) const {
    if (m_fixedBounds) return *m_fixedBounds;
    // OGRE asks once for each light and shadow texture when it renders the scene, and nothing
    // moves between those asks: the walk made at a render's first is kept for the rest. A new
    // render shows as a new frame (Ogre::Root's frame number, as OGRE applies its animations once
    // a frame) or, for an application that renders targets itself, as a light and texture asked
    // again.
    const Ogre::Root* root = Ogre::Root::getSingletonPtr();
    const unsigned long frame = root ? root->getNextFrameNumber() : 0;
    const std::pair asked(light, iteration);
    const bool sameRender =
        root && m_sceneWalks > 0 && m_walkedFor == sm && m_walkedFrame == frame &&
        std::find(m_askedSinceWalk.begin(), m_askedSinceWalk.end(), asked) == m_askedSinceWalk.end();
    if (sameRender) {
        m_askedSinceWalk.push_back(asked);
        return m_walkedBounds;
    }
    // Not the root node's world box: it holds the cameras' boxes, which reach their far planes.
    // OGRE hands the set-up a const scene manager, whose getRootSceneNode is not const though
    // it only returns the node.
    m_walkedBounds = sceneBounds(*const_cast<Ogre::SceneManager*>(sm)->getRootSceneNode());
    m_walkedFor = sm, m_walkedFrame = frame;
    m_askedSinceWalk.assign(1, asked);
    ++m_sceneWalks;
    return m_walkedBounds;
}

void ShadowCameraSetup::report(const std::string& error, std::string& last) {
    if (!error.empty() && error != last) Ogre::LogManager::getSingleton().logWarning("shadowkit: " + error);
    last = error;
}

bool ShadowCameraSetup::spotCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Light* light,
                                   Ogre::Camera* texCam) const {
    const double far = sm->getShadowFarDistance();
    auto setup = spotSetupFor(cam->getViewMatrix(), cam->getProjectionMatrix(),
                              far > 0.0 ? far : std::numeric_limits<double>::infinity(), light->getDerivedPosition(),
                              light->getDerivedDirection(), light->getSpotlightOuterAngle(),
                              double(light->getAttenuationRange()), boundsOf(sm, light, 0), m_inputs.mapSize);
    return keepLocal(std::move(setup), m_lastSpotSetup, m_lastSpotError) &&
           localCamera(*m_lastSpotSetup, 0, cam, light, texCam);
}

bool ShadowCameraSetup::pointCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Light* light,
                                    Ogre::Camera* texCam, size_t iteration) const {
    if (m_pointCubeFaces && iteration > 0) {
        // The light's later textures: the faces of the set-up its first computed.
        if (!m_lastPointSetup) return false;
        if (iteration < m_lastPointSetup->views.size())
            return localCamera(*m_lastPointSetup, iteration, cam, light, texCam);
        // No face left: a map of nothing, which every receiver reads as lit. A camera above the
        // scene box looking up, along the world's +Y, holds no caster; every receiver lies
        // behind it (w < 0), outside the map.
        const Ogre::AxisAlignedBox box = boundsOf(sm, light, iteration);
        Ogre::Affine3 view;
        // The camera's −Z (OGRE's forward) turned to the world's +Y: 90° about X.
        view.makeInverseTransform(Ogre::Vector3(0, box.getMaximum().y + 1.0f, 0), Ogre::Vector3::UNIT_SCALE,
                                  Ogre::Quaternion(Ogre::Degree(90), Ogre::Vector3::UNIT_X));
        texCam->setCustomViewMatrix(true, view);
        // 90° with its near plane at 0.1 and no far one: z_clip = −z − 0.2, w = −z.
        texCam->setCustomProjectionMatrix(true, Ogre::Matrix4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -0.2f, 0, 0, -1, 0));
        return true;
    }
    const double far = sm->getShadowFarDistance();
    const double shadowDistance = far > 0.0 ? far : std::numeric_limits<double>::infinity();
    auto setup = m_pointCubeFaces ? cubeSetupFor(cam->getViewMatrix(), cam->getProjectionMatrix(), shadowDistance,
                                                 light->getDerivedPosition(), double(light->getAttenuationRange()),
                                                 boundsOf(sm, light, 0), m_inputs.mapSize)
                                  : pointSetupFor(cam->getViewMatrix(), cam->getProjectionMatrix(), shadowDistance,
                                                  light->getDerivedPosition(), double(light->getAttenuationRange()),
                                                  boundsOf(sm, light, 0), m_inputs.mapSize);
    return keepLocal(std::move(setup), m_lastPointSetup, m_lastPointError) &&
           localCamera(*m_lastPointSetup, 0, cam, light, texCam);
}

bool ShadowCameraSetup::keepLocal(core::Result<core::ShadowSetup> setup, std::optional<core::ShadowSetup>& last,
                                  std::string& lastError) {
    report(setup ? std::string() : setup.error(), lastError);
    last = setup ? std::optional(std::move(*setup)) : std::nullopt;
    return last.has_value();
}

bool ShadowCameraSetup::localCamera(const core::ShadowSetup& setup, size_t view, const Ogre::Camera* cam,
                                    const Ogre::Light* light, Ogre::Camera* texCam) {
    // A light that misses the view lights nothing seen: OGRE's camera draws a map nothing reads.
    if (view >= setup.views.size()) return false;
    TextureCamera camera = textureCameraOf(setup, view);
    // The core's near plane lies just in front of the receivers, casters nearer the light to be
    // clamped to it; OGRE culls them against the texture camera's near plane first and has no
    // depth clamp. So the near plane moves towards the light, where OGRE's own camera for a
    // local light has it (the light's shadow near clip distance; the camera's near by default).
    // Only the depth row changes — x, y and w of a perspective from the light do not depend on
    // the planes — so every receiver keeps its texel. In the core's [0, 1] row z = f / (n − f)
    // · zv + n f / (n − f) the planes are n = m23 / m22 and f = m23 / (m22 + 1); OpenGL's row is
    // −(f + n') / (f − n') · zv − 2 f n' / (f − n').
    const core::Mat4& clipFromLight = setup.views[view].clipFromLight;
    const double zNear = clipFromLight[3][2] / clipFromLight[2][2];
    const double zFar = clipFromLight[3][2] / (clipFromLight[2][2] + 1.0);
    const double nearToLight = std::min(zNear, double(light->_deriveShadowNearClipDistance(cam)));
    camera.projectionMatrix[2][2] = Ogre::Real(-(zFar + nearToLight) / (zFar - nearToLight));
    camera.projectionMatrix[2][3] = Ogre::Real(-2.0 * zFar * nearToLight / (zFar - nearToLight));
    texCam->setCustomViewMatrix(true, camera.viewMatrix);
    texCam->setCustomProjectionMatrix(true, camera.projectionMatrix);
    return true;
}

void ShadowCameraSetup::getShadowCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Viewport* vp,
                                        const Ogre::Light* light, Ogre::Camera* texCam, size_t iteration) const {
    if (light->getType() != Ogre::Light::LT_DIRECTIONAL) {
        const bool ours = light->getType() == Ogre::Light::LT_SPOTLIGHT
                              ? spotCamera(sm, cam, light, texCam)
                              : pointCamera(sm, cam, light, texCam, iteration);
        if (!ours) m_fallback.getShadowCamera(sm, cam, vp, light, texCam, iteration);
        return;
    }
    if (iteration == 0 || !m_lastSetup) {
        const double far = sm->getShadowFarDistance();
        const auto frame = inputsFor(cam->getViewMatrix(), cam->getProjectionMatrix(),
                                     far > 0.0 ? far : std::numeric_limits<double>::infinity(),
                                     light->getDerivedDirection(), boundsOf(sm, light, iteration), m_inputs);
        auto setup = frame ? setupOf(*frame) : core::Result<core::ShadowSetup>(frame.errorInfo());
        // An error is said once per different error; the frame gets OGRE's default camera, not garbage.
        report(setup ? std::string() : setup.error(), m_lastError);
        if (setup)
            m_lastSetup = std::move(*setup);
        else
            m_lastSetup.reset();
    }
    if (!m_lastSetup || iteration >= m_lastSetup->views.size()) {
        // No set-up, or more textures than the technique has maps: those see OGRE's default.
        m_fallback.getShadowCamera(sm, cam, vp, light, texCam, iteration);
        return;
    }
    const TextureCamera camera = textureCameraOf(*m_lastSetup, iteration);
    texCam->setCustomViewMatrix(true, camera.viewMatrix);
    texCam->setCustomProjectionMatrix(true, camera.projectionMatrix);
}

} // namespace shadowkit::ogreadapter
