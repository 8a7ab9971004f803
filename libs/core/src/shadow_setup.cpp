#include "shadowkit/core/shadow_setup.h"

#include "shadowkit/core/cascades.h"
#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/lispsm.h"
#include "shadowkit/core/psm.h"
#include "shadowkit/core/tsm.h"
#include "shadowkit/core/uniform_shadow_map.h"
#include "shadowkit/core/virtual_clipmap.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace shadowkit::core {
namespace {

constexpr std::array kTechniques = {
    TechniqueInfo{Technique::Standard, "standard"}, TechniqueInfo{Technique::Focused, "focused"},
    TechniqueInfo{Technique::Psm, "psm"},           TechniqueInfo{Technique::Tsm, "tsm"},
    TechniqueInfo{Technique::Csm, "csm"},           TechniqueInfo{Technique::Lispsm, "lispsm"},
    TechniqueInfo{Technique::Virtual, "virtual"},
};

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
    case Technique::Standard:
        return computeStandardShadowMap(inputs);
    case Technique::Focused:
        return computeFocusedShadowMap(inputs);
    case Technique::Psm:
        return computePsm(inputs);
    case Technique::Csm:
        return computeCascades(inputs);
    case Technique::Tsm:
        return computeTsm(inputs);
    case Technique::Lispsm:
        return computeLispsm(inputs);
    case Technique::Virtual:
        return computeVirtualClipmap(inputs);
    }
    return makeError("technique: unknown");
}

// Linear depth: distance along the light over B (or the scene box when B is empty), the
// same for every technique since it does not depend on the warp.
void addLinearDepth(const ShadowSetupInputs& inputs, ShadowSetup& setup) {
    const Vec3 towards = inputs.light.wsTowardsLight();
    const Vec2 along = setup.body.isEmpty()
                           ? ConvexBody::fromAabb(sceneBoxForFocus(inputs.wsSceneBounds)).rangeAlong(towards)
                           : setup.body.rangeAlong(towards);
    const double lo = along.x, hi = along.y;
    const double range = std::max(hi - lo, 1e-9 * std::max(std::abs(hi), 1.0));
    for (ShadowView& view : setup.views) view.linearDepthFromWorld = Vec4(-towards / range, hi / range);
    setup.depthLayout = depthLayoutFor(inputs);
}

} // namespace

DepthLayout depthLayoutFor(const ShadowSetupInputs& inputs) {
    // A clipmap's pages are orthographic: their clip depth is linear already, and a page drawn
    // in one frame must hold what the next frame's layout expects, so it has only the one.
    if (inputs.technique == Technique::Virtual) return DepthLayout::Hyperbolic;
    return inputs.depthLayout.value_or(inputs.technique == Technique::Tsm ? DepthLayout::Linear
                                                                          : DepthLayout::Hyperbolic);
}

Status validate(const LispsmOptions& o) {
    if (!(o.weight > 0.0) || !std::isfinite(o.weight))
        return fieldError("lispsm.weight", "must be a finite number > 0");
    if (o.nOverride && !(*o.nOverride > 0.0 && std::isfinite(*o.nOverride)))
        return fieldError("lispsm.n", "must be a finite number of metres > 0");
    return Ok{};
}

Status validate(const TsmOptions& o) {
    if (!(o.focusFraction > 0.0 && o.focusFraction < 1.0))
        return fieldError("tsm.focus", "must be a fraction in (0, 1)");
    return Ok{};
}

Status validateSceneBounds(const Aabb& b) {
    if (!isFinite(b.min) || !isFinite(b.max) || b.isEmpty())
        return fieldError("scene_bounds", "must be finite with min <= max on every axis");
    return Ok{};
}

Status validateMapSize(int texels) {
    if (texels < kMinMapSize || texels > kMaxMapSize)
        return fieldError("map_size", "must be in [" + std::to_string(kMinMapSize) + ", " +
                                          std::to_string(kMaxMapSize) + "] texels, got " + std::to_string(texels));
    return Ok{};
}

Status validate(const ShadowSetupInputs& inputs) {
    if (Status s = inputs.camera.validate(); !s) return s;
    const Vec3& l = inputs.light.wsDirection;
    if (!isFinite(l) || std::abs(glm::length(l) - 1.0) > 1e-6)
        return fieldError("light_direction", "must be a finite unit vector");
    if (Status st = validateSceneBounds(inputs.wsSceneBounds); !st) return st;
    if (Status st = validateOptions(inputs); !st) return st;
    return inputs.technique == Technique::Csm ? validateCascades(inputs) : Status(Ok{});
}

Status validateOptions(const ShadowSetupInputs& inputs) {
    // Every technique's options are checked, used or not: a bad value is a mistake either way.
    if (Status s = validateMapSize(inputs.mapSize); !s) return s;
    if (Status s = validate(inputs.lispsm); !s) return s;
    if (Status s = validate(inputs.tsm); !s) return s;
    if (Status s = validate(inputs.virtualMaps); !s) return s;
    if (const auto& v = inputs.visibleDepth; v && !(v->x >= 0.0 && v->y > v->x && std::isfinite(v->y)))
        return fieldError("visible_depth", "must be [near, far] with 0 <= near < far");
    return validate(inputs.cascades);
}

Result<ShadowSetup> computeShadowSetup(const ShadowSetupInputs& inputs) {
    if (Status s = validate(inputs); !s) return s.errorInfo();
    // Large worlds: the technique runs on coordinates relative to the eye. Every technique
    // commutes with a translation, but its arithmetic does not: 90 km from the origin a
    // 1.6 cm-deep frustum's matrices, built in world coordinates, put receivers 1e-9 outside
    // the clip cube in double, and the depth of the whole light volume is a difference of
    // numbers of 1e5. Relative to the eye the inputs are of the size of the view; the world
    // matrices are then the eye-relative ones times T(−eye), composed once.
    const Vec3 wsEye = inputs.camera.wsEye;
    ShadowSetupInputs centred = inputs;
    centred.camera.wsEye = Vec3(0.0);
    centred.wsSceneBounds = Aabb::fromMinMax(inputs.wsSceneBounds.min - wsEye, inputs.wsSceneBounds.max - wsEye);
    centred.wsGridOrigin = inputs.wsGridOrigin - wsEye;
    Result<ShadowSetup> setup = runTechnique(centred);
    if (!setup) return setup;
    addLinearDepth(centred, *setup);
    if (!setup->clipmap) setup->mapSize = inputs.mapSize; // a clipmap has its own virtual size
    for (ShadowView& view : setup->views) {
        view.lightFromEyeRelative = view.lightFromWorld;
        view.clipFromEyeRelative = view.clipFromWorld;
        view.linearDepthFromEyeRelative = view.linearDepthFromWorld;
    }
    setup->wsEye = Vec3(0.0);
    rebase(*setup, -wsEye); // in place, not into a copy of the whole set-up (views, body)
    return setup;
}

void setEyeRelativeFromWorld(ShadowSetup& setup, const Vec3& wsEye) {
    const Mat4 worldFromEyeRelative = glm::translate(Mat4(1.0), wsEye);
    for (ShadowView& view : setup.views) {
        view.lightFromEyeRelative = view.lightFromWorld * worldFromEyeRelative;
        view.clipFromEyeRelative = view.clipFromWorld * worldFromEyeRelative;
        const Vec4& row = view.linearDepthFromWorld;
        view.linearDepthFromEyeRelative = Vec4(Vec3(row), row.w + glm::dot(Vec3(row), wsEye));
    }
    setup.wsEye = wsEye;
}

void rebase(ShadowSetup& setup, const Vec3& wsOrigin) {
    // q = p − wsOrigin, and p − wsEye = q − (wsEye − wsOrigin): the eye in the new coordinates.
    const Vec3 qsEye = setup.wsEye - wsOrigin;
    const Mat4 eyeRelativeFromQ = glm::translate(Mat4(1.0), -qsEye);
    for (ShadowView& view : setup.views) {
        view.lightFromWorld = view.lightFromEyeRelative * eyeRelativeFromQ;
        view.clipFromWorld = view.clipFromEyeRelative * eyeRelativeFromQ;
        const Vec4& row = view.linearDepthFromEyeRelative;
        view.linearDepthFromWorld = Vec4(Vec3(row), row.w - glm::dot(Vec3(row), qsEye));
    }
    setup.body.translate(-wsOrigin);
    if (setup.clipmap) setup.clipmap->wsGridOrigin -= wsOrigin;
    setup.wsLightPosition -= wsOrigin;
    setup.wsEye = qsEye;
}

ShadowSetup rebased(const ShadowSetup& setup, const Vec3& wsOrigin) {
    ShadowSetup out = setup;
    rebase(out, wsOrigin);
    return out;
}

} // namespace shadowkit::core
