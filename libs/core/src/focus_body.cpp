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

#include "shadowkit/core/convex_body_structure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

namespace shadowkit::core {

Aabb sceneBoxForFocus(const Aabb& wsSceneBounds) {
    SK_ASSERT(!wsSceneBounds.isEmpty(), "sceneBoxForFocus(): scene bounds must not be empty");
    // A flat scene (a ground alone) is given a millionth of its size of thickness, so the body
    // clipped by it keeps a volume; relative alone — a floor of a millimetre once made a model a
    // millimetre across a box twice its height, and its map half as fine. A point gets 1 mm.
    const double diagonal = wsSceneBounds.diagonal();
    const double minThickness = diagonal > 0.0 ? 1e-6 * diagonal : 1e-3;
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
    // Else re-solved from an earlier frame's structure where it still holds: the box's six planes
    // and the frustum's six define it, in that order.
    const Aabb box = sceneBoxForFocus(wsSceneBounds);
    const std::array<Plane, 6> boxPlanes = boxFaces(box), frustum = camera.wsFrustumPlanes();
    SmallVector<Plane, 12> definition;
    for (const Plane& p : boxPlanes) definition.push_back(p);
    for (const Plane& p : frustum) definition.push_back(p);
    const std::span<const Plane> planes(definition.data(), definition.size());
    thread_local ConvexBodyStructures structures;
    std::optional<ConvexBody> visible = structures.resolve(planes);
    if (!visible) {
        ConvexBody clipped = ConvexBody::fromAabb(box);
        clipped.clip(frustum);
        visible = structures.remember(std::move(clipped), planes);
    }
    last.emplace(std::pair{camera, wsSceneBounds}, *visible);
    return *visible;
}

ConvexBody focusBodyFromVisible(const ConvexBody& visibleScene, const Vec3& wsTowardsLight, const Aabb& wsSceneBounds) {
    if (visibleScene.isEmpty()) return {};
    // (V ∩ S swept) ∩ S: swept as far as the box's face that the sweep leaves it through
    // first (the least, over the faces facing the light, of the farthest any vertex travels
    // to reach it), then cut by the other faces facing the light, which the swept body then
    // rarely reaches. A face facing away cannot cut it: V ∩ S lies inside, n·p <= d, and the
    // sweep never raises n·(p + t·dir) for t >= 0 when n·dir <= 0.
    const Aabb box = sceneBoxForFocus(wsSceneBounds);
    const std::array<Plane, 6> boxPlanes = boxFaces(box);
    const Vec3 dir = glm::normalize(wsTowardsLight);
    std::array<double, 6> along{}; // n·dir per face: > 0 where the face faces the light
    size_t stop = 0;
    double nearest = INFINITY;
    for (size_t f = 0; f < boxPlanes.size(); ++f) {
        along[f] = glm::dot(boxPlanes[f].normal, dir);
        if (!(along[f] > 1e-3)) continue; // at least one face has along >= 1/√3
        // The farthest any vertex travels to the face: −(n·p + d) / along at the least n·p.
        const double lowest = visibleScene.rangeAlong(boxPlanes[f].normal).x;
        const double farthest = std::max(0.0, -(lowest + boxPlanes[f].d) / along[f]);
        if (farthest < nearest) nearest = farthest, stop = f;
    }
    ConvexBody body = visibleScene.sweptUntil(dir, boxPlanes[stop]);
    ConvexBody::Planes others;
    for (size_t f = 0; f < boxPlanes.size(); ++f)
        if (f != stop && along[f] > 0.0) others.push_back(boxPlanes[f]);
    body.clip(std::span<const Plane>(others.data(), others.size()));
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
