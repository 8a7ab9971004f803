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
#include <limits>

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
    if (!wsSceneBounds.valid() || !isFinite(wsSceneBounds))
        return core::Error{"scene bounds: empty or not finite (nothing under the ShadowedScene?)", "scene_bounds"};

    // OSG's main camera: OpenGL's clip depth, a right-handed view looking down −Z.
    core::EngineCamera engine{toCore(viewFromWorld), toCore(clipFromView), core::ClipDepthRange::MinusOneToOne};
    engine.shadowDistance = shadowDistance;
    auto camera = core::cameraFromMatrices(engine);
    if (!camera) return camera.errorInfo();
    auto light = core::DirectionalLight::fromDirection(
        core::Vec3(wsLightDirection.x(), wsLightDirection.y(), wsLightDirection.z()));
    if (!light) return light.errorInfo();

    options.camera = *camera;
    options.light = *light;
    options.wsSceneBounds =
        core::Aabb::fromMinMax(core::Vec3(wsSceneBounds.xMin(), wsSceneBounds.yMin(), wsSceneBounds.zMin()),
                               core::Vec3(wsSceneBounds.xMax(), wsSceneBounds.yMax(), wsSceneBounds.zMax()));
    // OSG's caster pass writes the rasteriser's depth; it cannot write TSM's linear depth.
    options.depthLayout = core::DepthLayout::Hyperbolic;
    return options;
}

core::Result<ShadowCamera> shadowCameraOf(const core::ShadowSetupInputs& inputs) {
    if (auto usable = checkTechnique(inputs.technique); !usable) return usable.errorInfo();
    auto setup = core::computeShadowSetup(inputs);
    if (!setup) return setup.errorInfo();
    if (setup->views.empty()) return core::Error{"the set-up has no shadow map for this view", "technique"};

    // The light's rigid frame is OSG's view matrix, the rest of the map's clip matrix (in
    // OpenGL's depth range) its projection, so OSG's caster culling sees a light-space frustum.
    const core::ShadowView& view = setup->views[0];
    const core::EngineShadowView gl = core::toEngineView(view, *setup, core::OutputConventions::openGL());
    const core::Mat4 clipFromLight = gl.clipFromWorld * glm::inverse(view.lightFromWorld);
    return ShadowCamera{toOsg(view.lightFromWorld), toOsg(clipFromLight), std::move(*setup)};
}

core::Result<ShadowCamera> shadowCameraFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                           double shadowDistance, const ::osg::Vec3d& wsLightDirection,
                                           const ::osg::BoundingBoxd& wsSceneBounds, core::ShadowSetupInputs options) {
    if (auto usable = checkTechnique(options.technique); !usable) return usable.errorInfo();
    auto inputs = inputsFor(viewFromWorld, clipFromView, shadowDistance, wsLightDirection, wsSceneBounds, options);
    if (!inputs) return inputs.errorInfo();
    return shadowCameraOf(*inputs);
}

ShadowMap::ShadowMap() = default;

ShadowMap::ShadowMap(const ShadowMap& other, const ::osg::CopyOp& copyop)
    : osgShadow::ViewDependentShadowMap(other, copyop), m_inputs(other.m_inputs), m_fixedBounds(other.m_fixedBounds),
      m_chooser(other.m_chooser), m_receivers(other.m_receivers), m_receiverWidth(other.m_receiverWidth),
      m_receiverHeight(other.m_receiverHeight) {}

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

bool ShadowMap::computeShadowCameraSettings(Frustum& frustum, LightData& light, ::osg::Matrixd& projectionMatrix,
                                            ::osg::Matrixd& viewMatrix) {
    m_ownCamera = light.directionalLight;
    if (!light.directionalLight)
        return osgShadow::ViewDependentShadowMap::computeShadowCameraSettings(frustum, light, projectionMatrix,
                                                                              viewMatrix);
    core::ShadowSetupInputs inputs = m_inputs;
    const osgShadow::ShadowSettings* settings = getShadowedScene() ? getShadowedScene()->getShadowSettings() : nullptr;
    if (settings) inputs.mapSize = static_cast<int>(settings->getTextureSize().x());
    const double maxDistance = settings ? settings->getMaximumShadowMapDistance() : std::numeric_limits<double>::max();
    const double shadowDistance =
        maxDistance >= std::numeric_limits<double>::max() ? std::numeric_limits<double>::infinity() : maxDistance;

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
