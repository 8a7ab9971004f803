// The technique and render option groups (options.h) — which set-up, its warps, cascades and
// virtual pages; bias, filter, blur, culling and the debug views — and the parsers and error
// spelling every group shares. The scene and view groups: scene_options.cpp.
#include "options.h"

#include "common.h"

#include "shadowkit/core/light_size.h"
#include "shadowkit/frame/frame_config.h"
#include "shadowkit/frame/option_table.h"

#include <fmt/format.h>

#include <cmath>
#include <sstream>
#include <string_view>
#include <vector>

namespace shadowkit::app {

bool parseNumbers(const std::string& text, char separator, std::vector<double>& out) {
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, separator)) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) return false;
        out.push_back(v);
    }
    return !text.empty() && text.back() != separator;
}

core::Result<core::Vec3> parseVec3(const std::string& flag, const std::string& text) {
    std::vector<double> v;
    if (!parseNumbers(text, ',', v) || v.size() != 3)
        return core::makeError(fmt::format("{}: expected three comma-separated numbers x,y,z, got '{}'", flag, text));
    return core::Vec3(v[0], v[1], v[2]);
}

namespace {

Choices<core::Technique> techniqueChoices() {
    Choices<core::Technique> choices;
    for (const core::TechniqueInfo& info : core::allTechniques()) choices.emplace_back(info.name, info.technique);
    return choices;
}

} // namespace

std::vector<std::string> choicesOf(CLI::App& cmd, const std::string& flag) {
    CLI::Option* option = cmd.get_option_no_throw(flag);
    if (!option) return {};
    try {
        std::vector<std::string> names;
        std::stringstream list(option->get_validator(kChoicesValidator)->get_description());
        for (std::string name; std::getline(list, name, '|');) names.push_back(name);
        return names;
    } catch (const CLI::OptionNotFound&) {
        return {}; // not an enumerated option
    }
}

std::string defaultOf(CLI::App& cmd, const std::string& flag) {
    const CLI::Option* option = cmd.get_option_no_throw(flag);
    return option ? option->get_default_str() : std::string();
}

core::Error withFlagName(const core::Error& error) {
    // The flag of the field from the one table of options (frame/option_table.h).
    const frame::OptionRow* row = frame::optionForField(error.field);
    if (!row) return error;
    const std::string prefix = error.field + ": ";
    const bool prefixed = error.message.compare(0, prefix.size(), prefix) == 0;
    return core::Error{std::string(row->flag) + ": " + (prefixed ? error.message.substr(prefix.size()) : error.message),
                       error.field, error.kind};
}

void RenderOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--bias-slope", biasSlope,
                   "slope-scaled depth bias (glPolygonOffset factor; default: per technique)");
    cmd.add_option("--bias-constant", biasConstant,
                   "constant depth bias (glPolygonOffset units; default: per technique)");
    cmd.add_option("--cull", cull,
                   "caster faces left out of the map (closed: back faces of closed meshes, the same map as none's "
                   "at half the samples; front: back-side rendering; auto: per technique)")
        ->transform(choice(Choices<CullChoice>{{"auto", CullChoice::Auto},
                                               {"closed", CullChoice::Closed},
                                               {"back", CullChoice::Back},
                                               {"front", CullChoice::Front},
                                               {"none", CullChoice::None}}))
        ->default_str("auto");
    cmd.add_option("--normal-offset", normalOffset, "receiver offset along its normal, in texels' world size");
    cmd.add_option("--normal-offset-footprint", normalOffsetFootprint,
                   "receiver offset along its normal besides, × its texel's footprint on the normal (0 for a face "
                   "turned to the sun; 0.5 clears its own plane)");
    cmd.add_option(
        "--fog", fog,
        "fog density in 1/m, 0 for none (default: the scene's, 0.002 for the forest, scaled to a loaded scene's size)");
    cmd.add_option("--receiver-plane-bias", receiverPlaneBias,
                   "reference depth on the receiver's plane (auto: for wide kernels)")
        ->transform(choice(Choices<Choice>{{"auto", Choice::Auto}, {"on", Choice::On}, {"off", Choice::Off}}))
        ->capture_default_str();
    cmd.add_option("--offset-guard", offsetGuard,
                   "with a normal offset, a receiver the light grazes, behind another caster in its own texel, stays "
                   "shadowed where the offset moved its lookup (hard and pcf2; auto: the recommended bias's, on where "
                   "it offsets)")
        ->transform(choice(Choices<Choice>{{"auto", Choice::Auto}, {"on", Choice::On}, {"off", Choice::Off}}))
        ->capture_default_str();
    cmd.add_option("--filter", filter,
                   "hard, pcf2 (hardware 2x2), pcf:N (N x N, 1-9), poisson:N (N rotated taps, 1-32), pcss[:N] (soft "
                   "shadows of a --sun-angle sun: blocker search and filter of N taps each, default 16)")
        ->capture_default_str();
    cmd.add_option("--sun-angle", sunAngle,
                   "the sun's angular diameter in degrees, [0, 20] (the real sun: 0.53): the penumbrae --filter pcss "
                   "draws, and eval's soft truth (soft_mae, penumbra_mae, soft_wrong_pct); 0: a point, hard shadows "
                   "and the hard truth alone")
        ->capture_default_str();
    cmd.add_flag("--foliage-opacity", foliageOpacity,
                 "alpha-tested casters (leaves) cast a fraction of the light through opacity layers beside the sun's "
                 "maps or virtual pages, the opaque casters through their depth");
    cmd.add_option("--blur-iterations", blur.iterations, "eye-space blur of the shadow mask: 0, 1, 2, 4, 8, 16 ...")
        ->capture_default_str();
    cmd.add_option("--blur-radius", blur.radiusPixels, "blur tap distance in pixels at the viewer")
        ->capture_default_str();
    cmd.add_option("--blur-depth-threshold", blur.depthThreshold,
                   "blur: neighbours whose view depth differs by more than this fraction are left out")
        ->capture_default_str();
    cmd.add_option("--blur-depth-falloff", blur.depthFalloff, "blur radius / (1 + falloff * depth): 0 = uniform blur")
        ->capture_default_str();
    cmd.add_flag("--cascade-colors", cascadeColors, "tint each cascade's depth range (Dimitrov 2007 Figure 3-2)");
    cmd.add_flag(
        "--aliasing-overlay", aliasingOverlay,
        "show pixels per texel of the sun's map instead of shading, computed per pixel in the shader (eval's colours)");
    cmd.add_option("--visibility", visibility,
                   "instances the camera pass draws: off (all, every pass), frustum, chc (CHC++ occlusion queries), "
                   "gpu (frustum, two-phase depth-pyramid occlusion and receiver masks in compute passes writing "
                   "indirect draws: the camera's and the sun's lists never reach the CPU), auto (gpu on a GPU, chc "
                   "on a software rasteriser such as llvmpipe, whose compute passes share the CPU's cores)")
        ->transform(choice(Choices<gl::Culling>{{"off", gl::Culling::Off},
                                                {"frustum", gl::Culling::Frustum},
                                                {"chc", gl::Culling::Occlusion},
                                                {"gpu", gl::Culling::Gpu},
                                                {"auto", gl::Culling::Auto}}))
        ->default_str("auto");
    cmd.add_option("--caster-culling", receiverMask,
                   "casters each shadow map draws: volume (its clip volume), receivers (also only those that can "
                   "shadow a pixel the camera sees; a camera depth pre-pass)")
        ->transform(choice(Choices<bool>{{"volume", false}, {"receivers", true}}))
        ->default_str("receivers");
    cmd.add_flag("--no-cull", noCull,
                 "same as --visibility off: every instance in every pass (same pixels, more work)");
    cmd.add_flag("--no-lod", noLod, "draw full meshes in every pass (no levels of detail)");
    cmd.add_option("--lod-pixel-error", lodPixelError,
                   "levels of detail: the coarsest level whose error stays within this many pixels of the camera")
        ->capture_default_str();
    cmd.add_option("--lod-texel-error", lodTexelError,
                   "levels of detail: within this many texels of each shadow map (and the camera's bound near it)")
        ->capture_default_str();
    cmd.add_option("--lod-foliage-scale", lodFoliageScale,
                   "levels of detail that keep coverage (leaf cards, billboard clouds) may err this many times the "
                   "pixel and texel bounds; 1: as every other mesh")
        ->capture_default_str();
    cmd.add_option("--lod-fade", lodFade,
                   "levels of detail that keep coverage are crossed into over this fraction of their bound, both "
                   "levels drawn in a dither; 0: they switch at the bound")
        ->capture_default_str();
}

std::string cullingSaid(gl::Culling requested, std::string_view glRenderer) {
    const gl::Culling drawn = gl::resolveCulling(requested, glRenderer);
    if (requested != gl::Culling::Auto) return gl::cullingName(drawn);
    return fmt::format("{} (auto: {} is a {} rasteriser)", gl::cullingName(drawn), glRenderer,
                       gl::isSoftwareRasteriser(glRenderer) ? "software" : "GPU");
}

core::Status RenderOptions::check() const {
    if (auto f = core::parseFilter(filter); !f) return withFlagName(f.errorInfo());
    if (auto s = core::validateSunAngle(sunAngle); !s) return withFlagName(s.errorInfo());
    if (auto s = gl::validate(blur); !s) return withFlagName(s.errorInfo());
    if (auto s = frame::validateFog(fog); !s) return withFlagName(s.errorInfo());
    if (auto s = gl::validateLevelsOfDetail(lodPixelError, lodTexelError, lodFoliageScale, lodFade); !s)
        return withFlagName(s.errorInfo());
    const frame::BiasOverrides overrides{.slope = biasSlope,
                                         .constant = biasConstant,
                                         .normalOffset = normalOffset,
                                         .normalOffsetFootprint = normalOffsetFootprint};
    if (auto s = overrides.validate(); !s) return withFlagName(s.errorInfo());
    return core::Ok{};
}

void TechniqueOptions::addTo(CLI::App& cmd) {
    // "auto" stands for the default technique until a frame is resolved (the raw text is seen first).
    Choices<core::Technique> techniques = techniqueChoices();
    techniques.emplace_back("auto", core::defaultTechnique());
    cmd.add_option("--technique", technique,
                   "shadow technique; auto: the family and its parameters chosen per frame from the predicted "
                   "sampling error at the receivers in view, within --texel-budget")
        ->transform(choice(techniques))
        // CLI11 runs a transform added later first: this one sees the text as given.
        ->transform(CLI::Validator(
            [this](std::string& text) {
                automatic = text == "auto";
                return std::string();
            },
            ""))
        ->default_str(std::string(core::techniqueName(technique)));
    cmd.add_option("--texel-budget", texelBudget,
                   "--technique auto: texels of all maps together, e.g. 4M = 1 x 2048² or 4 x 1024² (default: one "
                   "--map-size map)");
    cmd.add_option("--lispsm-formula", lispsmFormula,
                   "LiSPSM n: Wimmer et al. 2004 §4.4 (paper) or Scherzer 2005 eq. 1")
        ->transform(choice(Choices<core::LispsmFormula>{{"paper", core::LispsmFormula::Paper},
                                                        {"scherzer", core::LispsmFormula::Scherzer}}))
        ->default_str("scherzer");
    cmd.add_option("--lispsm-direction", lispsmDirection,
                   "LiSPSM warp axis: cross (Scherzer 2005 eq. 3) or middle (B's middle vector)")
        ->transform(choice(Choices<core::LispsmDirection>{{"cross", core::LispsmDirection::CrossProduct},
                                                          {"middle", core::LispsmDirection::MiddleVector}}))
        ->default_str("cross");
    cmd.add_option("--lispsm-weight", lispsmWeight, "LiSPSM: multiplies n (> 1 warps less)")->capture_default_str();
    cmd.add_option("--lispsm-n", lispsmN, "LiSPSM: fixed n in metres instead of the formula");
    cmd.add_option("--visible-depth", visibleDepth,
                   "near,far view depth actually visible, or 'auto' to measure it from the frame: LiSPSM's n "
                   "(Scherzer 2005 §4.4) and csm's split distances, never the focus body");
    cmd.add_flag("--lispsm-visible-near", lispsmVisibleNear,
                 "LiSPSM with --visible-depth: take z_n from the visible near distance too, not only Δz from the far");
    cmd.add_option("--tsm-focus", tsmFocus, "TSM: focus point as a fraction of the view depth range (80 % rule)")
        ->capture_default_str();
    cmd.add_option("--depth-layout", depthLayout, "shadow depth (auto: linear for TSM, else hyperbolic)")
        ->transform(choice(Choices<LayoutChoice>{
            {"auto", LayoutChoice::Auto}, {"hyperbolic", LayoutChoice::Hyperbolic}, {"linear", LayoutChoice::Linear}}))
        ->default_str("auto");
    cmd.add_option("--map-size", mapSize, "shadow map texels per side (per cascade for csm)")->capture_default_str();
    cmd.add_option("--cascades", cascades.count,
                   "csm: number of splits, 1-8; with --technique auto: that many maps (1: a single map)")
        ->each([this](const std::string&) { cascadesGiven = true; })
        ->capture_default_str();
    cmd.add_option("--lambda", cascades.lambda, "csm: split scheme, 0 uniform ... 1 logarithmic (Zhang et al. 2006)")
        ->capture_default_str();
    cmd.add_option("--splits", splits, "csm: explicit split distances near,...,far (count + 1 values)");
    cmd.add_option("--cascade-warp", cascades.warp, "csm: per-split warp")
        ->transform(choice(
            Choices<core::CascadeWarp>{{"none", core::CascadeWarp::None}, {"lispsm", core::CascadeWarp::Lispsm}}))
        ->default_str("none");
    cmd.add_flag(
        "--stabilize", cascades.stabilize,
        "csm: rotation-invariant, texel-snapped splits (no swimming); other techniques and warped cascades: held "
        "texel lattices (each map's warp kept fixed in the world and shifted by whole texels until it no longer "
        "covers the view or its texels have grown by --stabilize-growth)");
    cmd.add_option("--virtual-texels", virtualMaps.virtualTexels,
                   "virtual: texels per side of each clipmap level's virtual map")
        ->capture_default_str();
    cmd.add_option("--virtual-page-texels", virtualMaps.pageTexels, "virtual: texels per side of a page")
        ->capture_default_str();
    cmd.add_option("--virtual-first-level", virtualMaps.firstLevel,
                   "virtual: exponent e of the finest level, whose texels are 2^e metres (default: a pixel's "
                   "footprint at the nearest visible depth)");
    cmd.add_option("--virtual-lod-bias", virtualMaps.lodBias,
                   "virtual: levels added to the level rule (+1 halves the resolution everywhere)")
        ->capture_default_str();
    cmd.add_option("--virtual-blend-band", virtualBlendBand,
                   "virtual: the last fraction of each level's footprints faded into the next coarser level, [0, 1)")
        ->capture_default_str();
    cmd.add_option("--virtual-pool-pages", virtualPoolPages,
                   "virtual: pages in the physical pool (0: as many as fit 64 MiB of depth)")
        ->capture_default_str();
    cmd.add_option("--virtual-page-budget", virtualPageBudget,
                   "virtual: at most N pages drawn a frame (0: all requested); a moving sun's new pages are drawn a "
                   "level at a time while the earlier sun's keep serving")
        ->capture_default_str();
    cmd.add_option("--virtual-requests", virtualRequestsLate,
                   "virtual: wait for each frame's page requests (exact at once, a stall a frame on a GPU), or read "
                   "them late as the GPU returns them (pages first needed served coarser for a frame or two)")
        ->transform(choice(Choices<bool>{{"wait", false}, {"late", true}}))
        ->default_str(virtualRequestsLate ? "late" : "wait");
    cmd.add_option("--stabilize-margin", hysteresis.margin,
                   "--stabilize with held lattices: spare room round the view at a refit, a fraction of the map")
        ->capture_default_str();
    cmd.add_option(
           "--stabilize-growth", hysteresis.maxTexelGrowth,
           "--stabilize with held lattices: refit when a texel on the central ray is this many times a fresh fit's")
        ->capture_default_str();
    cmd.add_option("--stabilize-lookahead", hysteresis.lookaheadFrames,
                   "--stabilize with held lattices: a refit also covers where the camera will be on its way this many "
                   "frames on (as far as that costs at most 3x a fresh fit's texels)")
        ->capture_default_str();
    cmd.add_option("--blend-band", cascades.blendBand, "csm: fraction of each split blended into the next, 0-0.5")
        ->capture_default_str();
}

core::Status TechniqueOptions::check(bool measuresFrames, bool takesAuto) const {
    if (!measuresFrames && visibleDepthFromFrame())
        return core::makeError("--visible-depth: 'auto' measures a rendered frame, so give near,far here "
                               "(render, eval and compare take auto)");
    auto in = inputsFor(scene::ResolvedView{}, core::Aabb::fromMinMax(core::Vec3(0.0), core::Vec3(1.0)));
    if (!in) return in.errorInfo();
    if (!automatic && !texelBudget.empty()) return core::makeError("--texel-budget: only with --technique auto");
    if (automatic) {
        if (!takesAuto)
            return core::makeError(
                "--technique auto: chooses from a rendered frame's receivers, so render and eval take it "
                "(analyze --candidates lists what it weighs)");
        if (auto a = autoOptions(); !a) return a.errorInfo();
    }
    // The camera-independent checks only: the view is not resolved yet.
    if (auto s = core::validateOptions(*in); !s) return withFlagName(s.errorInfo());
    if (auto s = core::validate(hysteresis); !s) return withFlagName(s.errorInfo());
    gl::RenderSettings pages;
    pages.virtualPoolPages = virtualPoolPages;
    pages.virtualBlendBand = virtualBlendBand;
    pages.virtualPageBudget = virtualPageBudget;
    if (auto s = gl::validateVirtualSettings(pages); !s) return withFlagName(s.errorInfo());
    return core::Ok{};
}

core::Result<core::AutoOptions> TechniqueOptions::autoOptions() const {
    core::AutoOptions options;
    options.cascades = cascadesGiven ? cascades.count : 0;
    options.texelBudget = int64_t(mapSize) * mapSize;
    if (!texelBudget.empty()) {
        const char suffix = texelBudget.back();
        const int64_t unit = suffix == 'K' || suffix == 'k'   ? int64_t(1) << 10
                             : suffix == 'M' || suffix == 'm' ? int64_t(1) << 20
                                                              : 1;
        const std::string digits = unit == 1 ? texelBudget : texelBudget.substr(0, texelBudget.size() - 1);
        double value = 0.0;
        size_t used = 0;
        try {
            value = std::stod(digits, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != digits.size() || digits.empty() || !(value > 0.0 && value * double(unit) < 1e15))
            return core::makeError(fmt::format(
                "--texel-budget: expected a number of texels such as 4M or 16777216, got '{}'", texelBudget));
        options.texelBudget = static_cast<int64_t>(value * double(unit));
    }
    // With held lattices a change of family is a refit, a pop on screen like any other: it is
    // made only for a candidate as much better as a refit must be (texels grown past
    // --stabilize-growth G): an objective below 1 / G of the held choice's.
    if (holdsLattices()) options.hysteresis = 1.0 - 1.0 / hysteresis.maxTexelGrowth;
    if (auto s = core::validate(options); !s) return withFlagName(s.errorInfo());
    return options;
}

core::Result<core::ShadowSetupInputs> TechniqueOptions::inputsFor(const scene::ResolvedView& view,
                                                                  const core::Aabb& wsBounds) const {
    core::ShadowSetupInputs in{
        .camera = view.camera, .light = view.light, .wsSceneBounds = wsBounds, .technique = technique};
    in.mapSize = mapSize;
    in.lispsm.formula = lispsmFormula;
    in.lispsm.direction = lispsmDirection;
    in.lispsm.weight = lispsmWeight;
    in.lispsm.nOverride = lispsmN;
    in.lispsm.visibleNear = lispsmVisibleNear;
    in.tsm.focusFraction = tsmFocus;
    if (depthLayout != LayoutChoice::Auto)
        in.depthLayout =
            depthLayout == LayoutChoice::Linear ? core::DepthLayout::Linear : core::DepthLayout::Hyperbolic;
    in.cascades = cascades;
    in.virtualMaps = virtualMaps;
    if (view.height > 0) in.virtualMaps.imageHeight = view.height; // a pixel's footprint: the level rule
    if (holdsLattices()) in.cascades.stabilize = false;            // held by core::SetupHysteresis, not snapped
    if (!splits.empty() && !parseNumbers(splits, ',', in.cascades.splits))
        return core::makeError(fmt::format("--splits: expected comma-separated distances, got '{}'", splits));
    if (!visibleDepth.empty() && !visibleDepthFromFrame()) {
        std::vector<double> v;
        if (!parseNumbers(visibleDepth, ',', v) || v.size() != 2)
            return core::makeError(fmt::format("--visible-depth: expected near,far or auto, got '{}'", visibleDepth));
        in.visibleDepth = core::Vec2(v[0], v[1]);
    }
    return in;
}

} // namespace shadowkit::app
