// The focus body B.
//
// Based on: Wimmer, Scherzer, Purgathofer, "Light Space Perspective Shadow Maps",
// EGSR 2004 (§3.3), and Scherzer, "Robust Shadow Maps for Large Environments", CESCG 2005
// (§4.1; full citations in docs/references.md): B is the convex hull of the view frustum
// and the light position, clipped by the scene box. For a directional light the "light
// position" is at infinity, so the hull is the frustum swept along the light's reverse
// direction.
// Deviation: we first intersect V with S (so the sweep starts only from visible
// receivers), then clip the sweep by S. Both papers compute the same set; the authors' 2004 demo
// code approximated the sweep by appending one exit point per vertex, which loses volume
// when rays leave S through different faces — here the sweep is exact (ConvexBody).
#include "shadowkit/core/focus_body.h"

#include <optional>
#include <utility>

namespace shadowkit::core {

Aabb sceneBoxForFocus(const Aabb& wsSceneBounds) {
    SK_ASSERT(!wsSceneBounds.isEmpty(), "sceneBoxForFocus(): scene bounds must not be empty");
    const double minThickness = std::max(1e-6 * wsSceneBounds.diagonal(), 1e-3);
    Aabb box = wsSceneBounds;
    for (int axis = 0; axis < 3; ++axis) {
        const double grow = 0.5 * std::max(0.0, minThickness - (box.max[axis] - box.min[axis]));
        box.min[axis] -= grow;
        box.max[axis] += grow;
    }
    return box;
}

namespace {

bool sameCamera(const PerspectiveCamera& a, const PerspectiveCamera& b) {
    return a.wsEye == b.wsEye && a.wsDirection == b.wsDirection && a.wsUp == b.wsUp && a.fovYDegrees == b.fovYDegrees &&
           a.aspect == b.aspect && a.zNear == b.zNear && a.zFar == b.zFar;
}

} // namespace

ConvexBody visibleSceneBody(const PerspectiveCamera& camera, const Aabb& wsSceneBounds) {
    // The last V ∩ S per thread, as computeFocusBody keeps B: a TSM set-up asks for it again
    // after B (where its nearest receivers lie, tsm.cpp). Exact comparison.
    thread_local std::optional<std::pair<std::pair<PerspectiveCamera, Aabb>, ConvexBody>> last;
    if (last && sameCamera(last->first.first, camera) && last->first.second.min == wsSceneBounds.min &&
        last->first.second.max == wsSceneBounds.max)
        return last->second;
    ConvexBody visible = ConvexBody::fromAabb(sceneBoxForFocus(wsSceneBounds));
    visible.clip(camera.wsFrustumPlanes());
    last.emplace(std::pair{camera, wsSceneBounds}, visible);
    return visible;
}

ConvexBody focusBodyFromVisible(const ConvexBody& visibleScene, const Vec3& wsTowardsLight, const Aabb& wsSceneBounds) {
    if (visibleScene.isEmpty()) return {};
    // (V ∩ S swept) ∩ S. Only the sweep's planes that cut S can cut the body: those of V ∩ S's
    // faces lying on S's own faces, and silhouettes beyond S, are passed over at the cost of
    // one dot product each (the box's corner farthest out along the plane's normal).
    const Aabb sceneBox = sceneBoxForFocus(wsSceneBounds);
    const ConvexBody::Planes sweep = visibleScene.sweepHalfSpaces(wsTowardsLight);
    const Vec3 centre = sceneBox.center(), half = 0.5 * (sceneBox.max - sceneBox.min);
    ConvexBody::Planes cutting;
    for (const Plane& plane : sweep)
        if (plane.signedDistance(centre) + glm::dot(glm::abs(plane.normal), half) > 0.0) cutting.push_back(plane);
    ConvexBody body = ConvexBody::fromAabb(sceneBox);
    body.clip(std::span<const Plane>(cutting.data(), cutting.size()));
    return body;
}

namespace {

// What B depends on, compared exactly.
struct FocusBodyKey {
    PerspectiveCamera camera;
    Vec3 wsTowardsLight;
    Aabb wsSceneBounds;
    bool operator==(const FocusBodyKey& o) const {
        return sameCamera(camera, o.camera) && wsTowardsLight == o.wsTowardsLight &&
               wsSceneBounds.min == o.wsSceneBounds.min && wsSceneBounds.max == o.wsSceneBounds.max;
    }
};

} // namespace

ConvexBody computeFocusBody(const PerspectiveCamera& camera, const DirectionalLight& light, const Aabb& wsSceneBounds) {
    // The last body per thread, returned again for the same inputs: B is about 80 % of a
    // single map's set-up (docs/performance.md), and the error-driven search (error_driven.h)
    // computes dozens of set-ups of one camera, light and scene per frame, differing only in
    // the warp's parameters. Exact comparison, so the result is the one computed afresh.
    thread_local std::optional<std::pair<FocusBodyKey, ConvexBody>> last;
    const FocusBodyKey key{camera, light.wsTowardsLight(), wsSceneBounds};
    if (last && last->first == key) return last->second;
    ConvexBody body = focusBodyFromVisible(visibleSceneBody(camera, wsSceneBounds), key.wsTowardsLight, wsSceneBounds);
    last.emplace(key, body);
    return body;
}

} // namespace shadowkit::core
