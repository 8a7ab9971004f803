// The focus body B: the part of the scene whose depth the shadow map must hold.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/light.h"

namespace shadowkit::core {

/// B = ((V ∩ S) swept towards the light) ∩ S, with V the view frustum and S the scene
/// box. V ∩ S holds every visible receiver; sweeping it towards the light and clipping by
/// S adds every caster that can shadow one. Empty when the frustum misses the scene box.
///
/// S is padded to a minimum thickness first (sceneBoxForFocus), so a flat or
/// zero-size scene still gives a body with volume.
///
/// Each thread keeps its last result and returns it again for exactly the same camera, light
/// and box: a set-up search tries many warps of one frame's body (error_driven.h). Its first
/// half, V ∩ S, carries over from earlier frames (visibleSceneBody).
ConvexBody computeFocusBody(const PerspectiveCamera& camera, const DirectionalLight& light, const Aabb& wsSceneBounds);

/// V ∩ S, the first half of computeFocusBody: the part of the (padded) scene box the camera
/// sees. Empty when the frustum misses the box. Each thread keeps its last result for exactly the
/// same camera and box; for new ones it re-solves the body from an earlier frame's structure
/// while that provably still holds (ConvexBodyStructure: the same triples of planes at its
/// corners, each strictly inside the others), which a moving camera allows most frames; the
/// result is the same, to the last bit, as the body clipped afresh.
ConvexBody visibleSceneBody(const PerspectiveCamera& camera, const Aabb& wsSceneBounds);

/// The second half: B from a given V ∩ S (its sweep towards the light, cut by the scene box).
/// Cascades hand each split the view's V ∩ S cut by the split's near and far planes, the same
/// set as the split's own V ∩ S for two cuts instead of six.
ConvexBody focusBodyFromVisible(const ConvexBody& visibleScene, const Vec3& wsTowardsLight, const Aabb& wsSceneBounds);

/// The scene box grown so that no side is thinner than a millionth of its diagonal
/// (or a millimetre for a zero-size box): a plane of terrain has zero height.
Aabb sceneBoxForFocus(const Aabb& wsSceneBounds);

} // namespace shadowkit::core
