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
//      own perspective asks for (below), and the map tends to the focused one as z_f/z_n → 1,
//      or as the nearest pixels at the trapezoid's two ends draw level (the sun behind the
//      viewer, where the centre line runs across a model rather than into it); where the
//      receivers do not widen along the line (a model inside the frustum) the warp is held to
//      what pixels facing the camera ask for, √(z_b/z_t).
//   4. The trapezoid's sides pass through Q and touch the hull; a 2-D projective map sends it
//      to the square: y' = a + b / u (u: distance from Q along the centre line, u in
//      [η, η + λ] -> [−1, 1]) and x' proportional to (lateral offset) / u.
//   5. Depth: the paper's recommendation is L's own (linear) depth, written per vertex; the
//      set-up asks for it with DepthLayout::Linear. The matrix keeps z_L / u, which orders
//      depth along each light ray the same way (u is constant along a ray).
// Degenerate: when the view looks along the light the centre line has no length and no
// trapezoid exists: the focused map is used (the paper's own fallback).
#include "shadowkit/core/tsm.h"

#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/uniform_shadow_map.h"
#include "shadowkit/core/warp_fit.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {
namespace {

constexpr double kXi = -0.6;        // Martin & Tan's "80 % line": ξ = −0.6 maps to 0.8 of the map
constexpr double kEndBand = 0.25;   // the share of the footprint at each end whose nearest pixel it asks for
constexpr double kWarpedEnds = 0.5; // z_b / z_t − 1 from which the view's whole depth ratio may be warped
constexpr double kWidening = 1.0;   // base / top width of the receivers − 1 from which they widen as ground does

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

    // 3. The focus point and η; the perspective the warp answers bounds η from below: the view
    // depths B spans (within the visible depth range when the frame measured one) and where
    // the nearest pixels lie along the centre line.
    double bodyNear = cam.zFar, bodyFar = cam.zNear;
    for (const Vec3& p : wsPoints) {
        const double depth = glm::dot(p - cam.wsEye, v);
        bodyNear = std::min(bodyNear, depth), bodyFar = std::max(bodyFar, depth);
    }
    bodyNear = std::max(bodyNear, cam.zNear), bodyFar = std::min(bodyFar, cam.zFar);
    if (in.visibleDepth && in.visibleDepth->y > bodyNear && in.visibleDepth->x < bodyFar)
        bodyNear = std::max(bodyNear, in.visibleDepth->x), bodyFar = std::min(bodyFar, in.visibleDepth->y);
    if (!(bodyFar > bodyNear)) bodyNear = cam.zNear, bodyFar = cam.zFar;
    auto viewDepth = [&](const Vec3& ws) { return std::clamp(glm::dot(ws - cam.wsEye, v), bodyNear, bodyFar); };
    // The nearest view depth in the first and in the last kEndBand of the receivers' extent
    // along the centre line: what the finest pixels at each end ask of the map. The receivers
    // are V ∩ S, not B, whose sweep towards the light adds casters that no pixel sees. Depth
    // being linear, the nearest receiver of a band is a vertex of V ∩ S inside it or a point
    // where one of its edges crosses the band's edge.
    const ConvexBody receivers = visibleSceneBody(cam, in.wsSceneBounds);
    const Vec3 wsAlong = glm::transpose(glm::dmat3(lFromWorld)) * Vec3(u, 0.0); // ∇along, per metre
    const double along0 = glm::dot(toL(Vec3(0.0)) - nearCentre, u);             // along at the origin
    auto alongOf = [&](const Vec3& ws) { return glm::dot(wsAlong, ws) + along0; };
    double receiversTop = INFINITY, receiversBase = -INFINITY;
    const ConvexBody::Points receiverCorners = receivers.vertices();
    const ConvexBody::Edges receiverEdges = receivers.edges();
    for (const Vec3& p : receiverCorners)
        receiversTop = std::min(receiversTop, alongOf(p)), receiversBase = std::max(receiversBase, alongOf(p));
    // Across the line likewise (∇across, per metre): the band's width, linear too, is spanned
    // by the same points.
    const Vec3 wsAcross = glm::transpose(glm::dmat3(lFromWorld)) * Vec3(w, 0.0);
    struct Band {
        double nearest = INFINITY;                          // view depth of its nearest receiver
        double acrossMin = INFINITY, acrossMax = -INFINITY; // its extent across the line, L units
    };
    auto bandOf = [&](double sign, double edge) { // the receivers with sign·(along − edge) <= 0
        Band band;
        auto take = [&](const Vec3& ws) {
            const double across = glm::dot(wsAcross, ws);
            band.nearest = std::min(band.nearest, viewDepth(ws));
            band.acrossMin = std::min(band.acrossMin, across);
            band.acrossMax = std::max(band.acrossMax, across);
        };
        for (const Vec3& p : receiverCorners)
            if (sign * (alongOf(p) - edge) <= 0.0) take(p);
        for (const auto& [a, b] : receiverEdges) {
            const double da = sign * (alongOf(a) - edge), db = sign * (alongOf(b) - edge);
            if ((da < 0.0) != (db < 0.0)) take(a + (da / (da - db)) * (b - a));
        }
        return band;
    };
    const double receiversLength = receiversBase - receiversTop; // -inf for no receivers (not reached: B is empty then)
    const Band topBand = receiversLength > 0.0 ? bandOf(1.0, receiversTop + kEndBand * receiversLength) : Band{};
    const Band baseBand = receiversLength > 0.0 ? bandOf(-1.0, receiversBase - kEndBand * receiversLength) : Band{};

    const double focusDepth = cam.zNear + in.tsm.focusFraction * (cam.zFar - cam.zNear);
    double delta = glm::dot(toL(cam.wsEye + focusDepth * v) - nearCentre, u) - top;
    // η needs δ' < 0.8 λ; below 0.01 λ the far/near ratio of the warp (≈ 400) would exceed
    // what float texel coordinates resolve, so the focus is kept off the top line.
    delta = std::clamp(delta, 0.01 * lambda, 0.75 * lambda);
    // The warp never outgrows the perspective it answers: texels thin out from the top line to
    // the base by r = (η + λ)/η along the centre line, the camera's pixels by at most
    // z_f/z_n over B, so r <= z_f/z_n, η >= λ / (z_f/z_n − 1). On a terrain seen from its
    // surface z_f/z_n is in the hundreds and the 80 % rule's η stands; on a compact model seen
    // from afar it nears 1 and the map tends to the focused one, as perspective aliasing
    // vanishes there. And the far pixels must lie at the base: with the sun behind the viewer
    // the centre line is short, the footprint's extent along it is the model's width rather
    // than its depth, and the nearest pixels at the base end are no farther than those at the
    // top (z_b <= z_t): B's depth range warped a 12 m model seen from 13 m with the
    // sun behind into texels 2.5 times coarser than the focused map's at the median pixel. So
    // the allowed ratio fades from z_f/z_n, where z_b exceeds z_t by kWarpedEnds or more (every
    // view of a terrain), to 1 (no warp) where z_b <= z_t, geometrically: r = (z_f/z_n)^t.
    // (Bounding r by z_b/z_t itself also starves the far band's majority on views from above:
    // the sampling model's best TSM on the forest's `aerial` coarsens from 0.339 to 0.370 pixels
    // per texel at the median.)
    // Nor may the warp outgrow what the receivers' footprint can use. Along the line a texel's
    // length grows as u², across it its width as u (the trapezoid's), so from top to base the
    // worst direction's texel — the one eval's pixels per texel measures — grows by r². Ground
    // seen at a grazing angle asks for that much: its pixels' footprints grow as z² along the
    // ground (and as z across, where the ground's footprint widens with the frustum's: on a
    // terrain the receivers' width at the base is 2.5–4 times that at the top), so r = z_b/z_t,
    // which the view's ratio above allows. A compact model inside the frustum does not widen,
    // and its pixels on surfaces facing the camera grow as z in every direction: the warp that
    // fits them is r² = z_b/z_t. Without that bound the default's median texel on framed models
    // seen into the sun was up to 1.47 times the focused map's. The width ratio g of base to top
    // band says which: the bound holds in full at g = 1 and fades out geometrically by
    // g = 1 + kWidening.
    const double endsRatio =
        baseBand.nearest / topBand.nearest; // z_b / z_t: NaN where V ∩ S has no length along the line
    const double endsApart = std::isfinite(endsRatio) ? std::clamp((endsRatio - 1.0) / kWarpedEnds, 0.0, 1.0) : 1.0;
    double allowedRatio = std::pow(bodyFar / bodyNear, endsApart); // t = endsApart
    const double topWidth = topBand.acrossMax - topBand.acrossMin, baseWidth = baseBand.acrossMax - baseBand.acrossMin;
    const double widthRatio = topWidth > 0.0 && baseWidth > 0.0 ? baseWidth / topWidth : NAN; // g
    if (std::isfinite(endsRatio) && std::isfinite(widthRatio)) {
        const double widening = std::clamp((widthRatio - 1.0) / kWidening, 0.0, 1.0);
        const double facingRatio = std::min(allowedRatio, std::sqrt(std::max(endsRatio, 1.0)));
        allowedRatio = std::pow(allowedRatio, widening) * std::pow(facingRatio, 1.0 - widening);
    }
    const double perspectiveEta = allowedRatio > 1.0 + 1e-3 ? lambda / (allowedRatio - 1.0) : 1e3 * lambda;
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
    view.warp = TsmWarp{.lambda = lambda, .delta = delta, .eta = eta, .endsRatio = endsRatio, .widthRatio = widthRatio};
    return setup;
}

} // namespace shadowkit::core
