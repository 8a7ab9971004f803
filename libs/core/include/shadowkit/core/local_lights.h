// Local lights — spot and point — and their shadow set-ups.
//
// A local light sees the scene in perspective from its position, so its maps are
// perspective views from there: one for a spot light, six 90° faces of a cube for a point
// light (seed 003). Their stored depth is the distance to the light, mapped from each view's
// [near, far] to [0, 1] (DepthLayout::LightDistance), which is what the seed recommends for
// cube maps and what makes a bias in metres mean the same everywhere in the map.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <array>
#include <span>
#include <vector>

namespace shadowkit::core {

/// A spot light: one perspective map over its cone, focused on what the camera sees of it.
struct SpotLight {
    Vec3 wsPosition{0.0, 3.0, 0.0};   ///< apex of the cone, world space
    Vec3 wsDirection{0.0, -1.0, 0.0}; ///< axis of the cone, any length > 0
    double coneDegrees = 40.0;        ///< full opening angle of the cone, (0, 170]
    double range = 30.0;              ///< metres: nothing farther is lit, > 0
    double radius = 0.0;              ///< metres: a sphere of light (penumbrae), [0, range); 0 a point

    /// Fields "spot.position", "spot.direction", "spot.cone", "spot.range", "spot.radius".
    Status validate() const;
};

/// A point light: six 90° cube faces, each focused on what the camera sees of the light.
struct PointLight {
    Vec3 wsPosition{0.0, 3.0, 0.0}; ///< world space
    double range = 30.0;            ///< metres, > 0
    double radius = 0.0;            ///< metres: a sphere of light (penumbrae), [0, range); 0 a point

    /// Fields "point.position", "point.range", "point.radius".
    Status validate() const;
};

/// The cube faces in OpenGL's order (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face): +X, −X, +Y, −Y,
/// +Z, −Z, each a look-at along its axis with the up vector the cube map's (s, t) axes need,
/// so a face's NDC (x, y) is the cube texture's (s, t) for that face (OpenGL 4.5 §8.13).
struct CubeFace {
    Vec3 wsAxis; ///< the face looks along this axis
    Vec3 wsUp;   ///< and has this up vector
};
const std::array<CubeFace, 6>& cubeFaces();
/// The face a direction from the light selects: the axis of largest magnitude (ties to the
/// lower index), as the cube sampler does.
int cubeFaceOf(const Vec3& wsDirection);

/// What the local lights' set-ups need: the camera, the scene box and the map size.
struct LocalShadowInputs {
    PerspectiveCamera camera; ///< whose view the maps are focused on
    Aabb wsSceneBounds;       ///< every caster and receiver lies inside
    int mapSize = 1024;       ///< texels per side of the spot map or of each cube face
};

/// The spot light's map: a perspective view from the light, fitted to its receivers R =
/// cone ∩ range ∩ view frustum ∩ scene box: the field of view narrowed to R's angular
/// extent (an off-centre frustum inside the cone), the distance range to R's. Every caster
/// that can shadow a point of R lies on the segment from it to the light, so inside the
/// same angular extent, and nearer: at worst clamped to depth 0, still in front of its
/// receiver (the depth pass clamps rather than clips: setup.depthClamp). No view when R is
/// empty (the light cannot light anything the camera sees).
Result<ShadowSetup> computeSpotShadowSetup(const LocalShadowInputs& inputs, const SpotLight& light);

/// The point light's cube: one view per face whose pyramid meets R = range ∩ view frustum ∩
/// scene box, each a full 90° face (the cube sampler needs whole faces) with its own distance
/// range and `face` index; faces that see nothing of R are left out (setup.skippedFaces).
Result<ShadowSetup> computePointShadowSetup(const LocalShadowInputs& inputs, const PointLight& light);

/// A point light in one perspective map, for engines whose shadow pipelines draw no cube maps
/// (OpenSceneGraph's ViewDependentShadowMap and OGRE 1.12 give a point light one map, aimed by a
/// fixed rule that need not hold what the camera sees): the set-up of the spot light at the
/// point light's position whose cone is the narrowest that holds R = range ∩ view frustum ∩
/// scene box, narrowed to R as computeSpotShadowSetup narrows a spot's and turned about its axis
/// to the least area over R (lightType Spot, one view, no face), so every receiver the camera
/// sees lit lands in the map, and with it its casters. No view when R is empty. Fails,
/// naming "point.position", when R spans more than a 170° cone seen from the light (the light
/// stands among what the camera sees, or beside it): only a cube holds that.
Result<ShadowSetup> computePointSingleMapSetup(const LocalShadowInputs& inputs, const PointLight& light);
/// Where that is refused, the best one map here: a cone of coneDegrees aimed from the light at
/// the mean of R's corners, narrowed to R as a spot map is, with holdsPartOfView set and
/// `fallbacks` saying receivers outside the cone get no shadow from this light. Fails only for
/// bad input (a cone outside (0, 170] names "point.cone").
Result<ShadowSetup> computePointAimedMapSetup(const LocalShadowInputs& inputs, const PointLight& light,
                                              double coneDegrees = 170.0);
/// A point light in one map wherever it stands: computePointSingleMapSetup, or where that spans
/// more than 170° from the light, computePointAimedMapSetup's 170° cone (holdsPartOfView). What
/// an engine without cube maps draws (the OSG and OGRE adapters, the C API's
/// SHADOWKIT_LIGHT_POINT_AIMED_MAP). Fails only for bad input.
Result<ShadowSetup> computePointSingleOrAimedMapSetup(const LocalShadowInputs& inputs, const PointLight& light);

/// A frame's local lights with their set-ups, in the order given: what a renderer draws.
struct LocalLighting {
    std::vector<PointLight> points;                              ///< the point lights
    std::vector<ShadowSetup> pointSetups;                        ///< one per point light
    std::vector<SpotLight> spots;                                ///< the spot lights
    std::vector<ShadowSetup> spotSetups;                         ///< one per spot light
    int mapSize = 1024;                                          ///< of every spot map and cube face
    size_t size() const { return points.size() + spots.size(); } ///< lights of both kinds
    bool empty() const { return size() == 0; }                   ///< no local light
};
/// The same lights and set-ups for coordinates measured from `wsOrigin` (core::rebased).
LocalLighting rebased(const LocalLighting& lighting, const Vec3& wsOrigin);
/// Every light's set-up for this camera (errors name the light: "point[2]: ...").
Result<LocalLighting> computeLocalLighting(const LocalShadowInputs& inputs, std::span<const PointLight> points,
                                           std::span<const SpotLight> spots);

/// World size of one texel of a local light's view per metre of distance from the light:
/// a texel at distance d covers about d × this (the view's widest tangent span over the map's
/// texels; 2 / mapSize for a 90° cube face). Biases in texels become metres with it.
double texelSizePerMetre(const ShadowView& view, int mapSize);

/// The local lights' lookup biases (glsl/shadowkit_local_shadows.glsl's SkLocalShadowOptions), in
/// distance units, since their maps store the distance to the light: sizes in texels become metres
/// through the texel's world size at the receiver's distance (texelSizePerMetre), so one setting
/// holds near and far from the light. The defaults are the renderer's (docs/local-lights.md:
/// the `lamp` view 25.0 % wrong without them, 0.08 % with).
struct LocalBias {
    /// Distance reduced by this × texel size × tan(angle to the light), the tangent at most 3.2; [0, 16].
    double slopeTexels = 1.5;
    /// Receiver moved along its normal by this × texel size where the light grazes it (the angle's
    /// cosine below 0.3, in full below 0.15), where the slope term stops growing; [0, 16].
    double normalOffsetTexels = 0.5;
    /// And its distance reduced by this; [0, 1].
    double constantMetres = 0.005;
};
/// Fields "local_bias.slope", "local_bias.normal_offset", "local_bias.constant".
Status validate(const LocalBias& bias);

/// What a local light's depth pass writes per fragment and its lookup expects, stored =
/// distance · x + y over the light's whole range, one mapping for every face of a cube (the
/// lookup's filters cross faces): (1 / range, 0), or (−1 / range, 1) for a reversed-Z engine,
/// whose comparison is then GL_GEQUAL. Unlike a view's lightDistance, which spans only that
/// view's receivers.
Vec2 storedFromDistance(double range, bool reversedZ);

/// The depth a local light's view stores for a world point (LightDistance layout), before
/// clamping to [0, 1].
double lightDistanceDepth(const ShadowSetup& setup, const ShadowView& view, const Vec3& wsPoint);

} // namespace shadowkit::core
