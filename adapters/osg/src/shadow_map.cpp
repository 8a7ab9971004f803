// The OSG adapter's one idea: VDSM's shadow camera from shadowkit::core (shadow_map.h).
#include "shadowkit/osg/shadow_map.h"

#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/output_conventions.h"

#include <osg/ComputeBoundsVisitor>
#include <osg/Notify>
#include <osgShadow/ShadowedScene>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>

namespace shadowkit::osgadapter {

namespace {

// OSG's row-vector matrix M (v' = v · M) lies in memory as OpenGL's column-major M' with
// v' = M' · v: the same 16 doubles, read in order.
core::Mat4 toCore(const ::osg::Matrixd& m) { return glm::make_mat4(m.ptr()); }
::osg::Matrixd toOsg(const core::Mat4& m) { return ::osg::Matrixd(glm::value_ptr(m)); }

bool isFinite(const ::osg::BoundingBoxd& b) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(b._min[i]) || !std::isfinite(b._max[i])) return false;
    return true;
}

// The camera and scene box every set-up reads, converted and checked: a local light's inputs.
core::Result<core::LocalShadowInputs> viewInputsFor(const ::osg::Matrixd& viewFromWorld,
                                                    const ::osg::Matrixd& clipFromView, double shadowDistance,
                                                    const ::osg::BoundingBoxd& wsSceneBounds) {
    if (!wsSceneBounds.valid() || !isFinite(wsSceneBounds))
        return core::Error{"scene bounds: empty or not finite (nothing under the ShadowedScene?)", "scene_bounds"};
    // OSG's main camera: OpenGL's clip depth, a right-handed view looking down −Z.
    core::EngineCamera engine{toCore(viewFromWorld), toCore(clipFromView), core::ClipDepthRange::MinusOneToOne};
    engine.shadowDistance = shadowDistance;
    auto camera = core::cameraFromMatrices(engine);
    if (!camera) return camera.errorInfo();
    core::LocalShadowInputs out;
    out.camera = *camera;
    out.wsSceneBounds =
        core::Aabb::fromMinMax(core::Vec3(wsSceneBounds.xMin(), wsSceneBounds.yMin(), wsSceneBounds.zMin()),
                               core::Vec3(wsSceneBounds.xMax(), wsSceneBounds.yMax(), wsSceneBounds.zMax()));
    return out;
}

} // namespace

core::Status checkTechnique(core::Technique technique) {
    if (technique == core::Technique::Csm || technique == core::Technique::Virtual)
        return core::Error{"technique " + std::string(core::techniqueName(technique)) +
                               ": OSG's ViewDependentShadowMap draws one map per light; use tsm, lispsm, psm, "
                               "focused or standard",
                           "technique"};
    return core::Ok{};
}

core::Result<core::ShadowSetupInputs> inputsFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                                double shadowDistance, const ::osg::Vec3d& wsLightDirection,
                                                const ::osg::BoundingBoxd& wsSceneBounds,
                                                core::ShadowSetupInputs options) {
    auto view = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!view) return view.errorInfo();
    auto light = core::DirectionalLight::fromDirection(
        core::Vec3(wsLightDirection.x(), wsLightDirection.y(), wsLightDirection.z()));
    if (!light) return light.errorInfo();
    options.camera = view->camera;
    options.light = *light;
    options.wsSceneBounds = view->wsSceneBounds;
    // OSG's caster pass writes the rasteriser's depth; it cannot write TSM's linear depth.
    options.depthLayout = core::DepthLayout::Hyperbolic;
    return options;
}

ShadowCamera shadowCameraOfView(core::ShadowSetup setup) {
    // The light's rigid frame is OSG's view matrix, the rest of the map's clip matrix (in
    // OpenGL's depth range) its projection, so OSG's caster culling sees a light-space frustum.
    const core::ShadowView& view = setup.views[0];
    const core::EngineShadowView gl = core::toEngineView(view, setup, core::OutputConventions::openGL());
    const core::Mat4 clipFromLight = gl.clipFromWorld * glm::inverse(view.lightFromWorld);
    return ShadowCamera{toOsg(view.lightFromWorld), toOsg(clipFromLight), std::move(setup)};
}

core::Result<ShadowCamera> shadowCameraOf(const core::ShadowSetupInputs& inputs) {
    if (auto usable = checkTechnique(inputs.technique); !usable) return usable.errorInfo();
    auto setup = core::computeShadowSetup(inputs);
    if (!setup) return setup.errorInfo();
    if (setup->views.empty()) return core::Error{"the set-up has no shadow map for this view", "technique"};
    return shadowCameraOfView(std::move(*setup));
}

core::Result<ShadowCamera> shadowCameraFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                           double shadowDistance, const ::osg::Vec3d& wsLightDirection,
                                           const ::osg::BoundingBoxd& wsSceneBounds, core::ShadowSetupInputs options) {
    if (auto usable = checkTechnique(options.technique); !usable) return usable.errorInfo();
    auto inputs = inputsFor(viewFromWorld, clipFromView, shadowDistance, wsLightDirection, wsSceneBounds, options);
    if (!inputs) return inputs.errorInfo();
    return shadowCameraOf(*inputs);
}

core::Result<core::ShadowSetup> spotSetupFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                             double shadowDistance, const ::osg::Vec3d& wsPosition,
                                             const ::osg::Vec3d& wsDirection, double spotCutoffDegrees, double range,
                                             const ::osg::BoundingBoxd& wsSceneBounds, int mapSize) {
    auto inputs = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!inputs) return inputs.errorInfo();
    inputs->mapSize = mapSize;
    core::SpotLight spot;
    spot.wsPosition = core::Vec3(wsPosition.x(), wsPosition.y(), wsPosition.z());
    spot.wsDirection = core::Vec3(wsDirection.x(), wsDirection.y(), wsDirection.z());
    spot.coneDegrees = 2.0 * spotCutoffDegrees; // OSG's cutoff is the half-angle
    spot.range = range;
    auto setup = core::computeSpotShadowSetup(*inputs, spot);
    // The core names its own field (the cone, "spot.cone"); an OSG user set the cutoff, half of it.
    if (!setup && setup.errorInfo().field == "spot.cone") {
        char message[160];
        std::snprintf(message, sizeof message,
                      "spot light cutoff %g degrees: shadowkit's spot maps take a cutoff in (0, 85] (a cone of at "
                      "most 170 degrees)",
                      spotCutoffDegrees);
        return core::Error{message, "spot.cone"};
    }
    return setup;
}

core::Result<core::ShadowSetup> pointSetupFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                              double shadowDistance, const ::osg::Vec3d& wsPosition, double range,
                                              const ::osg::BoundingBoxd& wsSceneBounds, int mapSize) {
    auto inputs = viewInputsFor(viewFromWorld, clipFromView, shadowDistance, wsSceneBounds);
    if (!inputs) return inputs.errorInfo();
    inputs->mapSize = mapSize;
    const core::PointLight point{.wsPosition = core::Vec3(wsPosition.x(), wsPosition.y(), wsPosition.z()),
                                 .range = range};
    return core::computePointSingleOrAimedMapSetup(*inputs, point);
}

ShadowMap::ShadowMap() = default;

ShadowMap::ShadowMap(const ShadowMap& other, const ::osg::CopyOp& copyop)
    : osgShadow::ViewDependentShadowMap(other, copyop), m_inputs(other.m_inputs), m_fixedBounds(other.m_fixedBounds),
      m_chooser(other.m_chooser), m_receivers(other.m_receivers), m_receiverWidth(other.m_receiverWidth),
      m_receiverHeight(other.m_receiverHeight), m_reachCutoff(other.m_reachCutoff) {}

core::Status ShadowMap::setAuto(const core::AutoOptions& options) {
    if (options.cascades != 1)
        return core::Error{"auto.cascades: OSG's ViewDependentShadowMap draws one map per light here; use 1",
                           "auto.cascades"};
    if (auto valid = core::validate(options); !valid) return valid;
    m_chooser.emplace(options);
    m_lastChoice.reset();
    return core::Ok{};
}

void ShadowMap::setReceivers(std::vector<core::ReceiverSample> receivers, int width, int height) {
    m_receivers = std::move(receivers);
    m_receiverWidth = width, m_receiverHeight = height;
}

void ShadowMap::init() {
    osgShadow::ViewDependentShadowMap::init();
    // The set-ups fit the map's near plane to what the camera needs, and ask that casters
    // between it and the sun be clamped to it rather than clipped (ShadowSetup::depthClamp).
    if (_shadowCastingStateSet.valid()) _shadowCastingStateSet->setMode(GL_DEPTH_CLAMP, ::osg::StateAttribute::ON);
}

::osg::BoundingBoxd ShadowMap::sceneBounds() {
    if (m_fixedBounds) return *m_fixedBounds;
    osgShadow::ShadowedScene* scene = getShadowedScene();
    if (!scene) return {};
    // The bound sphere is cached by OSG and dirtied by every change below it: a cheap key.
    const ::osg::BoundingSphere& sphere = scene->getBound();
    if (m_cachedBounds.valid() && sphere.center() == m_cachedFor.center() && sphere.radius() == m_cachedFor.radius())
        return m_cachedBounds;
    ::osg::ComputeBoundsVisitor visitor;
    for (unsigned i = 0; i < scene->getNumChildren(); ++i) scene->getChild(i)->accept(visitor);
    const ::osg::BoundingBox& box = visitor.getBoundingBox();
    m_cachedBounds = box.valid() ? ::osg::BoundingBoxd(box._min, box._max) : ::osg::BoundingBoxd();
    m_cachedFor = sphere;
    return m_cachedBounds;
}

namespace {
// The brightest channel a light shines with on a white surface facing it: diffuse or specular.
double brightestChannel(const ::osg::Light& light) {
    double intensity = 0.0;
    for (int channel = 0; channel < 3; ++channel)
        intensity = std::max({intensity, double(light.getDiffuse()[channel]), double(light.getSpecular()[channel])});
    return intensity;
}

// A local light's set-up within its reach: setupWithin(reach) where it reaches past itself, a
// set-up of no view where its attenuation dims it below the cutoff at the light, or the
// attenuation's error.
template <class SetupWithin>
core::Result<core::ShadowSetup> withinReach(const core::Result<double>& reach, core::LightType type,
                                            const ::osg::Vec3d& wsLight, SetupWithin setupWithin) {
    if (!reach) return reach.errorInfo();
    if (*reach > 0.0) return setupWithin(*reach);
    core::ShadowSetup none;
    none.lightType = type;
    none.wsLightPosition = core::Vec3(wsLight.x(), wsLight.y(), wsLight.z());
    none.fallbacks.push_back("its attenuation dims it below the reach cutoff at the light itself: no map");
    return none;
}
} // namespace

core::Result<double> reachOf(const ::osg::Light& light, const ::osg::Vec3d& wsLight, const ::osg::BoundingBoxd& box,
                             double cutoff) {
    double boxReach = 0.0;
    for (unsigned corner = 0; corner < 8; ++corner)
        boxReach = std::max(boxReach, (box.corner(corner) - wsLight).length());
    const core::Attenuation attenuation{.constant = light.getConstantAttenuation(),
                                        .linear = light.getLinearAttenuation(),
                                        .quadratic = light.getQuadraticAttenuation()};
    auto reach = core::attenuationReach(attenuation, brightestChannel(light), cutoff);
    if (reach) return std::min(*reach, boxReach);
    // Named as OSG's user set it: "light 0's linear attenuation -0.5: must be …".
    const core::Error& error = reach.errorInfo();
    const std::string what = error.message.substr(error.message.find(": ") + 2);
    const std::pair<const char*, double> terms[] = {{"attenuation.constant", attenuation.constant},
                                                    {"attenuation.linear", attenuation.linear},
                                                    {"attenuation.quadratic", attenuation.quadratic}};
    for (const auto& [field, value] : terms)
        if (error.field == field) {
            char message[200];
            std::snprintf(message, sizeof message, "light %d's %s attenuation %g: %s", light.getLightNum(),
                          field + std::strlen("attenuation."), value, what.c_str());
            return core::Error{message, error.field};
        }
    return core::Error{"light " + std::to_string(light.getLightNum()) + ": " + error.message, error.field};
}

void setReach(::osg::Light& light, double range, double cutoff) {
    const core::Attenuation attenuation = core::quadraticAttenuationReaching(range, brightestChannel(light), cutoff);
    light.setConstantAttenuation(float(attenuation.constant));
    light.setLinearAttenuation(float(attenuation.linear));
    light.setQuadraticAttenuation(float(attenuation.quadratic));
}

core::Status ShadowMap::setReachCutoff(double cutoff) {
    if (auto valid = core::validateReachCutoff(cutoff); !valid) return valid;
    m_reachCutoff = cutoff;
    return core::Ok{};
}

ShadowMap::SpotOutcome ShadowMap::localOutcome(const core::Result<core::ShadowSetup>& setup,
                                               std::optional<core::ShadowSetup>& last, std::string& lastError,
                                               ::osg::Matrixd& projectionMatrix, ::osg::Matrixd& viewMatrix) {
    // A light the core refuses is the user's setting: said once as a warning.
    if (!setup && setup.error() != lastError) OSG_WARN << "shadowkit: " << setup.error() << std::endl;
    lastError = setup ? std::string() : setup.error();
    last = setup ? std::optional(*setup) : std::nullopt;
    if (!setup) return SpotOutcome::LeftToOsg;
    if (setup->views.empty()) return SpotOutcome::NothingInView;
    const ShadowCamera camera = shadowCameraOfView(*setup);
    viewMatrix = camera.viewMatrix;
    projectionMatrix = camera.projectionMatrix;
    return SpotOutcome::Mapped;
}

ShadowMap::SpotOutcome ShadowMap::spotCamera(const Frustum& frustum, const LightData& light, double shadowDistance,
                                             int mapSize, ::osg::Matrixd& projectionMatrix,
                                             ::osg::Matrixd& viewMatrix) {
    const ::osg::BoundingBoxd box = sceneBounds();
    const auto setup = withinReach(reachOf(*light.light, light.lightPos3, box, m_reachCutoff), core::LightType::Spot,
                                   light.lightPos3, [&](double reach) {
                                       return spotSetupFor(frustum.modelViewMatrix, frustum.projectionMatrix,
                                                           shadowDistance, light.lightPos3, light.lightDir,
                                                           light.light->getSpotCutoff(), reach, box, mapSize);
                                   });
    return localOutcome(setup, m_lastSpotSetup, m_lastSpotError, projectionMatrix, viewMatrix);
}

ShadowMap::SpotOutcome ShadowMap::pointCamera(const Frustum& frustum, const LightData& light, double shadowDistance,
                                              int mapSize, ::osg::Matrixd& projectionMatrix,
                                              ::osg::Matrixd& viewMatrix) {
    const ::osg::BoundingBoxd box = sceneBounds();
    const auto setup = withinReach(reachOf(*light.light, light.lightPos3, box, m_reachCutoff), core::LightType::Point,
                                   light.lightPos3, [&](double reach) {
                                       return pointSetupFor(frustum.modelViewMatrix, frustum.projectionMatrix,
                                                            shadowDistance, light.lightPos3, reach, box, mapSize);
                                   });
    return localOutcome(setup, m_lastPointSetup, m_lastPointError, projectionMatrix, viewMatrix);
}

bool ShadowMap::computeShadowCameraSettings(Frustum& frustum, LightData& light, ::osg::Matrixd& projectionMatrix,
                                            ::osg::Matrixd& viewMatrix) {
    core::ShadowSetupInputs inputs = m_inputs;
    const osgShadow::ShadowSettings* settings = getShadowedScene() ? getShadowedScene()->getShadowSettings() : nullptr;
    if (settings) inputs.mapSize = static_cast<int>(settings->getTextureSize().x());
    const double maxDistance = settings ? settings->getMaximumShadowMapDistance() : std::numeric_limits<double>::max();
    const double shadowDistance =
        maxDistance >= std::numeric_limits<double>::max() ? std::numeric_limits<double>::infinity() : maxDistance;

    m_ownCamera = true;
    // OSG's spot cutoff is half the cone; 180 makes a point light (between them: a spot wider
    // than any map, refused by the core with its cutoff named).
    if (!light.directionalLight) {
        const bool point = light.light->getSpotCutoff() >= 180.0;
        switch (point ? pointCamera(frustum, light, shadowDistance, inputs.mapSize, projectionMatrix, viewMatrix)
                      : spotCamera(frustum, light, shadowDistance, inputs.mapSize, projectionMatrix, viewMatrix)) {
        case SpotOutcome::Mapped:
            return true;
        case SpotOutcome::NothingInView:
            return false; // the light lights nothing in view
        case SpotOutcome::LeftToOsg:
            break;
        }
    }
    if (!light.directionalLight) {
        m_ownCamera = false;
        return osgShadow::ViewDependentShadowMap::computeShadowCameraSettings(frustum, light, projectionMatrix,
                                                                              viewMatrix);
    }

    auto camera = [&]() -> core::Result<ShadowCamera> {
        auto frame = inputsFor(frustum.modelViewMatrix, frustum.projectionMatrix, shadowDistance, light.lightDir,
                               sceneBounds(), inputs);
        if (!frame || !m_chooser) return frame ? shadowCameraOf(*frame) : frame.errorInfo();
        // auto: the chooser's technique and parameters for the receivers last handed over.
        auto choice =
            m_chooser->choose(*frame, std::max(m_receiverWidth, 1), std::max(m_receiverHeight, 1), m_receivers);
        if (!choice) return choice.errorInfo();
        m_lastChoice = *choice;
        core::ShadowSetupInputs chosen = choice->inputs;
        chosen.depthLayout = core::DepthLayout::Hyperbolic;
        return shadowCameraOf(chosen);
    }();
    if (!camera) {
        // Said once per different error, not once a frame; the frame goes without shadows.
        if (camera.error() != m_lastError) OSG_WARN << "shadowkit: " << camera.error() << std::endl;
        m_lastError = camera.error();
        m_lastSetup.reset();
        return false;
    }
    m_lastError.clear();
    viewMatrix = camera->viewMatrix;
    projectionMatrix = camera->projectionMatrix;
    m_lastSetup = std::move(camera->setup);
    return true;
}

bool ShadowMap::adjustPerspectiveShadowMapCameraSettings(osgUtil::RenderStage*, Frustum&, LightData&, ::osg::Camera*) {
    return true;
}

void ShadowMap::cullShadowCastingScene(osgUtil::CullVisitor* cv, ::osg::Camera* camera) const {
    // The cameras are reused from light to light: OSG's own (positional lights) fit theirs.
    camera->setComputeNearFarMode(m_ownCamera ? ::osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR
                                              : ::osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES);
    osgShadow::ViewDependentShadowMap::cullShadowCastingScene(cv, camera);
}

} // namespace shadowkit::osgadapter
