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

ConvexBody computeFocusBody(const PerspectiveCamera& camera, const DirectionalLight& light,
                            const Aabb& wsSceneBounds) {
    const Aabb sceneBox = sceneBoxForFocus(wsSceneBounds);

    ConvexBody visible = ConvexBody::fromAabb(sceneBox); // V ∩ S
    const auto frustumPlanes = camera.wsFrustumPlanes();
    visible.clip(frustumPlanes);
    if (visible.isEmpty()) return visible;

    ConvexBody body = ConvexBody::fromAabb(sceneBox); // (V ∩ S swept) ∩ S
    const ConvexBody::Planes sweep = visible.sweepHalfSpaces(light.wsTowardsLight());
    body.clip(std::span<const Plane>(sweep.data(), sweep.size()));
    return body;
}

} // namespace shadowkit::core
