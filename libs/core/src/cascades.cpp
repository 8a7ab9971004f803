// Cascaded shadow maps.
//
// Based on: Dimitrov, "Cascaded Shadow Maps", NVIDIA 2007: split the view
// frustum along depth (cascade_splits.cpp), give every split its own map fitted to it by a
// crop matrix, and pick the split per fragment by view depth.
// Deviations, each for robustness:
// - Each split is fitted to its own focus body B_i = (slice ∩ S) swept towards the light ∩ S
//   (focus_body.cpp), not to the slice's 8 corners: casters outside the slice but between it
//   and the sun are kept without the "maxZ += 50" patch of public ports
//   (docs/references.md, pitfall 5).
// - With a visible depth range (ShadowSetupInputs::visibleDepth), the split distances are
//   placed over [visible near, visible far] instead of [near, far], as sample-distribution
//   shadow maps do (Lauritzen, Salvi, Lefohn 2011): a forest seen from 3 m on does not
//   spend a split on the first metres. The first split still starts at the near plane and
//   the last ends at the far plane, so every fragment keeps a map that covers it even when
//   the range comes from an older frame; only where the splits fall moves.
// - Optional per-split LiSPSM (Zhang et al.'s PSSM + LiSPSM): each split is a LiSPSM set-up
//   whose z_n is the split's near distance.
// - Stabilisation (as in bgfx and Filament; docs/references.md, pitfall 8): a light frame
//   fixed in
//   the world, an extent from the split's bounding sphere (which depends on the camera's
//   fov, aspect and split distances only, so it is bit-identical under rotation and
//   translation), and the centre snapped to whole texels.
#include "shadowkit/core/cascades.h"

#include "shadowkit/core/cascade_splits.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/light_frame.h"
#include "shadowkit/core/lispsm.h"
#include "shadowkit/core/uniform_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace shadowkit::core {
namespace {

// The split's bounding sphere: centre on the view axis at `centreDepth`, `radius`.
struct SliceSphere {
    double centreDepth, radius;
};

SliceSphere boundingSphere(const PerspectiveCamera& cam, double n, double f) {
    const double ty = std::tan(0.5 * glm::radians(cam.fovYDegrees));
    const double k2 = ty * ty * (1.0 + cam.aspect * cam.aspect); // (corner offset / depth)²
    // Equidistant from the near and far corner rings: (c − n)² + n²k² = (f − c)² + f²k².
    const double c = std::min(0.5 * (f + n) * (1.0 + k2), f);
    const double r = std::max(std::sqrt((c - n) * (c - n) + n * n * k2), std::sqrt((f - c) * (f - c) + f * f * k2));
    return {c, r};
}

ShadowView stableView(const ShadowSetupInputs& in, const PerspectiveCamera& slice, const ConvexBody& body) {
    // World-fixed frame (origin at the grid origin, by default the world's; north up):
    // independent of the view, so the texel lattice stays where it is as the camera moves.
    const LightFrame frame = makeLightFrame(in.light.wsDirection, in.wsGridOrigin, {Vec3(0, 0, -1)});
    const SliceSphere sphere = boundingSphere(slice, slice.zNear, slice.zFar);
    const Vec3 wsCentre = slice.wsEye + sphere.centreDepth * glm::normalize(slice.wsDirection);
    const Vec3 lsCentre(frame.lightFromWorld * Vec4(wsCentre, 1.0));
    // The map spans 2·half with one texel of margin on each side of the sphere; snapping the
    // centre to multiples of that texel puts the map's edges (cx ± half, half = mapSize/2
    // texels) on one fixed world grid, whatever the camera does.
    const int mapSize = in.mapSize;
    const double half = sphere.radius * mapSize / (mapSize - 2);
    const double texel = 2.0 * half / mapSize;
    const double cx = std::floor(lsCentre.x / texel) * texel, cy = std::floor(lsCentre.y / texel) * texel;

    // Depth from the split's body (all of its casters), or the sphere when it is empty.
    double zMin = lsCentre.z - sphere.radius, zMax = lsCentre.z + sphere.radius;
    if (!body.isEmpty()) {
        zMin = INFINITY, zMax = -INFINITY;
        for (const Vec3& p : body.vertices()) {
            const double z = (frame.lightFromWorld * Vec4(p, 1.0)).z;
            zMin = std::min(zMin, z);
            zMax = std::max(zMax, z);
        }
        if (!(zMax > zMin)) zMax = zMin + 1e-6;
    }
    ShadowView view;
    view.lightFromWorld = frame.lightFromWorld;
    // Snapping moves the centre by under a texel, which the margin absorbs.
    view.clipFromLight = orthoZeroToOne(cx - half, cx + half, cy - half, cy + half, -zMax, -zMin);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    return view;
}

} // namespace

Status validate(const CascadeOptions& o) {
    if (o.count < 1 || o.count > kMaxCascadeCount)
        return fieldError("cascades.count",
                          "must be in [1, " + std::to_string(kMaxCascadeCount) + "], got " + std::to_string(o.count));
    if (!(o.lambda >= 0.0 && o.lambda <= 1.0)) return fieldError("cascades.lambda", "must be in [0, 1]");
    if (!(o.blendBand >= 0.0 && o.blendBand <= 0.5)) return fieldError("cascades.blend_band", "must be in [0, 0.5]");
    if (o.stabilize && o.warp != CascadeWarp::None)
        return fieldError("cascades.stabilize",
                          "stabilisation by snapping cannot take a per-split warp (a warp's texels differ in "
                          "size, no shift resamples them): hold its lattices with SetupHysteresis instead");
    return Ok{};
}

Status validateCascades(const ShadowSetupInputs& in) {
    const CascadeOptions& o = in.cascades;
    if (o.stabilize && in.mapSize % 2 != 0)
        return fieldError("cascades.stabilize",
                          "stabilisation needs an even map size (the map's edges must fall on the texel grid)");
    if (!o.splits.empty()) {
        if (o.splits.size() != static_cast<size_t>(o.count) + 1)
            return fieldError("cascades.splits",
                              "explicit splits need count + 1 = " + std::to_string(o.count + 1) + " distances");
        const double tolerance = 1e-9 * in.camera.zFar;
        if (std::abs(o.splits.front() - in.camera.zNear) > tolerance ||
            std::abs(o.splits.back() - in.camera.zFar) > tolerance)
            return fieldError("cascades.splits",
                              "explicit splits must start at the near plane and end at the far plane");
        for (size_t i = 1; i < o.splits.size(); ++i)
            if (!(o.splits[i] > o.splits[i - 1])) return fieldError("cascades.splits", "explicit splits must increase");
    }
    return Ok{};
}

ShadowSetup computeCascades(const ShadowSetupInputs& in) {
    const CascadeOptions& o = in.cascades;
    ShadowSetup setup;
    setup.technique = Technique::Csm;
    // V ∩ S once: each split's is the same body cut by the split's near and far planes.
    const ConvexBody visible = visibleSceneBody(in.camera, in.wsSceneBounds);
    const Vec3 wsTowardsLight = in.light.wsTowardsLight();
    setup.body = focusBodyFromVisible(visible, wsTowardsLight, in.wsSceneBounds);
    SplitDistances z;
    if (o.splits.empty()) {
        double zNear = in.camera.zNear, zFar = in.camera.zFar;
        if (in.visibleDepth) {
            const double visibleNear = std::max(zNear, in.visibleDepth->x),
                         visibleFar = std::min(zFar, in.visibleDepth->y);
            if (visibleFar > visibleNear) zNear = visibleNear, zFar = visibleFar;
        }
        z = practicalSplits(zNear, zFar, o.count, o.lambda);
    } else
        for (const double d : o.splits) z.push_back(d);
    z.front() = in.camera.zNear; // exact ends, whatever rounding the caller's list carries
    z.back() = in.camera.zFar;

    const Vec3 forward = glm::normalize(in.camera.wsDirection);
    for (int i = 0; i < o.count; ++i) {
        const size_t k = static_cast<size_t>(i);
        const double start = i == 0 ? z[0] : z[k] - o.blendBand * (z[k] - z[k - 1]);
        ShadowSetupInputs slice = in;
        slice.camera.zNear = start;
        slice.camera.zFar = z[k + 1];
        slice.technique = o.warp == CascadeWarp::Lispsm ? Technique::Lispsm : Technique::Focused;

        ConvexBody visibleSlice = visible;
        visibleSlice.clip(Plane::fromPointNormal(in.camera.wsEye + start * forward, -forward));
        visibleSlice.clip(Plane::fromPointNormal(in.camera.wsEye + z[k + 1] * forward, forward));
        const ConvexBody body = focusBodyFromVisible(visibleSlice, wsTowardsLight, in.wsSceneBounds);

        ShadowView view;
        if (o.stabilize) {
            view = stableView(in, slice.camera, body);
        } else {
            // The slice's technique itself, not computeShadowSetup: these inputs are validated and
            // already relative to the eye (computeShadowSetup's work), and the depth rows are
            // the whole set-up's (addLinearDepth), so only the split's view is wanted.
            const ShadowSetup sub =
                o.warp == CascadeWarp::Lispsm ? computeLispsm(slice, body) : computeFocusedShadowMap(slice, body);
            view = sub.views[0];
            for (const std::string& f : sub.fallbacks)
                setup.fallbacks.push_back("cascade " + std::to_string(i) + ": " + f);
        }
        view.split = Vec2(start, z[k + 1]);
        setup.views.push_back(view);
    }
    return setup;
}

} // namespace shadowkit::core
