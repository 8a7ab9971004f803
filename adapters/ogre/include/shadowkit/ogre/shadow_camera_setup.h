// shadowkit inside OGRE 1.12: a ShadowCameraSetup whose texture-shadow cameras are shadowkit's
// (TSM, LiSPSM, PSM, focused, standard, cascades one per shadow-texture iteration, or `auto`:
// the core's error-driven choice each frame for the receivers the application hands it), and
// for spot lights the core's spot map, narrowed to what the camera sees of the cone, and for
// point lights one map over what the camera sees within the light's range, or the cube's faces,
// one shadow texture each (setPointLightCubeFaces).
//
// OGRE asks a light's ShadowCameraSetup once per shadow texture and frame (getShadowCamera,
// `iteration` counting the light's textures) to set the texture camera; OGRE then draws the
// casters with it and derives the receivers' texture projection from the same camera. This
// class sets the core's set-up as the camera's custom view and projection, so a user switches
// with one line:
//
//     sceneManager->setShadowCameraSetup(std::make_shared<shadowkit::ogreadapter::ShadowCameraSetup>());
//     // was: std::make_shared<Ogre::LiSPSMShadowCameraSetup>() (or the Focused / PSSM ones)
//
// Conventions, converted once here: OGRE's matrices are row-major for column vectors (M · v),
// its Real is float in Debian's build, and its "standard" projection is OpenGL's (clip depth
// [−1, 1]; each render system converts it): core::OutputConventions::openGL(). The map holds
// what OGRE's rasteriser writes, so the depth layout is always Hyperbolic.
#pragma once

#include "shadowkit/core/auto_chooser.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/shadow_setup.h"

// OgreShadowCameraSetup.h returns a SharedPtr it does not include.
#include <OgreSharedPtr.h>

#include <OgreAxisAlignedBox.h>
#include <OgreMatrix4.h>
#include <OgreShadowCameraSetup.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadowkit::ogreadapter {

/// Every technique but `virtual` (OGRE draws a fixed number of shadow textures per light;
/// `csm` takes one per cascade, as OGRE's PSSM set-up does).
core::Status checkTechnique(core::Technique technique);

/// The core's set-up for an OGRE camera as OGRE holds it (its view and standard projection)
/// and a sun travelling along wsLightDirection, with the options of `options` (technique,
/// map size, the techniques' own; camera, light, bounds and depth layout come from here).
/// shadowDistance: where shadows end along the view (+inf: the far plane). Fails in one line.
core::Result<core::ShadowSetup> setupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                         double shadowDistance, const Ogre::Vector3& wsLightDirection,
                                         const Ogre::AxisAlignedBox& wsSceneBounds, core::ShadowSetupInputs options);

/// The world box of everything under `node` that can cast or receive a shadow: every attached
/// object but cameras, frustums and lights, whose boxes (a camera's reaches its far plane)
/// are not geometry. What the set-ups take by default.
Ogre::AxisAlignedBox sceneBounds(const Ogre::SceneNode& node);

/// setupFor's inputs before the set-up is computed (camera, light, bounds and depth layout
/// converted and checked): what `auto` chooses a technique for. Fails in one line.
core::Result<core::ShadowSetupInputs> inputsFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                                double shadowDistance, const Ogre::Vector3& wsLightDirection,
                                                const Ogre::AxisAlignedBox& wsSceneBounds,
                                                core::ShadowSetupInputs options);

/// The core's spot map (core::computeSpotShadowSetup) for an OGRE camera and a spot light at
/// wsPosition shining along wsDirection: its outer angle the cone (full angle, at most 170°),
/// its attenuation range the range. Its one view, when the cone meets what the camera sees, is
/// a perspective frustum from the light over that part alone; none when it does not (the light
/// then lights nothing in view). Fails in one line, naming the spot's field.
core::Result<core::ShadowSetup> spotSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                             double shadowDistance, const Ogre::Vector3& wsPosition,
                                             const Ogre::Vector3& wsDirection, Ogre::Radian outerAngle, double range,
                                             const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize);

/// The core's one map for a point light at wsPosition with its attenuation range as the range:
/// the narrowest cone from the light over what the camera sees within reach
/// (core::computePointSingleMapSetup), or where that spans more than 170° from the light, a 170°
/// cone aimed at the middle of it (core::computePointAimedMapSetup, its `fallbacks` saying so);
/// no view where the camera sees nothing in reach. Fails in one line for bad input.
core::Result<core::ShadowSetup> pointSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                              double shadowDistance, const Ogre::Vector3& wsPosition, double range,
                                              const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize);

/// The core's cube for a point light at wsPosition reaching `range` (core::computePointShadowSetup):
/// the faces that see something of what the camera sees, each a 90° view with its `face`. Fails
/// in one line for bad input.
core::Result<core::ShadowSetup> cubeSetupFor(const Ogre::Affine3& viewFromWorld, const Ogre::Matrix4& clipFromView,
                                             double shadowDistance, const Ogre::Vector3& wsPosition, double range,
                                             const Ogre::AxisAlignedBox& wsSceneBounds, int mapSize);

/// One view of a set-up as OGRE's texture camera takes it: the light's rigid frame and the
/// rest of the map's OpenGL-convention clip matrix.
struct TextureCamera {
    Ogre::Affine3 viewMatrix;
    Ogre::Matrix4 projectionMatrix;
};
TextureCamera textureCameraOf(const core::ShadowSetup& setup, size_t view);

/// Ogre::ShadowCameraSetup with shadowkit's set-ups for directional, spot and point lights.
/// OGRE 1.12's texture shadows have no cube maps: its default camera gives a point light one
/// 120° map aimed from the light at a point ahead of the camera; here it gets the narrowest
/// cone over what the camera sees within the light's range (pointSetupFor), or where the light
/// stands among what the camera sees, a 170° cone aimed at the middle of it. Give the scene manager as many
/// shadow textures per directional light as the technique has maps (one; four cascades for
/// `csm` by default), and one per spot or point light.
class ShadowCameraSetup : public Ogre::ShadowCameraSetup {
public:
    /// The technique and its options (ShadowSetupInputs' camera, light, bounds and depth
    /// layout are ignored: they come from OGRE). Default: TSM. Fails for `virtual`.
    core::Status setInputs(const core::ShadowSetupInputs& inputs);
    const core::ShadowSetupInputs& inputs() const { return m_inputs; }

    /// The box every caster and receiver lies in. Unset (the default): sceneBounds of the root
    /// scene node, taken once each time OGRE renders the scene, for all the lights that cast.
    void setSceneBounds(std::optional<Ogre::AxisAlignedBox> wsBounds) { m_fixedBounds = wsBounds; }
    /// A point light as the faces of a cube (core::computePointShadowSetup), one shadow texture
    /// each, where OGRE gives point lights several (Ogre::SceneManager::
    /// setShadowTextureCountPerLightType(Ogre::Light::LT_POINT, 6)): texture i is the i-th face
    /// that sees something of the camera's view, the rest drawn by a camera that sees nothing (a
    /// receiver shader multiplies the textures' terms, each lit outside its own frustum). Off (the
    /// default): one map (core::computePointSingleOrAimedMapSetup), which a lamp among what the
    /// camera sees cannot hold whole.
    void setPointLightCubeFaces(bool on) { m_pointCubeFaces = on; }
    bool pointLightCubeFaces() const { return m_pointCubeFaces; }
    /// How many times the scene graph was walked for its box: a count of work, one a render of
    /// the scene however many lights cast.
    long sceneWalks() const { return m_sceneWalks; }

    /// `--technique auto` in OGRE: each frame, the technique and parameters the core's error-driven
    /// chooser (core::AutoChooser, docs/error-driven.md) predicts best for the receivers last
    /// handed to setReceivers, with hysteresis between frames; at most options.cascades maps (0:
    /// up to 4 cascades; give the light as many shadow textures). Until receivers come, the
    /// recommended technique. Fails, keeping the last mode, for invalid options.
    core::Status setAuto(const core::AutoOptions& options);
    /// What the camera sees, as receivers of a width × height frame: the engine's read-back of
    /// view depth and normals through core::receiverSamples (a frame or two late is fine).
    void setReceivers(std::vector<core::ReceiverSample> receivers, int width, int height);
    /// With setAuto: the last frame's choice.
    const std::optional<core::ParameterChoice>& lastChoice() const { return m_lastChoice; }
    /// The set-up of the last frame (for cascades, its views' `split` are the view depths each
    /// texture serves, what a receiver shader selects by), or the error that left the frame
    /// with OGRE's default camera instead.
    const std::optional<core::ShadowSetup>& lastSetup() const { return m_lastSetup; }
    const std::string& lastError() const { return m_lastError; }
    /// The set-up of the last spot light asked for (no view: its cone missed what the camera
    /// sees, and OGRE's default camera drew a map nothing reads), or none after the error
    /// lastSpotError says (that light then had OGRE's default camera).
    const std::optional<core::ShadowSetup>& lastSpotSetup() const { return m_lastSpotSetup; }
    const std::string& lastSpotError() const { return m_lastSpotError; }
    /// The set-up of the last point light asked for (no view: it lights nothing the camera
    /// sees; its `fallbacks` say when its one map holds only part of what the camera sees), or
    /// none after the error lastPointError says (that light then had OGRE's default camera).
    const std::optional<core::ShadowSetup>& lastPointSetup() const { return m_lastPointSetup; }
    const std::string& lastPointError() const { return m_lastPointError; }

    void getShadowCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Viewport* vp,
                         const Ogre::Light* light, Ogre::Camera* texCam, size_t iteration) const override;

private:
    // The scene box of the render that asks for light's texture `iteration`: the fixed one, or
    // the root node's geometry, walked once a render.
    Ogre::AxisAlignedBox boundsOf(const Ogre::SceneManager* sm, const Ogre::Light* light, size_t iteration) const;
    // Sets texCam to the spot light's map; false where OGRE's default camera must do.
    bool spotCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Light* light,
                    Ogre::Camera* texCam) const;
    // The same for a point light's one map, or its texture `iteration` of the cube's faces.
    bool pointCamera(const Ogre::SceneManager* sm, const Ogre::Camera* cam, const Ogre::Light* light,
                     Ogre::Camera* texCam, size_t iteration) const;
    // Keeps a local light's set-up in `last`, or its error in `lastError` (said once); whether
    // there is a set-up.
    static bool keepLocal(core::Result<core::ShadowSetup> setup, std::optional<core::ShadowSetup>& last,
                          std::string& lastError);
    // Sets texCam to a local light's view `view`, its near plane moved towards the light; false
    // where the set-up has no such view.
    static bool localCamera(const core::ShadowSetup& setup, size_t view, const Ogre::Camera* cam,
                            const Ogre::Light* light, Ogre::Camera* texCam);
    // Keeps a frame's error in `last`, said in OGRE's log once per different error (not once
    // a frame); an empty error clears it.
    static void report(const std::string& error, std::string& last);
    // The frame's set-up from its inputs: the fixed technique's, or auto's choice.
    core::Result<core::ShadowSetup> setupOf(const core::ShadowSetupInputs& frame) const;

    core::ShadowSetupInputs m_inputs;
    std::optional<Ogre::AxisAlignedBox> m_fixedBounds;
    mutable std::optional<core::AutoChooser> m_chooser; // with setAuto
    mutable std::optional<core::ParameterChoice> m_lastChoice;
    std::vector<core::ReceiverSample> m_receivers;
    int m_receiverWidth = 0, m_receiverHeight = 0;
    // getShadowCamera is const in OGRE's interface; a frame's set-up is computed at its first
    // texture (iteration 0) and its views handed out for the others.
    mutable std::optional<core::ShadowSetup> m_lastSetup;
    mutable std::optional<core::ShadowSetup> m_lastSpotSetup, m_lastPointSetup;
    mutable std::string m_lastError, m_lastSpotError, m_lastPointError;
    Ogre::DefaultShadowCameraSetup m_fallback; ///< lights and frames whose set-up failed
    // The last box walked, for the scene manager and frame it was walked in, and the lights'
    // textures asked for since (a render asks for each once).
    mutable Ogre::AxisAlignedBox m_walkedBounds;
    mutable std::vector<std::pair<const Ogre::Light*, size_t>> m_askedSinceWalk;
    mutable const Ogre::SceneManager* m_walkedFor = nullptr;
    mutable unsigned long m_walkedFrame = 0;
    mutable long m_sceneWalks = 0;
    bool m_pointCubeFaces = false;
};

} // namespace shadowkit::ogreadapter
