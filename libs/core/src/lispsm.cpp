// Light space perspective shadow maps.
//
// Based on: Wimmer, Scherzer, Purgathofer, "Light Space Perspective Shadow Maps",
// EGSR 2004: light space §3.4, the frustum P and its projection reference
// point §3.4–3.5, n_opt §4.3–4.4; and Scherzer's practical improvements (Scherzer 2005 §4.4):
// n_opt from the depth extent Δz of B (eq. 1), Δz from the visible far distance for n only
// (and, as an option of ours, z_n from the visible near distance: LispsmOptions), the
// projection direction V_P as a cross product (eq. 3) or B's "middle vector".
//
// Construction (column vectors): clipFromWorld = Fit · P(n, n + d) · T(−C) · lightFromWorld.
//   light space: looks along the light; +y = V_P (the warp axis), −z = the light direction.
//   P: perspective along +y; C = (eye.x, y_min(B) − n, middle of B's depth), so every point
//   of B has r.y = y − C.y >= n > 0 and none lies behind the projection centre
//   (docs/references.md, pitfall 2: C relative to B, not to the eye).
//   Fit: B's NDC bounds to the clip cube.
// Deviations: γ → 0 is handled by the n/d ratio (kLispsmUniformRatio) rather than a fixed
// angle: the switch happens where the warp has already converged to uniform, so there is
// no visible jump, and no 1/sin γ is evaluated at sin γ = 0 (docs/references.md, pitfall 1).
// The general-case z0 is the closed form (pitfall 3).
#include "shadowkit/core/lispsm.h"

#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/light_frame.h"
#include "shadowkit/core/uniform_shadow_map.h"
#include "shadowkit/core/warp_fit.h"

#include <cmath>
#include <string>

namespace shadowkit::core {
namespace {

Vec3 perpendicularTo(const Vec3& v, const Vec3& unitAxis) { return v - glm::dot(v, unitAxis) * unitAxis; }

// Extent along light-space y of B cut to the visible view-depth slab (for n only).
double visibleExtent(const ConvexBody& body, const PerspectiveCamera& cam, const Vec2& visible,
                     const Mat4& lightFromWorld) {
    ConvexBody cut = body;
    const Vec3 forward = glm::normalize(cam.wsDirection);
    cut.clip(Plane::fromPointNormal(cam.wsEye + visible.x * forward, -forward));
    cut.clip(Plane::fromPointNormal(cam.wsEye + visible.y * forward, forward));
    if (cut.isEmpty()) return 0.0;
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& p : cut.vertices()) {
        const double y = (lightFromWorld * Vec4(p, 1.0)).y;
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    return hi - lo;
}

} // namespace

ShadowSetup computeLispsm(const ShadowSetupInputs& in) {
    return computeLispsm(in, computeFocusBody(in.camera, in.light, in.wsSceneBounds));
}

ShadowSetup computeLispsm(const ShadowSetupInputs& in, const ConvexBody& body) {
    // The uniform map LiSPSM converges to: also the answer in every degenerate case.
    ShadowSetup setup = computeFocusedShadowMap(in, body);
    setup.technique = Technique::Lispsm;
    if (setup.body.isEmpty()) return setup;

    const PerspectiveCamera& cam = in.camera;
    const LispsmOptions& o = in.lispsm;
    const Vec3 l = in.light.wsDirection;
    const Vec3 v = glm::normalize(cam.wsDirection);
    const double sinGamma = glm::length(glm::cross(v, l));
    const double gammaDegrees = glm::degrees(std::atan2(sinGamma, glm::dot(v, l)));
    const ConvexBody::Points wsPoints = setup.body.vertices();

    Vec3 projection = perpendicularTo(v, l); // (l ⊗ v) ⊗ l, unnormalized
    if (o.direction == LispsmDirection::MiddleVector) {
        Vec3 middle(0.0);
        for (const Vec3& p : wsPoints) middle += p - cam.wsEye;
        const Vec3 perpendicular = perpendicularTo(middle, l);
        if (glm::length(perpendicular) > kParallelSine * glm::length(middle)) projection = perpendicular;
    }
    ShadowView& view = setup.views[0];
    // Only an exactly (anti-)parallel view has no warp axis: |v⊥| = sin γ carries ~1e-16 of
    // rounding, so its direction is still exact at 1e-12. Everything above converges to
    // uniform smoothly through the n/d test below.
    if (glm::length(projection) < kLispsmParallelSine) {
        view.warp = LispsmWarp{.gammaDegrees = gammaDegrees, .uniform = true, .viewParallel = true};
        setup.fallbacks.emplace_back(
            "lispsm: view parallel to the light, no perspective aliasing to correct: uniform map");
        return setup;
    }

    const LightFrame frame = makeLightFrame(l, cam.wsEye, {projection});
    ConvexBody::Points lsPoints;
    Aabb lsBounds;
    for (const Vec3& p : wsPoints) {
        lsPoints.push_back(Vec3(frame.lightFromWorld * Vec4(p, 1.0)));
        lsBounds.extend(lsPoints.back());
    }
    const double d = lsBounds.max.y - lsBounds.min.y; // depth of P along the warp axis

    double zNear = cam.zNear;
    double deltaZ = d;
    if (in.visibleDepth) {
        // Δz: B cut to the visible slab, measured along the warp axis. B itself stays whole.
        if (o.visibleNear && in.visibleDepth->x < cam.zFar) zNear = std::max(zNear, in.visibleDepth->x);
        const double visible = visibleExtent(setup.body, cam, Vec2(zNear, in.visibleDepth->y), frame.lightFromWorld);
        if (visible > 0.0) deltaZ = std::min(d, visible);
    }
    double n = 0.0;
    if (o.nOverride) {
        n = *o.nOverride;
    } else {
        const double sinG = std::max(sinGamma, 1e-300); // > 0 here (|v⊥| = sin γ); guard anyway
        switch (o.formula) {
        case LispsmFormula::Paper: {
            const double z0 = zNear, z1 = zNear + d * sinG;
            n = (z0 + std::sqrt(z0 * z1)) / sinG;
            break;
        }
        case LispsmFormula::Scherzer:
            n = (zNear + std::sqrt(zNear * (zNear + deltaZ))) / sinG;
            break;
        }
        n *= o.weight;
    }
    LispsmWarp& warp =
        view.warp.emplace<LispsmWarp>(LispsmWarp{.n = n, .f = n + d, .d = d, .gammaDegrees = gammaDegrees});
    view.lightFromWorld = frame.lightFromWorld;
    if (!(d > 0.0) || n > kLispsmUniformRatio * d) {
        // The uniform limit in the same light frame, so the texel grid does not turn at the switch.
        warp.uniform = true;
        view.clipFromLight = fitOrthographic(frame.lightFromWorld, wsPoints);
        view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
        setup.fallbacks.emplace_back("lispsm: n = " + std::to_string(n) + " m exceeds " +
                                     std::to_string(int(kLispsmUniformRatio)) +
                                     " d (view nearly parallel to the light): uniform map");
        return setup;
    }

    // P looking along +y from C; y' = a + b / r.y maps r.y = n -> -1 and r.y = f -> +1.
    const double f = n + d;
    const double a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
    const Vec3 c(0.0 /* the eye is the frame's origin */, lsBounds.min.y - n, 0.5 * (lsBounds.min.z + lsBounds.max.z));
    Mat4 perspective(0.0);
    perspective[0][0] = 1.0; // X = r.x
    perspective[1][1] = a;   // Y = a r.y + b
    perspective[3][1] = b;
    perspective[2][2] = -1.0; // Z = -r.z: depth grows away from the light
    perspective[1][3] = 1.0;  // W = r.y
    const Mat4 preClipFromLight = perspective * glm::translate(Mat4(1.0), -c);

    view.clipFromLight = fitToClipCube(preClipFromLight, lsPoints);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    return setup;
}

} // namespace shadowkit::core
