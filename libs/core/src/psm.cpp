// Perspective shadow maps.
//
// Based on: Stamminger, Drettakis, "Perspective Shadow Maps", SIGGRAPH 2002, as the
// LiSPSM papers describe it (Wimmer et al. 2004 §2, §4.3–4.5; Scherzer 2005 §4.4):
//   1. Post-perspective space (PP) of a virtual camera: the real camera slid back along its
//      view axis until every point of the focus body B lies at least z_n in front of it,
//      so no caster reaches the camera plane, where PP has its singularity.
//   2. The directional light becomes the homogeneous PP point L = M_pp (l_towards, 0).
//      With the zero-to-one projection its PP depth is f/(f − n) > 1 whatever the sign of
//      L.w, i.e. beyond every point of B (which spans [0, 1]): a projection looking from L
//      down −z_pp has all of B in front of it.
//   3. L.w > 0 (sun ahead): a point light in PP; occluders lie between a point and L.
//      L.w < 0 (sun behind the viewer): the light ray from a point leaves L's side, goes
//      through the camera plane and comes back: occluders lie *farther* from L, so the
//      depth order is inverted (depth decreasing with distance from L).
//      |L.w| ≈ 0 (light parallel to the view plane): a directional light in PP, orthographic.
//   4. Fit B's image to the clip cube.
// Deviation: the original pushes the virtual near plane as far into the scene as a depth
// read-back allows; we avoid read-backs and keep it at the camera's near distance.
#include "shadowkit/core/psm.h"

#include "shadowkit/core/light_frame.h"
#include "shadowkit/core/uniform_shadow_map.h"
#include "shadowkit/core/warp_fit.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {
namespace {

// Below this |L.w| / |L.xyz| the PP light is treated as directional: L then lies 10^4
// times B's PP extent away, where the perspective differs from parallel by < 0.01 %.
constexpr double kPpDirectionalRatio = 1e-4;

} // namespace

ShadowSetup computePsm(const ShadowSetupInputs& in) {
    ShadowSetup setup = computeFocusedShadowMap(in);
    setup.technique = Technique::Psm;
    if (setup.body.isEmpty()) return setup;

    const PerspectiveCamera& cam = in.camera;
    const Vec3 v = glm::normalize(cam.wsDirection);
    const ConvexBody::Points wsPoints = setup.body.vertices();
    double minDepth = INFINITY, maxDepth = -INFINITY;
    for (const Vec3& p : wsPoints) {
        const double depth = glm::dot(p - cam.wsEye, v);
        minDepth = std::min(minDepth, depth);
        maxDepth = std::max(maxDepth, depth);
    }
    // 1. Slide back so B starts at the camera's near distance from the virtual eye.
    const double slideBack = std::max(0.0, cam.zNear - minDepth);
    const double ppNear = minDepth + slideBack;
    const double ppFar = std::max(maxDepth + slideBack, ppNear * (1.0 + 1e-9));
    PerspectiveCamera virtualCam = cam;
    virtualCam.wsEye = cam.wsEye - slideBack * v;
    const Mat4 viewFromWorld = virtualCam.viewFromWorld();
    const Mat4 ppFromView = perspectiveZeroToOne(glm::radians(90.0), 1.0, ppNear, ppFar);

    ConvexBody::Points vsPoints;
    for (const Vec3& p : wsPoints) vsPoints.push_back(Vec3(viewFromWorld * Vec4(p, 1.0)));

    // 2. The light in PP space.
    const Vec4 light = ppFromView * (viewFromWorld * Vec4(in.light.wsTowardsLight(), 0.0));
    const double lightXyz = glm::length(Vec3(light));
    Mat4 lightFromPp(1.0); // 3. the projection in PP space, before the fit
    bool inverted = false;
    if (std::abs(light.w) < kPpDirectionalRatio * lightXyz) {
        // Directional in PP: orthographic along −L.xyz, depth growing away from the light.
        const LightFrame frame = makeLightFrame(-Vec3(light), Vec3(0.0), {Vec3(0, 1, 0)});
        Mat4 flipDepth(1.0);
        flipDepth[2][2] = -1.0;
        lightFromPp = flipDepth * frame.lightFromWorld;
    } else {
        const Vec3 lp = Vec3(light) / light.w; // PP position of the light; lp.z = f/(f − n) > 1
        inverted = light.w < 0.0;
        // From L looking down −z_pp: X = q.x − L.x, Y = q.y − L.y, W = L.z − q.z > 0 on B;
        // Z = −W' with W' = 1 (normal: z_ndc = −1/W grows with distance from L) or +1
        // (inverted: z_ndc = 1/W shrinks with distance from L).
        Mat4 m(0.0);
        m[0][0] = 1.0;
        m[3][0] = -lp.x;
        m[1][1] = 1.0;
        m[3][1] = -lp.y;
        m[3][2] = inverted ? 1.0 : -1.0;
        m[2][3] = -1.0;
        m[3][3] = lp.z;
        lightFromPp = m;
    }
    ShadowView& view = setup.views[0];
    view.lightFromWorld = viewFromWorld;
    view.clipFromLight = fitToClipCube(lightFromPp * ppFromView, vsPoints);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    view.warp = PsmWarp{.slideBack = slideBack,
                        .ppNear = ppNear,
                        .ppFar = ppFar,
                        .lightW = light.w / std::max(lightXyz, 1e-300),
                        .inverted = inverted};
    return setup;
}

} // namespace shadowkit::core
