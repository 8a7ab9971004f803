// shadowkit inside OpenSceneGraph 3.6: a ViewDependentShadowMap whose shadow camera is
// shadowkit's (TSM, LiSPSM, PSM, focused or standard, or `auto`: the core's choice of them each
// frame for the receivers the application hands it; for spot lights the core's spot map,
// narrowed to what the camera sees of the cone; for point lights one map over what the camera
// sees within reach), drawn and looked up by OSG as before.
//
// OSG's ViewDependentShadowMap (VDSM) calls computeShadowCameraSettings once a frame per light
// with the view's frustum and the light; what it returns is the shadow camera's view and
// projection, which OSG then draws the casters with (its polygon offset and face culling) and
// turns into the receivers' texgen (bias · projection · view · inverse(camera view)). This
// class answers that call with shadowkit::core's set-up, so a user switches with one line:
//
//     auto shadowMap = new shadowkit::osgadapter::ShadowMap;   // was: new osgShadow::ViewDependentShadowMap
//     shadowedScene->setShadowTechnique(shadowMap);
//
// Conventions, converted once in shadowCameraFor: OSG's matrices are row-vector (v · M) and
// their memory is OpenGL's column-major order, so a glm::dmat4 reads them as they lie; OSG
// rasterises with OpenGL's clip depth [−1, 1] and samples with v = 0 at the bottom row
// (core::OutputConventions::openGL()). The map stores what OSG's rasteriser writes, so the
// set-up's depth layout is always Hyperbolic (TSM's linear depth would need our depth shader).
#pragma once

#include "shadowkit/core/auto_chooser.h"
#include "shadowkit/core/light_reach.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/shadow_setup.h"

#include <osg/BoundingBox>
#include <osg/Light>
#include <osg/Matrixd>
#include <osgShadow/ViewDependentShadowMap>

#include <optional>
#include <string>
#include <vector>

namespace shadowkit::osgadapter {

/// A shadow camera as OSG holds it (row-vector matrices): the map is drawn with
/// viewMatrix · projectionMatrix, whose clip depth is OpenGL's [−1, 1].
struct ShadowCamera {
    ::osg::Matrixd viewMatrix;       ///< world to light space: rigid
    ::osg::Matrixd projectionMatrix; ///< light space to clip (the warp of TSM, LiSPSM, PSM)
    core::ShadowSetup setup;         ///< what the core computed: fallbacks, warp parameters
};

/// Whether the adapter can draw a technique: those of one map (tsm, lispsm, psm, focused,
/// standard); `csm` and `virtual` fail in one line (VDSM draws one map per light here).
core::Status checkTechnique(core::Technique technique);

/// The core's set-up for OSG's camera (its modelview and projection as OSG holds them) and a
/// directional light travelling along wsLightDirection, with the options of `options` (its
/// technique, mapSize and the techniques' own options; camera, light, bounds and depth layout
/// are taken from here). Fails, in one line, for the techniques with more than one map
/// (`csm`, `virtual`: VDSM draws one map per light here), a camera the core cannot read, an
/// empty or non-finite scene box, or a zero light direction.
core::Result<ShadowCamera> shadowCameraFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                           double shadowDistance, const ::osg::Vec3d& wsLightDirection,
                                           const ::osg::BoundingBoxd& wsSceneBounds, core::ShadowSetupInputs options);

/// shadowCameraFor's inputs before the set-up (camera, light, bounds and depth layout converted
/// and checked): what `auto` chooses a technique for. Fails in one line.
core::Result<core::ShadowSetupInputs> inputsFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                                double shadowDistance, const ::osg::Vec3d& wsLightDirection,
                                                const ::osg::BoundingBoxd& wsSceneBounds,
                                                core::ShadowSetupInputs options);
/// The shadow camera of the set-up for `inputs` (from inputsFor): one map, or a one-line error.
core::Result<ShadowCamera> shadowCameraOf(const core::ShadowSetupInputs& inputs);

/// The core's spot map (core::computeSpotShadowSetup) for OSG's camera and a spot light at
/// wsPosition shining along wsDirection with OSG's spot cutoff (half the cone, degrees; the
/// cone at most 170°) reaching `range`: one perspective view from the light over the part of
/// the cone the camera sees, or none where it sees none of it. Fails in one line, naming the
/// spot's field.
core::Result<core::ShadowSetup> spotSetupFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                             double shadowDistance, const ::osg::Vec3d& wsPosition,
                                             const ::osg::Vec3d& wsDirection, double spotCutoffDegrees, double range,
                                             const ::osg::BoundingBoxd& wsSceneBounds, int mapSize);
/// The core's one map for a point light at wsPosition reaching `range`: the narrowest cone from
/// the light over what the camera sees within the range (core::computePointSingleMapSetup), or
/// where that spans more than 170° from the light, a 170° cone aimed at the middle of it
/// (core::computePointAimedMapSetup, its `fallbacks` saying so); no view where the camera sees
/// nothing in reach. Fails in one line for bad input.
core::Result<core::ShadowSetup> pointSetupFor(const ::osg::Matrixd& viewFromWorld, const ::osg::Matrixd& clipFromView,
                                              double shadowDistance, const ::osg::Vec3d& wsPosition, double range,
                                              const ::osg::BoundingBoxd& wsSceneBounds, int mapSize);
/// The shadow camera of a set-up's first view (it must have one).
ShadowCamera shadowCameraOfView(core::ShadowSetup setup);

/// How far an OSG light at wsLight reaches, which its spot or point map spans: OSG's lights have
/// attenuation, not a range, so where it takes the light's brightest channel (diffuse or
/// specular) below `cutoff` of full white (core::attenuationReach), and no farther than the
/// box's farthest corner — all of it for OSG's default, no fall-off. 0 for a light that never
/// shows. Fails in one line for a negative or non-finite attenuation term ("attenuation.linear").
core::Result<double> reachOf(const ::osg::Light& light, const ::osg::Vec3d& wsLight,
                             const ::osg::BoundingBoxd& wsSceneBounds, double cutoff = core::kDefaultReachCutoff);
/// Gives `light` the quadratic attenuation (constant 1, linear 0) that reaches `range` metres at
/// `cutoff` for its present colour: how an application that thinks in ranges gives OSG one, and
/// the adapter a map that ends there. Precondition: range > 0 and finite, a colour brighter than
/// the cutoff.
void setReach(::osg::Light& light, double range, double cutoff = core::kDefaultReachCutoff);

/// osgShadow::ViewDependentShadowMap with shadowkit's shadow camera for directional lights,
/// spot lights and point lights (a spot's and a point light's map spans its reach: where its
/// attenuation fades it out, reachOf, or the farthest corner of the scene box). OSG gives a point light one map along
/// the light's direction, its field of view widened to the view frustum's corners up to 160°; here it gets the
/// narrowest cone over what the camera sees (pointSetupFor), or where the light stands among what the camera sees, a
/// 170° cone aimed at the middle of it. The map size is ShadowSettings' texture size; shadows end at ShadowSettings'
/// maximum shadow map distance, as OSG's own do; use one shadow map per light.
class ShadowMap : public osgShadow::ViewDependentShadowMap {
public:
    ShadowMap();
    ShadowMap(const ShadowMap& other, const ::osg::CopyOp& copyop = ::osg::CopyOp::SHALLOW_COPY);
    META_Object(shadowkit, ShadowMap);

    /// The technique and its options (ShadowSetupInputs' camera, light, bounds, map size and
    /// depth layout are ignored: they come from OSG). Default: TSM, the core's default.
    void setInputs(const core::ShadowSetupInputs& inputs) { m_inputs = inputs; }
    const core::ShadowSetupInputs& inputs() const { return m_inputs; }

    /// The fraction of full white below which a spot or point light is taken not to reach: its
    /// map spans no farther (reachOf). Default 1/256, one step of an 8-bit channel. Fails in one
    /// line ("reach.cutoff"), keeping the last.
    core::Status setReachCutoff(double cutoff);
    double reachCutoff() const { return m_reachCutoff; }

    /// The box every caster and receiver lies in. Unset (the default): the shadowed scene's
    /// own, from a ComputeBoundsVisitor, computed again whenever the scene's bound changes.
    void setSceneBounds(std::optional<::osg::BoundingBoxd> wsBounds) { m_fixedBounds = wsBounds; }

    /// The last frame's set-up (its technique, fallbacks and warp), or the error that left the
    /// frame without a shadow camera.
    const std::optional<core::ShadowSetup>& lastSetup() const { return m_lastSetup; }
    /// `auto`: each frame, the single map and parameters the core's error-driven chooser
    /// (core::AutoChooser, docs/error-driven.md) predicts best for the receivers last handed to
    /// setReceivers, with hysteresis between frames; the recommended technique until receivers
    /// come. options.cascades must be 1 (one map per light here). Fails in one line, keeping
    /// the last mode.
    core::Status setAuto(const core::AutoOptions& options);
    /// What the camera sees, as receivers of a width × height frame: the application's read-back
    /// of view depth and normals through core::receiverSamples (a frame or two late is fine).
    void setReceivers(std::vector<core::ReceiverSample> receivers, int width, int height);
    /// With setAuto: the last frame's choice.
    const std::optional<core::ParameterChoice>& lastChoice() const { return m_lastChoice; }
    const std::string& lastError() const { return m_lastError; }
    /// The set-up of the last spot light (no view: its cone missed what the camera sees within
    /// its reach, or its attenuation dims it out at the light, as its `fallbacks` then say, and
    /// the light went without a map), or none after the error lastSpotError says (that light then
    /// had OSG's own shadow camera).
    const std::optional<core::ShadowSetup>& lastSpotSetup() const { return m_lastSpotSetup; }
    const std::string& lastSpotError() const { return m_lastSpotError; }
    /// The set-up of the last point light (no view: it lights nothing the camera sees; its
    /// `fallbacks` say when its one map holds only part of what the camera sees), or none after
    /// the error lastPointError says (that light then had OSG's own shadow camera).
    const std::optional<core::ShadowSetup>& lastPointSetup() const { return m_lastPointSetup; }
    const std::string& lastPointError() const { return m_lastPointError; }

    void init() override;

    /// The call VDSM makes once a frame: public so an application (and the tests) can ask it
    /// for a frustum and light of its own.
    bool computeShadowCameraSettings(Frustum& frustum, LightData& light, ::osg::Matrixd& projectionMatrix,
                                     ::osg::Matrixd& viewMatrix) override;

protected:
    ~ShadowMap() override = default;
    /// OSG's perspective hint would warp the map a second time: ours is warped already.
    bool adjustPerspectiveShadowMapCameraSettings(osgUtil::RenderStage* renderStage, Frustum& frustum, LightData& light,
                                                  ::osg::Camera* camera) override;
    /// OSG narrows a shadow camera's depth range to the casters by taking its projection apart
    /// as a frustum or a box, which a trapezoid or a post-perspective map is not: ours already
    /// spans the casters, so the shadow cameras keep it.
    void cullShadowCastingScene(osgUtil::CullVisitor* cv, ::osg::Camera* camera) const override;

private:
    ::osg::BoundingBoxd sceneBounds();
    // A spot light's camera: set (Mapped), not needed (NothingInView: the cone misses the view),
    // or left to OSG's own after an error, said once (LeftToOsg).
    enum class SpotOutcome { Mapped, NothingInView, LeftToOsg };
    SpotOutcome spotCamera(const Frustum& frustum, const LightData& light, double shadowDistance, int mapSize,
                           ::osg::Matrixd& projectionMatrix, ::osg::Matrixd& viewMatrix);
    // The same for a point light's one map.
    SpotOutcome pointCamera(const Frustum& frustum, const LightData& light, double shadowDistance, int mapSize,
                            ::osg::Matrixd& projectionMatrix, ::osg::Matrixd& viewMatrix);
    // A local light's outcome: `setup` kept in `last` (or its error in `lastError`, said once),
    // and the camera set from it (Mapped), NothingInView, or LeftToOsg.
    static SpotOutcome localOutcome(const core::Result<core::ShadowSetup>& setup,
                                    std::optional<core::ShadowSetup>& last, std::string& lastError,
                                    ::osg::Matrixd& projectionMatrix, ::osg::Matrixd& viewMatrix);

    core::ShadowSetupInputs m_inputs;
    std::optional<::osg::BoundingBoxd> m_fixedBounds;
    std::optional<core::AutoChooser> m_chooser; // with setAuto
    std::optional<core::ParameterChoice> m_lastChoice;
    std::vector<core::ReceiverSample> m_receivers;
    int m_receiverWidth = 0, m_receiverHeight = 0;
    ::osg::BoundingBoxd m_cachedBounds;
    ::osg::BoundingSphere m_cachedFor; ///< the scene's bound when m_cachedBounds was computed
    std::optional<core::ShadowSetup> m_lastSetup;
    std::optional<core::ShadowSetup> m_lastSpotSetup, m_lastPointSetup;
    std::string m_lastError, m_lastSpotError, m_lastPointError;
    double m_reachCutoff = core::kDefaultReachCutoff;
    bool m_ownCamera =
        false; ///< this light's shadow camera is ours (directional, spot, point), for the cull that follows
};

} // namespace shadowkit::osgadapter
