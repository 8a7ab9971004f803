// A camera from an engine's own matrices: viewFromWorld and clipFromView as the engine
// renders with them, whatever its conventions, plus a shadow distance that limits what is
// shadowed independently of the camera's far plane.
//
// The set-ups are computed for a PerspectiveCamera (a symmetric frustum). The projection is
// recognised from the matrix and replaced by the smallest symmetric frustum about the same
// axis that contains it:
//   - perspective, symmetric: the same frustum (set-ups equal eye/direction/fov within
//     rounding);
//   - off-centre or jittered (temporal anti-aliasing): widened to the symmetric frustum
//     that encloses it, so everything the engine's camera sees is still covered (a jitter
//     of a pixel widens it by a pixel);
//   - orthographic: an orthographic view has no perspective aliasing, so the right map is
//     a uniform one; it is represented by a perspective camera moved back along its axis
//     until its far cross-section is at most kOrthographicOverscan wider than its near one,
//     enclosing the box: the warped techniques then see a huge z_n and fall back to their
//     uniform limit by their own rules;
//   - reversed-Z (near -> 1) and an infinite far plane are recognised from the depth row;
//     an infinite far plane needs a finite shadowDistance.
// Depth must not depend on x or y: oblique near planes (mirror and water reflections)
// are refused with an error, since their frustum is not one this API can enclose simply.
#pragma once

#include "shadowkit/core/camera.h"

#include <limits>

namespace shadowkit::core {

/// Which way the view space looks. A perspective matrix says it itself (clip w = -z or +z);
/// an orthographic one cannot, so it is taken from here: right-handed views look down -Z
/// (glm::lookAt, OpenGL, Vulkan with glm), left-handed down +Z (Direct3D's LookAtLH).
enum class ViewHandedness { RightHanded, LeftHanded };

/// An orthographic camera is enclosed by a far-away perspective one whose far plane is at
/// most this much wider than its near plane (1 %).
inline constexpr double kOrthographicOverscan = 0.01;

/// An engine's camera as the matrices it renders with, in its own conventions.
struct EngineCamera {
    Mat4 viewFromWorld{1.0};                                 ///< rigid: a rotation (or a mirror) and a translation
    Mat4 clipFromView{1.0};                                  ///< perspective or orthographic, any depth convention
    ClipDepthRange clipDepth = ClipDepthRange::ZeroToOne;    ///< the clip depth range clipFromView maps to
    ViewHandedness handedness = ViewHandedness::RightHanded; ///< orthographic projections only
    /// Shadows end at this view depth (metres along the view axis) even when the camera's far
    /// plane lies beyond: engines draw kilometres but shadow hundreds of metres. Required
    /// (finite) with an infinite far plane; +inf: up to the far plane.
    double shadowDistance = std::numeric_limits<double>::infinity();
};

/// What recognising a projection found, in the view's own units (metres).
struct RecognisedProjection {
    bool orthographic = false; ///< else perspective
    bool reversedZ = false;    ///< near maps to clip depth 1
    bool infiniteFar = false;  ///< the depth row never reaches the far value
    bool offCentre = false;    ///< asymmetric about the view axis (off-centre, jittered)
    double zNear = 0.0;        ///< distance of the near plane along the view axis
    double zFar = 0.0;         ///< of the far plane; +inf when infinite
    /// View-space x and y extents of the near plane; for a perspective projection as slopes
    /// (x / depth), for an orthographic one in metres.
    double left = 0.0;      ///< near-plane extent: −x
    double right = 0.0;     ///< +x
    double bottom = 0.0;    ///< −y
    double top = 0.0;       ///< +y
    double forwardZ = -1.0; ///< the view-space z of the view axis: -1 (looks down -Z) or +1
};

/// Error field "camera.clip_from_view": non-finite, not projective in depth, depth that
/// depends on x or y, near/far not in front of the eye, a degenerate x/y mapping.
Result<RecognisedProjection> recogniseProjection(const Mat4& clipFromView, ClipDepthRange clipDepth,
                                                 ViewHandedness handedness = ViewHandedness::RightHanded);

/// The camera the set-ups use for the engine's (see the top of this file). Error fields
/// "camera.view_from_world" (not finite or not rigid), "camera.clip_from_view",
/// "camera.shadow_distance" (not > near, or infinite with an infinite far plane).
Result<PerspectiveCamera> cameraFromMatrices(const EngineCamera& camera);

} // namespace shadowkit::core
