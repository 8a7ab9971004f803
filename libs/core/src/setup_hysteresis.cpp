// Held texel lattices (setup_hysteresis.h).
//
// Why a whole-texel shift in clip space is exact for any projective map: the map's texel
// centres lie at x_ndc = −1 + (i + ½)·2/N. Adding t·w to clip x (a row operation on the
// matrix) adds t to x_ndc = x / w for every point, so with t a multiple of 2/N every texel
// centre lands on a former texel centre: the same world points are sampled, whatever the
// warp. The pops left are the refits, so the design question is only when to refit:
// - coverage: the view's focus body must fit inside the held map after the shift;
// - staleness: LiSPSM and TSM put their densest texels where the viewer was at the refit; a
//   camera that moves on leaves them behind. The texel footprint along the central ray, held
//   against what a refit would give now, says when a refit would pay `maxTexelGrowth`: a bound
//   in the quantity the error depends on (seed 000 §4: dp/ds), not in metres or degrees,
//   which mean different things 1.8 m and 40 m above the ground. (Held instead against a
//   fresh fit, grown beyond what the refit itself cost, it let a refit's room for motion
//   stay for good: along flythrough 5 refits, but `wrong_pct` 0.86 against 0.61 unheld.)
// - motion: a refit that covers only this frame's body is outgrown within frames by a moving
//   camera; covering also the bodies on the way `lookaheadFrames` on (its last step
//   repeated, turn and all: extrapolatedCamera, camera.h) makes room for the motion, paid
//   for in texels only while it moves. The margin is paid always: a refit without it for a
//   still camera (measured) only moves the pop to the first frame the camera moves, and
//   shifts every later refit with it.
#include "shadowkit/core/setup_hysteresis.h"

#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/output_conventions.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace shadowkit::core {
namespace {

// The lookahead is covered at several cameras along the extrapolated motion, not only at its
// end: a turning camera sweeps a fan whose middle the two ends do not hold, and an end that
// has turned behind the warp's projection centre cannot be held at all — with one sample
// that lost the whole lookahead (measured on flythrough with 60 frames of lookahead, before
// the staleness rule and the cap below: 21 refits with one sample, 6 with its quarters).
// Before its quarters, 1, 2, 4, … frames on: where the first quarter is already behind the
// centre or past the cap, quarters alone left a refit no room at all, and a turntable's
// camera outgrew each refit's margin the next frame (SetupHysteresis tests, TSM: refits in
// 32 frames running, 44 once round against 16 with the nearer samples).
constexpr int kLookaheadSteps = 4;

// The frames ahead at which the lookahead is sampled, nearest first.
std::vector<double> lookaheadSamples(double lookahead) {
    std::vector<double> frames;
    for (double f = 1.0; f < lookahead / kLookaheadSteps; f *= 2.0) frames.push_back(f);
    for (int step = 1; step <= kLookaheadSteps; ++step) frames.push_back(lookahead * step / kLookaheadSteps);
    return frames;
}
// The most the lookahead's room may cost: a refit's texels on the central ray at most this many
// times a fresh fit's. A climbing or turning camera extrapolated far sees most of the terrain;
// uncapped, one refit there paid 46x in texel size (measured on flythrough at frame 85), and as
// the camera slowed, that price fell by a third a frame, so each refit looked stale against
// the next one within two frames: chains of refits (21 along flythrough with 40 frames of
// lookahead, 5 with the cap).
constexpr double kMaxLookaheadPrice = 3.0;

// Adds (tx, ty, 0) · w to clip coordinates: NDC shifted by (tx, ty).
void shiftClip(ShadowView& view, double tx, double ty) {
    for (int c = 0; c < 4; ++c) {
        view.clipFromLight[c][0] += tx * view.clipFromLight[c][3];
        view.clipFromLight[c][1] += ty * view.clipFromLight[c][3];
    }
    view.recomposeClip();
}

// Fits NDC x and y of the points to [−1, 1] shrunk by 1 + margin: x' = (x − c·w) · s per axis.
// Points with w <= 0 cannot be held by this projection and must not be passed.
void fitClip(ShadowView& view, std::span<const Vec3> wsPoints, double margin) {
    Vec2 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& p : wsPoints) {
        const Vec4 c = view.clipFromWorld * Vec4(p, 1.0);
        lo = glm::min(lo, Vec2(c) / c.w), hi = glm::max(hi, Vec2(c) / c.w);
    }
    for (int axis = 0; axis < 2; ++axis) {
        const double centre = 0.5 * (lo[axis] + hi[axis]);
        const double scale = 2.0 / (std::max(hi[axis] - lo[axis], 1e-12) * (1.0 + margin));
        for (int c = 0; c < 4; ++c)
            view.clipFromLight[c][axis] = scale * (view.clipFromLight[c][axis] - centre * view.clipFromLight[c][3]);
    }
    view.recomposeClip();
}

// A range [lo, hi] grown by the margin about its middle, never to zero width.
Vec2 widened(double lo, double hi, double margin) {
    const double middle = 0.5 * (lo + hi);
    const double half = std::max(0.5 * (hi - lo) * (1.0 + margin), 1e-9 * std::max(std::abs(middle), 1.0));
    return {middle - half, middle + half};
}

// The depth rows. Depth does not move texels, so it is refitted on its own — at a refit, or
// when the body leaves [0, 1] — and must keep every caster of the body:
// clip z' = (z − lo·w) / (hi − lo), and the linear row likewise.
void fitDepth(ShadowView& view, const ConvexBody::Points& body, double margin, bool refit) {
    double lo = INFINITY, hi = -INFINITY, linearLo = INFINITY, linearHi = -INFINITY;
    for (const Vec3& p : body) {
        const Vec4 c = view.clipFromWorld * Vec4(p, 1.0);
        lo = std::min(lo, c.z / c.w), hi = std::max(hi, c.z / c.w);
        const double linear = glm::dot(view.linearDepthFromWorld, Vec4(p, 1.0));
        linearLo = std::min(linearLo, linear), linearHi = std::max(linearHi, linear);
    }
    if (refit || lo < 0.0 || hi > 1.0) {
        const Vec2 range = widened(lo, hi, margin);
        for (int c = 0; c < 4; ++c)
            view.clipFromLight[c][2] =
                (view.clipFromLight[c][2] - range.x * view.clipFromLight[c][3]) / (range.y - range.x);
        view.recomposeClip();
    }
    if (refit || linearLo < 0.0 || linearHi > 1.0) {
        const Vec2 range = widened(linearLo, linearHi, margin);
        for (Vec4* row : {&view.linearDepthFromWorld, &view.linearDepthFromEyeRelative}) {
            row->w -= range.x;
            *row /= range.y - range.x;
        }
    }
}

// A view held since an earlier frame, its eye-relative members made relative to this frame's
// eye: composed with the camera's step since then, small wherever the world is.
ShadowView reanchored(ShadowView view, const Vec3& wsHeldEye, const Vec3& wsEye) {
    const Mat4 heldFromNow = glm::translate(Mat4(1.0), wsEye - wsHeldEye);
    view.lightFromEyeRelative = view.lightFromEyeRelative * heldFromNow;
    view.clipFromEyeRelative = view.clipFromEyeRelative * heldFromNow;
    const Vec4& row = view.linearDepthFromEyeRelative;
    view.linearDepthFromEyeRelative = Vec4(Vec3(row), row.w + glm::dot(Vec3(row), wsEye - wsHeldEye));
    return view;
}

// The held view shifted by whole texels so that it covers the body, or nothing when no shift
// can (the body is wider than the map, or reaches behind the warp's projection centre).
std::optional<ShadowView> shiftedToCover(const ShadowView& held, const ConvexBody::Points& body, int mapSize) {
    Vec2 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& p : body) {
        const Vec4 c = held.clipFromWorld * Vec4(p, 1.0);
        if (!(c.w > 0.0)) return std::nullopt;
        lo = glm::min(lo, Vec2(c) / c.w);
        hi = glm::max(hi, Vec2(c) / c.w);
    }
    const double texel = 2.0 / mapSize, edge = 1.0 + 1e-9; // a fit's own rounding still fits
    Vec2 shift(0.0); // unchanged matrices while the body fits: bit-identical frames
    for (int axis = 0; axis < 2; ++axis) {
        if (lo[axis] >= -edge && hi[axis] <= edge) continue;
        const double k = std::round(-0.5 * (lo[axis] + hi[axis]) / texel);
        shift[axis] = k * texel;
        if (lo[axis] + shift[axis] < -edge || hi[axis] + shift[axis] > edge) return std::nullopt;
    }
    ShadowView out = held;
    if (shift != Vec2(0.0)) shiftClip(out, shift.x, shift.y);
    return out;
}

// Whether every point lies in front of the view's projection centre.
bool inFront(const ShadowView& view, const ConvexBody::Points& points) {
    for (const Vec3& p : points)
        if (!((view.clipFromWorld * Vec4(p, 1.0)).w > 0.0)) return false;
    return true;
}

// The view's focus body: B of the camera limited to the view's split.
ConvexBody::Points viewBody(const ShadowSetupInputs& in, const ShadowView& view) {
    PerspectiveCamera slice = in.camera;
    if (view.split) slice.zNear = view.split->x, slice.zFar = view.split->y;
    return computeFocusBody(slice, in.light, in.wsSceneBounds).vertices();
}

// The largest ratio of held to candidate texel footprint at points of the central ray inside the
// scene, from the view's near end (where a warp puts its densest texels) out, doubling.
double texelGrowth(const ShadowSetupInputs& in, const ShadowView& held, const ShadowView& fresh) {
    const PerspectiveCamera& cam = in.camera;
    double lo = fresh.split ? fresh.split->x : cam.zNear, hi = fresh.split ? fresh.split->y : cam.zFar;
    if (in.visibleDepth && std::min(hi, in.visibleDepth->y) > std::max(lo, in.visibleDepth->x))
        lo = std::max(lo, in.visibleDepth->x), hi = std::min(hi, in.visibleDepth->y);
    const Vec3 forward = glm::normalize(cam.wsDirection);
    double worst = 0.0;
    for (double depth = lo;; depth *= 2.0) {
        const Vec3 p = cam.wsEye + std::min(depth, hi) * forward;
        if (in.wsSceneBounds.contains(p)) {
            const double now = texelFootprint(fresh, in.mapSize, in.light.wsDirection, p);
            if (std::isfinite(now))
                worst = std::max(worst, texelFootprint(held, in.mapSize, in.light.wsDirection, p) / now);
        }
        if (depth >= hi) break;
    }
    return worst;
}

// A refit: the fresh warp fitted to the body with the margin and, where the warp can hold
// them, to the bodies the camera will have on its way if it goes on as it went — as many of
// them, nearest first, as cost at most kMaxLookaheadPrice in texel size on the central ray.
ShadowView withRoomForMotion(const ShadowSetupInputs& in, const ShadowView& fresh, const ConvexBody::Points& body,
                             std::span<const ShadowSetupInputs> ahead, double margin) {
    ShadowView refit = fresh;
    fitClip(refit, body, margin);
    ConvexBody::Points cover = body;
    for (const ShadowSetupInputs& later : ahead) {
        const ConvexBody::Points laterBody = viewBody(later, fresh);
        if (!inFront(fresh, laterBody)) break;
        ConvexBody::Points wider = cover;
        for (const Vec3& p : laterBody) wider.push_back(p);
        ShadowView candidate = fresh;
        fitClip(candidate, wider, margin);
        if (texelGrowth(in, candidate, fresh) > kMaxLookaheadPrice) break;
        cover = std::move(wider), refit = candidate;
    }
    return refit;
}

// Whether a held set-up can go on: the same light, technique, map and layout, view for view.
bool compatible(const ShadowSetupInputs& was, const ShadowSetup& held, const ShadowSetupInputs& now,
                const ShadowSetup& fresh) {
    return was.light.wsDirection == now.light.wsDirection && was.technique == now.technique &&
           was.mapSize == now.mapSize && held.depthLayout == fresh.depthLayout &&
           held.views.size() == fresh.views.size();
}

} // namespace

Status validate(const HysteresisOptions& o) {
    if (!(o.margin >= 0.0 && o.margin <= 1.0)) return fieldError("hysteresis.margin", "must be a fraction in [0, 1]");
    if (!(o.lookaheadFrames >= 0.0 && o.lookaheadFrames <= 1000.0))
        return fieldError("hysteresis.lookahead", "must be in [0, 1000] frames");
    if (!(o.maxTexelGrowth > 1.0) || !std::isfinite(o.maxTexelGrowth))
        return fieldError("hysteresis.growth", "must be finite and > 1");
    return Ok{};
}

double texelFootprint(const ShadowView& view, int mapSize, const Vec3& wsLight, const Vec3& wsPoint) {
    return wsTexelSize(view.clipFromWorld, mapSize, wsLight, wsPoint);
}

Result<ShadowSetup> SetupHysteresis::next(const ShadowSetupInputs& inputs) {
    if (auto s = validate(m_options); !s) return s.errorInfo();
    Result<ShadowSetup> fresh = computeShadowSetup(inputs);
    if (!fresh) return fresh;
    const bool refitAll = !m_held || !compatible(m_held->inputs, m_held->setup, inputs, *fresh);
    // Where the camera will be `lookaheadFrames` on if it keeps this frame's motion.
    const bool moving = m_previousCamera &&
                        (m_previousCamera->wsEye != inputs.camera.wsEye ||
                         glm::normalize(m_previousCamera->wsDirection) != glm::normalize(inputs.camera.wsDirection));
    // A light that moved since the last frame will likely move again, and then every frame
    // refits anyway: room for the camera's motion would only coarsen each of them.
    const bool lightHeld = m_held && m_held->inputs.light.wsDirection == inputs.light.wsDirection;
    std::vector<ShadowSetupInputs> ahead;
    if (moving && lightHeld && m_options.lookaheadFrames > 0)
        for (const double frames : lookaheadSamples(m_options.lookaheadFrames)) {
            ShadowSetupInputs later = inputs;
            later.camera = extrapolatedCamera(*m_previousCamera, inputs.camera, frames);
            if (later.camera.validate()) ahead.push_back(later);
        }
    ShadowSetup out = *fresh; // body, fallbacks and splits of this frame
    m_refits = {};
    for (size_t i = 0; i < out.views.size(); ++i) {
        const ShadowView& now = fresh->views[i];
        // A single map's body is the set-up's own B, computed already; a split's is not kept.
        const ConvexBody::Points body =
            !now.split && !fresh->body.isEmpty() ? fresh->body.vertices() : viewBody(inputs, now);
        if (body.empty()) { // nothing of the scene to cover: nothing to hold either
            ++m_refits.views;
            continue;
        }
        std::optional<ShadowView> refit; // what a refit would give now, once asked for
        auto refitNow = [&]() -> const ShadowView& {
            if (!refit) refit = withRoomForMotion(inputs, now, body, ahead, m_options.margin);
            return *refit;
        };
        std::optional<ShadowView> kept;
        if (!refitAll) {
            kept = shiftedToCover(reanchored(m_held->setup.views[i], m_held->setup.wsEye, out.wsEye), body,
                                  inputs.mapSize);
            if (!kept) {
                ++m_refits.toCover;
            } else if (texelGrowth(inputs, *kept, refitNow()) > m_options.maxTexelGrowth) {
                kept.reset();
                ++m_refits.stale;
            }
        }
        const bool refitted = !kept;
        if (refitted) {
            kept = refitNow();
            ++m_refits.views;
        }
        fitDepth(*kept, body, m_options.margin, refitted);
        kept->split = now.split; // the shader picks the split by this frame's distances
        out.views[i] = *kept;
    }
    m_held = Held{inputs, out};
    m_previousCamera = inputs.camera;
    return out;
}

} // namespace shadowkit::core
