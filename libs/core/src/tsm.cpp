// Trapezoidal shadow maps.
//
// Based on: Martin, Tan, "Anti-aliasing and Continuity with Trapezoidal Shadow Maps",
// EGSR 2004 (§4–5):
//   1. L: the light's post-perspective space. For the sun: the focused orthographic map of
//      B (x, y in [−1, 1]). B's footprint there is the view's footprint: B is V ∩ S swept
//      along the light, which projects onto itself, so bounding B bounds every receiver
//      and every caster's texel.
//   2. The centre line runs from the projected centre of the near plane to that of the far
//      plane; top and base lines are perpendicular to it and touch the footprint's hull;
//      λ is the distance between them.
//   3. The 80 % rule: the focus point (view depth z_n + focus·(z_f − z_n) on the view axis)
//      at distance δ' from the top line is sent to the 80 % line (ξ = −0.6) by placing the
//      projection point Q at η = λ δ' (1 + ξ) / (λ (1 − ξ) − 2 δ') beyond the top line.
//      The paper tunes the rule on views whose far/near ratio is large; where it is not (a
//      compact model seen from afar) the rule still warps hard and spends the map on B's
//      first metres: a 25 m model at `noon` was 27.5 % wrong at 28 pixels per texel where the
//      focused map was 2.07 % at 0.32. So η is also kept at or above the warp that the view's
//      own perspective asks for (below), and the map tends to the focused one as z_f/z_n → 1.
//   4. The trapezoid's sides pass through Q and touch the hull; a 2-D projective map sends it
//      to the square: y' = a + b / u (u: distance from Q along the centre line, u in
//      [η, η + λ] -> [−1, 1]) and x' proportional to (lateral offset) / u.
//   5. Depth: the paper's recommendation is L's own (linear) depth, written per vertex; the
//      set-up asks for it with DepthLayout::Linear. The matrix keeps z_L / u, which orders
//      depth along each light ray the same way (u is constant along a ray).
// Degenerate: when the view looks along the light the centre line has no length and no
// trapezoid exists: the focused map is used (the paper's own fallback).
#include "shadowkit/core/tsm.h"

#include "shadowkit/core/uniform_shadow_map.h"
#include "shadowkit/core/warp_fit.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {
namespace {

constexpr double kXi = -0.6; // Martin & Tan's "80 % line": ξ = −0.6 maps to 0.8 of the map

} // namespace

ShadowSetup computeTsm(const ShadowSetupInputs& in) {
    ShadowSetup setup = computeFocusedShadowMap(in);
    setup.technique = Technique::Tsm;
    if (setup.body.isEmpty()) return setup;
    ShadowView& view = setup.views[0];
    const Mat4 lFromWorld = view.clipFromWorld; // 1. L: the focused orthographic map

    const PerspectiveCamera& cam = in.camera;
    const Vec3 v = glm::normalize(cam.wsDirection);
    auto toL = [&](const Vec3& ws) { return Vec2(lFromWorld * Vec4(ws, 1.0)); }; // affine: w = 1
    const Vec2 nearCentre = toL(cam.wsEye + cam.zNear * v), farCentre = toL(cam.wsEye + cam.zFar * v);
    const Vec2 axis = farCentre - nearCentre;
    if (glm::length(axis) < 1e-6) { // in L units: the map spans 2
        view.warp = TsmWarp{.uniform = true};
        setup.fallbacks.emplace_back("tsm: view parallel to the light, no trapezoid: uniform map");
        return setup;
    }
    // 2. Centre line frame: u along the line (towards the far plane), w across it.
    const Vec2 u = glm::normalize(axis), w(-u.y, u.x);
    const ConvexBody::Points wsPoints = setup.body.vertices();
    double top = INFINITY, base = -INFINITY;
    for (const Vec3& p : wsPoints) {
        const double along = glm::dot(toL(p) - nearCentre, u);
        top = std::min(top, along);
        base = std::max(base, along);
    }
    const double lambda = base - top;

    // 3. The focus point and η; the view depths B spans (within the visible depth range when
    // the frame measured one) bound η from below.
    double bodyNear = cam.zFar, bodyFar = cam.zNear;
    for (const Vec3& p : wsPoints) {
        const double depth = glm::dot(p - cam.wsEye, v);
        bodyNear = std::min(bodyNear, depth), bodyFar = std::max(bodyFar, depth);
    }
    bodyNear = std::max(bodyNear, cam.zNear), bodyFar = std::min(bodyFar, cam.zFar);
    if (in.visibleDepth && in.visibleDepth->y > bodyNear && in.visibleDepth->x < bodyFar)
        bodyNear = std::max(bodyNear, in.visibleDepth->x), bodyFar = std::min(bodyFar, in.visibleDepth->y);
    if (!(bodyFar > bodyNear)) bodyNear = cam.zNear, bodyFar = cam.zFar;
    const double focusDepth = cam.zNear + in.tsm.focusFraction * (cam.zFar - cam.zNear);
    double delta = glm::dot(toL(cam.wsEye + focusDepth * v) - nearCentre, u) - top;
    // η needs δ' < 0.8 λ; below 0.01 λ the far/near ratio of the warp (≈ 400) would exceed
    // what float texel coordinates resolve, so the focus is kept off the top line.
    delta = std::clamp(delta, 0.01 * lambda, 0.75 * lambda);
    // The warp never outgrows the perspective it answers: texels thin out from the top line to
    // the base by (η + λ)/η along the centre line, the camera's pixels by z_f/z_n over B, so η
    // is kept at or above λ z_n / (z_f − z_n). On a terrain seen from its surface z_f/z_n is in
    // the hundreds and the 80 % rule's η stands; on a compact model seen from afar the ratio
    // nears 1 and the map tends to the focused one, as perspective aliasing vanishes there.
    const double perspectiveEta = lambda * bodyNear / std::max(bodyFar - bodyNear, 1e-3 * bodyNear);
    const double eta = std::max(lambda * delta * (1.0 + kXi) / (lambda * (1.0 - kXi) - 2.0 * delta),
                                std::min(perspectiveEta, 1e3 * lambda));

    // 4. Q and the sides through it; (a, b) = (along from Q, across) coordinates.
    const Vec2 q = nearCentre + (top - eta) * u;
    double sMin = INFINITY, sMax = -INFINITY;
    for (const Vec3& p : wsPoints) {
        const Vec2 d = toL(p) - q;
        const double slope = glm::dot(d, w) / glm::dot(d, u); // along >= η > 0
        sMin = std::min(sMin, slope);
        sMax = std::max(sMax, slope);
    }
    if (!(sMax - sMin > 1e-12)) sMax = sMin + 1e-12;
    const double n = eta, f = eta + lambda;
    // Homogeneous map of L (x, y, z, 1): A = a, B = b relative to Q, then
    //   X = (2 B − (sMax + sMin) A) / (sMax − sMin),  Y = (f + n)/(f − n) A − 2 f n/(f − n),
    //   Z = z_L,  W = A.
    Mat4 toAB(1.0); // L -> (a, b, z, 1)
    toAB[0][0] = u.x, toAB[1][0] = u.y, toAB[3][0] = -glm::dot(q, u);
    toAB[0][1] = w.x, toAB[1][1] = w.y, toAB[3][1] = -glm::dot(q, w);
    Mat4 trapezoid(0.0);
    trapezoid[0][0] = -(sMax + sMin) / (sMax - sMin);
    trapezoid[1][0] = 2.0 / (sMax - sMin);
    trapezoid[0][1] = (f + n) / (f - n);
    trapezoid[3][1] = -2.0 * f * n / (f - n);
    trapezoid[2][2] = 1.0;
    trapezoid[0][3] = 1.0;

    ConvexBody::Points lsPoints; // light space = the focused map's light frame
    for (const Vec3& p : wsPoints) lsPoints.push_back(Vec3(view.lightFromWorld * Vec4(p, 1.0)));
    view.clipFromLight = fitToClipCube(trapezoid * toAB * view.clipFromLight, lsPoints);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    view.warp = TsmWarp{.lambda = lambda, .delta = delta, .eta = eta};
    return setup;
}

} // namespace shadowkit::core
