// Shadow set-ups for spot and point lights.
//
// Based on: seed 003 (the point light's map as a cube of six 90° views around the light,
// depth stored as the distance to the light; near and far chosen so that no occluder is
// clipped) and the focusing idea of the directional techniques (Wimmer et al. 2004 §3.3:
// spend the map only on what can matter to the viewer), applied to a light at a point.
//
// What can matter: the receivers R = light volume ∩ view frustum ∩ scene box. A caster that
// shadows a point p of R lies on the segment from p to the light, so
//   - it is seen from the light in the same direction as p: any view from the light whose
//     angular extent holds R's holds its casters too (that is why no sweep is needed, unlike
//     the directional focus body, whose light is at infinity);
//   - it is nearer the light than p: its stored distance is below p's, or clamped to 0 when
//     it is nearer than the view's near distance, and still in front. So near and far come
//     from R alone, and the depth pass clamps instead of clipping (depthClamp).
// Distances: R is a convex polytope. The largest distance to the light is at a vertex; the
// smallest may lie inside a face, so the near distance is the smallest *axial* depth over
// the vertices, a lower bound of every distance in the view (depth along the axis <= distance).
// A point light in one map, for engines without cube maps: by the first point, any cone from
// the light that holds R holds its casters, so the narrowest one over R's corners (while it is
// under 180°, it is convex and holds their hull) is a spot light's map with nothing missing.
#include "shadowkit/core/local_lights.h"

#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/light_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace shadowkit::core {
namespace {

Status checkInputs(const LocalShadowInputs& in) {
    if (Status s = in.camera.validate(); !s) return s;
    if (Status s = validateSceneBounds(in.wsSceneBounds); !s) return s;
    return validateMapSize(in.mapSize);
}

// The part of the scene within the light's range that the camera sees: the scene box and the
// range's bounding cube, clipped by the view frustum. (The range ball itself is not convex-
// polyhedral; its cube is the tightest axis-aligned stand-in, and the light volumes below
// cut it further.)
ConvexBody visibleInRange(const LocalShadowInputs& in, const Vec3& wsLight, double range) {
    Aabb box = sceneBoxForFocus(in.wsSceneBounds);
    box.min = glm::max(box.min, wsLight - Vec3(range));
    box.max = glm::min(box.max, wsLight + Vec3(range));
    if (box.isEmpty()) return {};
    ConvexBody body = ConvexBody::fromAabb(box);
    const auto frustum = in.camera.wsFrustumPlanes();
    body.clip(frustum);
    return body;
}

// The four side planes of a pyramid with its apex at the light, looking along the frame's −z,
// with half-extents tan(x) = tanX and tan(y) = tanY; outward normals in world space.
std::array<Plane, 4> pyramidPlanes(const Mat4& lightFromWorld, const Vec3& wsApex, double tanX, double tanY) {
    const Mat4 worldFromLight = glm::inverse(lightFromWorld);
    auto toWorld = [&](const Vec3& lsNormal) { return glm::normalize(Vec3(worldFromLight * Vec4(lsNormal, 0.0))); };
    // In light space a point is inside when |x| <= tanX·(−z) and |y| <= tanY·(−z).
    return {Plane::fromPointNormal(wsApex, toWorld(Vec3(1.0, 0.0, tanX))),
            Plane::fromPointNormal(wsApex, toWorld(Vec3(-1.0, 0.0, tanX))),
            Plane::fromPointNormal(wsApex, toWorld(Vec3(0.0, 1.0, tanY))),
            Plane::fromPointNormal(wsApex, toWorld(Vec3(0.0, -1.0, tanY)))};
}

// x in [l, r], y in [b, t] at unit distance in front of the light; clip depth [0, 1] over
// [near, far] (what GL clips is irrelevant with depth clamping: the stored depth is the
// distance, written per fragment). Frustum with clip w = −z.
Mat4 frustumZeroToOne(double l, double r, double b, double t, double zNear, double zFar) {
    Mat4 m(0.0);
    m[0][0] = 2.0 / (r - l);
    m[2][0] = (r + l) / (r - l);
    m[1][1] = 2.0 / (t - b);
    m[2][1] = (t + b) / (t - b);
    m[2][2] = zFar / (zNear - zFar);
    m[3][2] = zNear * zFar / (zNear - zFar);
    m[2][3] = -1.0;
    return m;
}

struct Extent {
    double l = INFINITY, r = -INFINITY, b = INFINITY, t = -INFINITY; // tangents at unit depth
    double axialNear = INFINITY, axialFar = 0.0, farthest = 0.0;     // metres
    bool apexInside = false; // a vertex at the light: every direction of the volume is present
};

Extent extentOf(const ConvexBody& body, const Mat4& lightFromWorld, const Vec3& wsLight, double range) {
    Extent e;
    for (const Vec3& p : body.vertices()) {
        const Vec3 ls(lightFromWorld * Vec4(p, 1.0));
        const double depth = -ls.z;
        e.axialNear = std::min(e.axialNear, depth > 0.0 ? depth : 0.0);
        e.axialFar = std::max(e.axialFar, depth);
        e.farthest = std::max(e.farthest, glm::distance(p, wsLight));
        if (depth <= 1e-9 * range) {
            e.apexInside = true;
            continue;
        }
        e.l = std::min(e.l, ls.x / depth), e.r = std::max(e.r, ls.x / depth);
        e.b = std::min(e.b, ls.y / depth), e.t = std::max(e.t, ls.y / depth);
    }
    return e;
}

// A perspective view from the light over tangents [l, r] × [b, t], distances fitted to R.
ShadowView localView(const Mat4& lightFromWorld, const Extent& e, double range, double l, double r, double b,
                     double t) {
    ShadowView view;
    view.lightFromWorld = lightFromWorld;
    // Clip planes for GL's sake only (the depth pass clamps): near a little in front of R,
    // never at the apex, far beyond R's farthest axial depth.
    const double clipNear = std::max(std::min(e.axialNear, range) * 0.5, 1e-4 * range);
    const double clipFar = std::max(e.axialFar, 2.0 * clipNear) * 1.01;
    view.clipFromLight = frustumZeroToOne(l, r, b, t, clipNear, clipFar);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    const double farDistance = std::min(e.farthest, range);
    view.lightDistance = Vec2(std::min(e.axialNear, farDistance), farDistance);
    if (!(view.lightDistance.y > view.lightDistance.x)) view.lightDistance.y = view.lightDistance.x + 1e-6 * range;
    return view;
}

ShadowSetup localSetup(LightType type, const Vec3& wsLight, int mapSize) {
    ShadowSetup setup;
    setup.technique = Technique::Focused;
    setup.lightType = type;
    setup.wsLightPosition = wsLight;
    setup.mapSize = mapSize;
    setup.depthLayout = DepthLayout::LightDistance;
    setup.depthClamp = true;
    return setup;
}

// The narrowest cone from `apex` that holds every point of `vertices` (R's corners; R is their
// convex hull and a cone under 180° is convex, so it holds R): its unit axis and half-angle.
// The axis is the direction of the smallest ball holding the corners' unit directions, found by
// Bădoiu and Clarkson's iteration (a step towards the farthest direction by 1 / (k + 1): within a
// factor 1 + 1/√k of the smallest radius); the half-angle is then measured, not estimated, so
// the cone holds every corner whatever the iteration's error. No cone when a corner lies at the
// apex or the directions surround it (the ball's centre at the origin).
struct Cone {
    Vec3 axis{0.0};
    double halfAngle = 0.0; // radians
};
std::optional<Cone> narrowestConeHolding(const ConvexBody::Points& vertices, const Vec3& apex, double scale) {
    std::vector<Vec3> directions;
    directions.reserve(vertices.size());
    for (const Vec3& p : vertices) {
        const double distance = glm::distance(p, apex);
        if (distance <= 1e-9 * scale) return std::nullopt;
        directions.push_back((p - apex) / distance);
    }
    if (directions.empty()) return std::nullopt;
    Vec3 centre = directions.front();
    for (int k = 1; k <= 400; ++k) {
        const Vec3* farthest = &directions.front();
        for (const Vec3& d : directions)
            if (glm::distance(d, centre) > glm::distance(*farthest, centre)) farthest = &d;
        centre += (*farthest - centre) / double(k + 1);
    }
    if (!(glm::length(centre) > 1e-9)) return std::nullopt;
    Cone cone{glm::normalize(centre), 0.0};
    for (const Vec3& d : directions)
        cone.halfAngle = std::max(cone.halfAngle, std::acos(std::clamp(glm::dot(d, cone.axis), -1.0, 1.0)));
    return cone;
}

// The spot light's frame: looking along its axis, rolled by the world's up hints.
Mat4 spotFrame(const Vec3& wsPosition, const Vec3& wsDirection) {
    return makeLightFrame(glm::normalize(wsDirection), wsPosition, {Vec3(0, 1, 0), Vec3(0, 0, -1)}).lightFromWorld;
}

// The spot's map in a given frame (its −z the cone's axis; the roll free): inputs checked.
Result<ShadowSetup> spotSetupInFrame(const LocalShadowInputs& in, const SpotLight& light, const Mat4& lightFromWorld) {
    ShadowSetup setup = localSetup(LightType::Spot, light.wsPosition, in.mapSize);
    // The cone inside its square pyramid (half-angle θ on both axes), cut at the range.
    const double tanHalf = std::tan(0.5 * glm::radians(light.coneDegrees));
    ConvexBody receivers = visibleInRange(in, light.wsPosition, light.range);
    const auto sides = pyramidPlanes(lightFromWorld, light.wsPosition, tanHalf, tanHalf);
    receivers.clip(sides);
    const Vec3 axis = glm::normalize(light.wsDirection);
    receivers.clip(Plane::fromPointNormal(light.wsPosition + light.range * axis, axis));
    if (receivers.isEmpty()) {
        setup.fallbacks.emplace_back("spot: its cone misses what the camera sees of the scene: no map");
        setEyeRelativeFromWorld(setup, light.wsPosition);
        return setup;
    }
    const Extent e = extentOf(receivers, lightFromWorld, light.wsPosition, light.range);
    // The field of view narrowed to R's angular extent; the whole cone when R reaches the light.
    auto clampTan = [&](double v) { return std::clamp(v, -tanHalf, tanHalf); };
    double l = -tanHalf, r = tanHalf, b = -tanHalf, t = tanHalf;
    if (!e.apexInside) l = clampTan(e.l), r = clampTan(e.r), b = clampTan(e.b), t = clampTan(e.t);
    // A sliver (R seen edge-on) still needs a finite, invertible frustum.
    const double minWidth = 1e-6 * tanHalf;
    if (r - l < minWidth) l -= 0.5 * minWidth, r += 0.5 * minWidth;
    if (t - b < minWidth) b -= 0.5 * minWidth, t += 0.5 * minWidth;
    setup.views.push_back(localView(lightFromWorld, e, light.range, l, r, b, t));
    // Relative to the light: a local light's map is of the size of its range around it.
    setEyeRelativeFromWorld(setup, light.wsPosition);
    return setup;
}

// The frame about the cone's axis whose map spans `vertices` over the least area of tangents
// (the most texels on them), ties to the least span on the wider side: the receivers' footprint
// need not lie square to the world's up. Not the least wider side first: a sliver turned 45°
// gains a little on its length and loses its width many times over. Searched by whole degrees
// over a quarter turn (a map's extent repeats every 90°).
Mat4 rolledToFit(const Mat4& lightFromWorld, const ConvexBody::Points& vertices) {
    double bestSide = INFINITY, bestArea = INFINITY, bestRoll = 0.0;
    for (int degrees = 0; degrees < 90; ++degrees) {
        const double roll = glm::radians(double(degrees)), c = std::cos(roll), s = std::sin(roll);
        double uMin = INFINITY, uMax = -INFINITY, vMin = INFINITY, vMax = -INFINITY;
        for (const Vec3& p : vertices) {
            const Vec3 ls(lightFromWorld * Vec4(p, 1.0));
            const double x = ls.x / -ls.z, y = ls.y / -ls.z; // every corner lies in front (cone < 180°)
            const double u = c * x + s * y, v = -s * x + c * y;
            uMin = std::min(uMin, u), uMax = std::max(uMax, u), vMin = std::min(vMin, v), vMax = std::max(vMax, v);
        }
        const double side = std::max(uMax - uMin, vMax - vMin), area = (uMax - uMin) * (vMax - vMin);
        if (area < bestArea * (1.0 - 1e-9) || (area <= bestArea * (1.0 + 1e-9) && side < bestSide))
            bestSide = side, bestArea = area, bestRoll = roll;
    }
    // (u, v) = R(roll) (x, y): a rotation of the light's frame by −roll about its z.
    return glm::rotate(Mat4(1.0), -bestRoll, Vec3(0.0, 0.0, 1.0)) * lightFromWorld;
}

} // namespace

Status SpotLight::validate() const {
    if (!isFinite(wsPosition)) return fieldError("spot.position", "must be finite");
    if (glm::length(wsPosition) > kMaxWorldMetres) return fieldError("spot.position", "at most 1e13 m from the origin");
    if (!isFinite(wsDirection) || !(glm::length(wsDirection) > 0.0))
        return fieldError("spot.direction", "must be a finite, non-zero vector");
    if (!(coneDegrees > 0.0 && coneDegrees <= 170.0)) return fieldError("spot.cone", "must be in (0, 170] degrees");
    if (!(range > 0.0 && std::isfinite(range)))
        return fieldError("spot.range", "must be a finite number of metres > 0");
    if (!(radius >= 0.0 && radius < range)) return fieldError("spot.radius", "must be in [0, range) metres");
    return Ok{};
}

Status PointLight::validate() const {
    if (!isFinite(wsPosition)) return fieldError("point.position", "must be finite");
    if (glm::length(wsPosition) > kMaxWorldMetres)
        return fieldError("point.position", "at most 1e13 m from the origin");
    if (!(range > 0.0 && std::isfinite(range)))
        return fieldError("point.range", "must be a finite number of metres > 0");
    if (!(radius >= 0.0 && radius < range)) return fieldError("point.radius", "must be in [0, range) metres");
    return Ok{};
}

const std::array<CubeFace, 6>& cubeFaces() {
    static const std::array<CubeFace, 6> faces = {{{{1, 0, 0}, {0, -1, 0}},
                                                   {{-1, 0, 0}, {0, -1, 0}},
                                                   {{0, 1, 0}, {0, 0, 1}},
                                                   {{0, -1, 0}, {0, 0, -1}},
                                                   {{0, 0, 1}, {0, -1, 0}},
                                                   {{0, 0, -1}, {0, -1, 0}}}};
    return faces;
}

int cubeFaceOf(const Vec3& d) {
    const Vec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

double texelSizePerMetre(const ShadowView& view, int mapSize) {
    // clipFromLight is frustumZeroToOne: m[0][0] = 2 / (r − l), m[1][1] = 2 / (t − b).
    const double span = std::max(2.0 / view.clipFromLight[0][0], 2.0 / view.clipFromLight[1][1]);
    return span / static_cast<double>(std::max(mapSize, 1));
}

Result<LocalLighting> computeLocalLighting(const LocalShadowInputs& inputs, std::span<const PointLight> points,
                                           std::span<const SpotLight> spots) {
    LocalLighting out;
    out.mapSize = inputs.mapSize;
    auto named = [](const char* kind, size_t i, const Error& e) {
        return Error{std::string(kind) + "[" + std::to_string(i) + "]: " + e.message, e.field, e.kind};
    };
    for (size_t i = 0; i < points.size(); ++i) {
        auto setup = computePointShadowSetup(inputs, points[i]);
        if (!setup) return named("point", i, setup.errorInfo());
        out.points.push_back(points[i]);
        out.pointSetups.push_back(std::move(setup).value());
    }
    for (size_t i = 0; i < spots.size(); ++i) {
        auto setup = computeSpotShadowSetup(inputs, spots[i]);
        if (!setup) return named("spot", i, setup.errorInfo());
        out.spots.push_back(spots[i]);
        out.spotSetups.push_back(std::move(setup).value());
    }
    return out;
}

LocalLighting rebased(const LocalLighting& lighting, const Vec3& wsOrigin) {
    LocalLighting out = lighting;
    for (PointLight& p : out.points) p.wsPosition -= wsOrigin;
    for (SpotLight& s : out.spots) s.wsPosition -= wsOrigin;
    for (ShadowSetup& s : out.pointSetups) s = rebased(s, wsOrigin);
    for (ShadowSetup& s : out.spotSetups) s = rebased(s, wsOrigin);
    return out;
}

double lightDistanceDepth(const ShadowSetup& setup, const ShadowView& view, const Vec3& wsPoint) {
    return (glm::distance(wsPoint, setup.wsLightPosition) - view.lightDistance.x) /
           (view.lightDistance.y - view.lightDistance.x);
}

Result<ShadowSetup> computeSpotShadowSetup(const LocalShadowInputs& in, const SpotLight& light) {
    if (Status s = checkInputs(in); !s) return s.errorInfo();
    if (Status s = light.validate(); !s) return s.errorInfo();
    return spotSetupInFrame(in, light, spotFrame(light.wsPosition, light.wsDirection));
}

Result<ShadowSetup> computePointShadowSetup(const LocalShadowInputs& in, const PointLight& light) {
    if (Status s = checkInputs(in); !s) return s.errorInfo();
    if (Status s = light.validate(); !s) return s.errorInfo();
    ShadowSetup setup = localSetup(LightType::Point, light.wsPosition, in.mapSize);
    const ConvexBody visible = visibleInRange(in, light.wsPosition, light.range);
    for (int f = 0; f < 6; ++f) {
        const CubeFace& face = cubeFaces()[static_cast<size_t>(f)];
        const Mat4 lightFromWorld = glm::lookAt(light.wsPosition, light.wsPosition + face.wsAxis, face.wsUp);
        ConvexBody receivers = visible;
        if (!receivers.isEmpty()) receivers.clip(pyramidPlanes(lightFromWorld, light.wsPosition, 1.0, 1.0));
        if (receivers.isEmpty()) {
            ++setup.skippedFaces;
            continue;
        }
        ShadowView view = localView(lightFromWorld, extentOf(receivers, lightFromWorld, light.wsPosition, light.range),
                                    light.range, -1.0, 1.0, -1.0, 1.0);
        view.face = f;
        setup.views.push_back(view);
    }
    if (setup.views.empty())
        setup.fallbacks.emplace_back("point: its range misses what the camera sees of the scene: no map");
    setEyeRelativeFromWorld(setup, light.wsPosition);
    return setup;
}

namespace {

// The full angle, in degrees, of the narrowest cone from the light over R's corners, a hair wider
// so that rounding leaves every corner inside, with its axis; +inf where no cone under 180°
// holds them (the light is among them).
std::pair<double, Vec3> coneOver(const ConvexBody& receivers, const PointLight& light) {
    const auto cone = narrowestConeHolding(receivers.vertices(), light.wsPosition, light.range);
    if (!cone) return {INFINITY, Vec3(0.0)};
    return {2.0 * glm::degrees(cone->halfAngle) * (1.0 + 1e-9) + 1e-6, cone->axis};
}

// The spot map of that cone, turned to the least area over R (what `in` sees of the light).
Result<ShadowSetup> oneMapOver(const LocalShadowInputs& in, const PointLight& light, const ConvexBody& receivers,
                               const std::pair<double, Vec3>& cone) {
    const SpotLight spot{.wsPosition = light.wsPosition,
                         .wsDirection = cone.second,
                         .coneDegrees = cone.first,
                         .range = light.range,
                         .radius = light.radius};
    return spotSetupInFrame(in, spot, rolledToFit(spotFrame(spot.wsPosition, spot.wsDirection), receivers.vertices()));
}

ShadowSetup noMap(const PointLight& light, int mapSize) {
    ShadowSetup setup = localSetup(LightType::Spot, light.wsPosition, mapSize);
    setup.fallbacks.emplace_back("point: its range misses what the camera sees of the scene: no map");
    setEyeRelativeFromWorld(setup, light.wsPosition);
    return setup;
}

constexpr double kWidestConeDegrees = 170.0; // the spot map's own bound (SpotLight::validate)

} // namespace

Result<ShadowSetup> computePointSingleMapSetup(const LocalShadowInputs& in, const PointLight& light) {
    if (Status s = checkInputs(in); !s) return s.errorInfo();
    if (Status s = light.validate(); !s) return s.errorInfo();
    // R's corners within the range's cube; the spot's far plane (at the range along the axis)
    // then cuts only points farther than the range, which the light does not reach.
    const ConvexBody receivers = visibleInRange(in, light.wsPosition, light.range);
    if (receivers.isEmpty()) return noMap(light, in.mapSize);
    const auto cone = coneOver(receivers, light);
    if (!(cone.first <= kWidestConeDegrees)) {
        // Past 180° the corners' directions no longer fit a cone: the light is among them.
        char what[160];
        if (cone.first < 180.0)
            std::snprintf(what, sizeof what,
                          "what the camera sees within the light's range spans a cone of %.0f degrees from it: one "
                          "map holds at most %g; a cube holds it",
                          std::ceil(cone.first), kWidestConeDegrees);
        else
            std::snprintf(what, sizeof what,
                          "what the camera sees within the light's range surrounds it: one map holds at most a cone "
                          "of %g degrees; a cube holds it",
                          kWidestConeDegrees);
        return fieldError("point.position", what);
    }
    return oneMapOver(in, light, receivers, cone);
}

Result<ShadowSetup> computePointAimedMapSetup(const LocalShadowInputs& in, const PointLight& light,
                                              double coneDegrees) {
    if (Status s = checkInputs(in); !s) return s.errorInfo();
    if (Status s = light.validate(); !s) return s.errorInfo();
    if (!(coneDegrees > 0.0 && coneDegrees <= kWidestConeDegrees))
        return fieldError("point.cone", "must be in (0, 170] degrees");
    const ConvexBody receivers = visibleInRange(in, light.wsPosition, light.range);
    if (receivers.isEmpty()) return noMap(light, in.mapSize);
    // Aimed at the mean of R's corners: the light among them, no direction holds them all, and
    // this one leans to where most of R lies.
    Vec3 sum(0.0);
    for (const Vec3& p : receivers.vertices()) sum += p;
    Vec3 aim = sum / double(receivers.vertices().size()) - light.wsPosition;
    if (!(glm::length(aim) > 1e-9 * light.range)) aim = in.camera.wsDirection; // R centred on the light
    const SpotLight spot{.wsPosition = light.wsPosition,
                         .wsDirection = glm::normalize(aim),
                         .coneDegrees = coneDegrees,
                         .range = light.range,
                         .radius = light.radius};
    Result<ShadowSetup> setup = spotSetupInFrame(in, spot, spotFrame(spot.wsPosition, spot.wsDirection));
    if (setup && !setup->views.empty()) {
        setup->holdsPartOfView = true;
        setup->fallbacks.push_back("point: what the camera sees within the light's range surrounds it; one map of " +
                                   std::to_string(int(std::lround(coneDegrees))) +
                                   " degrees aimed at the middle of it: receivers outside that cone get no shadow "
                                   "from this light (a cube holds them all)");
    }
    return setup;
}

Result<ShadowSetup> computePointSingleOrAimedMapSetup(const LocalShadowInputs& in, const PointLight& light) {
    // The single map refuses bad input and a light among what the camera sees alike under
    // "point.position"; the aimed map refuses the first again and takes the second.
    Result<ShadowSetup> whole = computePointSingleMapSetup(in, light);
    if (whole || whole.errorInfo().field != "point.position") return whole;
    return computePointAimedMapSetup(in, light);
}

Status validate(const LocalBias& b) {
    if (!(b.slopeTexels >= 0.0 && b.slopeTexels <= 16.0))
        return fieldError("local_bias.slope", "must be in [0, 16] texels");
    if (!(b.normalOffsetTexels >= 0.0 && b.normalOffsetTexels <= 16.0))
        return fieldError("local_bias.normal_offset", "must be in [0, 16] texels");
    if (!(b.constantMetres >= 0.0 && b.constantMetres <= 1.0))
        return fieldError("local_bias.constant", "must be in [0, 1] metres");
    return Ok{};
}

Vec2 storedFromDistance(double range, bool reversedZ) {
    return reversedZ ? Vec2(-1.0 / range, 1.0) : Vec2(1.0 / range, 0.0);
}

} // namespace shadowkit::core
