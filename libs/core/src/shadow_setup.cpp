#include "shadowkit/core/shadow_setup.h"

#include "shadowkit/core/cascades.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/lispsm.h"
#include "shadowkit/core/psm.h"
#include "shadowkit/core/tsm.h"
#include "shadowkit/core/uniform_shadow_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace shadowkit::core {
namespace {

constexpr std::array kTechniques = {
    TechniqueInfo{Technique::Standard, "standard", "orthographic map of the whole scene box (view independent)"},
    TechniqueInfo{Technique::Focused, "focused", "uniform map fitted to the focus body B (view frustum ∩ scene, swept to the light)"},
    TechniqueInfo{Technique::Psm, "psm", "perspective shadow map: taken in the camera's post-perspective space"},
    TechniqueInfo{Technique::Tsm, "tsm", "trapezoidal shadow map: a trapezoid around the view mapped to the square"},
    TechniqueInfo{Technique::Csm, "csm", "cascaded shadow maps: one map per depth split of the view"},
    TechniqueInfo{Technique::Lispsm, "lispsm", "light space perspective shadow map: B warped along the view, n from seed 000/001"},
};

bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

} // namespace

std::span<const TechniqueInfo> allTechniques() { return kTechniques; }

std::string_view techniqueName(Technique technique) {
    for (const TechniqueInfo& info : kTechniques)
        if (info.technique == technique) return info.name;
    SK_ASSERT(false, "techniqueName(): technique missing from kTechniques");
    return {};
}

std::optional<Technique> parseTechnique(std::string_view name) {
    for (const TechniqueInfo& info : kTechniques)
        if (info.name == name) return info.technique;
    return std::nullopt;
}

std::string techniqueNameList() {
    std::string list;
    for (const TechniqueInfo& info : kTechniques) {
        if (!list.empty()) list += ", ";
        list += info.name;
    }
    return list;
}

namespace {

Result<ShadowSetup> runTechnique(const ShadowSetupInputs& inputs) {
    switch (inputs.technique) {
    case Technique::Standard: return computeStandardShadowMap(inputs);
    case Technique::Focused: return computeFocusedShadowMap(inputs);
    case Technique::Psm: return computePsm(inputs);
    case Technique::Csm: {
        if (Status s = validateCascades(inputs); !s) return makeError(s.error());
        return computeCascades(inputs);
    }
    case Technique::Tsm:
        if (!(inputs.tsm.focusFraction > 0.0 && inputs.tsm.focusFraction < 1.0))
            return makeError("tsm focus: must be a fraction in (0, 1)");
        return computeTsm(inputs);
    case Technique::Lispsm: {
        const LispsmOptions& o = inputs.lispsm;
        if (!(o.weight > 0.0) || !std::isfinite(o.weight)) return makeError("lispsm weight: must be a finite number > 0");
        if (o.nOverride && !(*o.nOverride > 0.0 && std::isfinite(*o.nOverride)))
            return makeError("lispsm n: must be a finite number of metres > 0");
        if (o.visibleDepth && !(o.visibleDepth->x >= 0.0 && o.visibleDepth->y > o.visibleDepth->x))
            return makeError("visible depth: must be [near, far] with 0 <= near < far");
        return computeLispsm(inputs);
    }
    }
    return makeError("technique: unknown");
}

// Linear depth: distance along the light over B (or the scene box when B is empty), the
// same for every technique since it does not depend on the warp.
void addLinearDepth(const ShadowSetupInputs& inputs, ShadowSetup& setup) {
    const Vec3 towards = inputs.light.wsTowardsLight();
    std::vector<Vec3> points = setup.body.vertices();
    if (points.empty()) {
        const auto corners = sceneBoxForFocus(inputs.wsSceneBounds).corners();
        points.assign(corners.begin(), corners.end());
    }
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& p : points) {
        lo = std::min(lo, glm::dot(p, towards));
        hi = std::max(hi, glm::dot(p, towards));
    }
    const double range = std::max(hi - lo, 1e-9 * std::max(std::abs(hi), 1.0));
    for (ShadowView& view : setup.views) view.linearDepthFromWorld = Vec4(-towards / range, hi / range);
    setup.depthLayout = inputs.depthLayout.value_or(inputs.technique == Technique::Tsm ? DepthLayout::Linear
                                                                                        : DepthLayout::Hyperbolic);
}

} // namespace

Result<ShadowSetup> computeShadowSetup(const ShadowSetupInputs& inputs) {
    if (Status s = inputs.camera.validate(); !s) return makeError(s.error());
    const Vec3& l = inputs.light.wsDirection;
    if (!isFinite(l) || std::abs(glm::length(l) - 1.0) > 1e-6)
        return makeError("light direction: must be a finite unit vector");
    const Aabb& s = inputs.wsSceneBounds;
    if (!isFinite(s.min) || !isFinite(s.max) || s.isEmpty())
        return makeError("scene bounds: must be finite with min <= max on every axis");

    Result<ShadowSetup> setup = runTechnique(inputs);
    if (setup) addLinearDepth(inputs, *setup);
    return setup;
}

} // namespace shadowkit::core
