// Error-driven shadow parameters: each family's free parameters, and the family itself within
// a texel budget, chosen per frame by the sampling error they are predicted to give at the
// receivers the camera sees (sampling_error.h).
//
// The seeds say where the optimum lies only for ideal cases: LiSPSM's n_opt balances the error
// between the near and far planes of a view perpendicular to the light with receivers all over
// the frustum (Wimmer et al. 2004 §4.3); at other angles §4.4 falls back to a heuristic, and
// Scherzer 2005 §4.4 narrows Δz to what is visible because the receivers are not everywhere.
// TSM's 80 % line (Martin & Tan 2004) and the cascades' λ (Zhang et al. 2006; Dimitrov 2007)
// are constants tuned on typical views. Here each candidate is simply predicted at this frame's
// receivers and a bounded search keeps the best: a grid over the parameter's range (the
// objective need not be unimodal: it has a kink where the worst receiver changes), then golden
// section between the best grid point's neighbours.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/core/sampling_error.h"
#include "shadowkit/core/shadow_setup.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::core {

/// A technique's inputs with optimised parameters, and their predicted figures.
struct ParameterChoice {
    ShadowSetupInputs inputs;                                   ///< the technique, map size and parameters chosen
    SamplingFigures predicted;                                  ///< at the model's samples
    double objective = std::numeric_limits<double>::infinity(); ///< samplingObjective(predicted)
    int setupsTried = 0;                                        ///< set-ups computed to find it
};

/// "lispsm (n x 0.42, middle vector)", "csm 4 x 1024² (lambda 0.71, per-split lispsm)": the
/// family and what was chosen, for front ends to print.
std::string describe(const ParameterChoice& choice);

/// The best parameters of inputs.technique for the model's samples, searched over
///   lispsm: the weight on n, 2^-4 … 2^4 (from nearly PSM to nearly uniform), both warp axes;
///   tsm:    the focus fraction, 0.02 … 0.9;
///   csm:    λ, 0 … 1, with the split distances placed over the samples' view depths
///           (ShadowSetupInputs::visibleDepth, as sample-distribution shadow maps do);
/// the count, warp and map size as given. `standard`, `focused` and `psm` have no free
/// parameter here and are returned as given. The inputs as given are always a candidate, so the
/// result is never worse than them on these samples. Fails only when the inputs are invalid.
Result<ParameterChoice> optimiseParameters(const ShadowSetupInputs& inputs, const SamplingErrorModel& model);

/// A family's free parameter as the search sees it: x over [lo, hi], read from and written into
/// a set-up's inputs (LiSPSM: x = log2 of the weight on n; TSM: the focus fraction; cascades: λ).
struct ParameterAxis {
    double lo = 0.0;                                   ///< the lowest x searched
    double hi = 1.0;                                   ///< the highest
    double (*get)(const ShadowSetupInputs&) = nullptr; ///< x of these inputs
    void (*set)(ShadowSetupInputs&, double) = nullptr; ///< writes x into these inputs
};
/// nullopt for the families without one here (standard, focused, psm).
std::optional<ParameterAxis> parameterAxis(Technique technique);

/// Cascades: `in` with its split distances placed over the model's samples' view depths (as
/// ShadowSetupInputs::visibleDepth, unless `in` has one already) and no explicit splits.
ShadowSetupInputs withVisibleSplits(ShadowSetupInputs in, const SamplingErrorModel& model);

/// A candidate chosen on an earlier frame, for this one: `chosen`'s technique, map size and
/// parameters with `base`'s camera, light, scene box, grid origin and visible depth (cascades:
/// splits over this frame's samples).
ShadowSetupInputs forThisFrame(const ShadowSetupInputs& chosen, const ShadowSetupInputs& base,
                               const SamplingErrorModel& model);

/// What `--technique auto` may choose from: the texel budget, the split counts, the search and hysteresis settings.
struct AutoOptions {
    /// Texels of all maps together: one map of √budget² or N cascades of √(budget / N)² (sides
    /// rounded down to a multiple of 16), e.g. 4 M: 1 × 2048² or 4 × 1024².
    int64_t texelBudget = int64_t(2048) * 2048;
    /// 0: any (single maps and 2 to 4 cascades); 1: a single map; N > 1: N cascades.
    int cascades = 0;
    /// Keep the previous frame's choice unless the best is better by this fraction of its
    /// objective: a choice does not flip between frames over a difference the model cannot see.
    double hysteresis = 0.05;
    /// AutoChooser (auto_chooser.h): receivers its per-frame steps are predicted at, spread
    /// evenly over the read-back; the first frame's full search uses them all. 512: the p95 is
    /// then the 26th largest sample, and a step costs an eighth of what 4,096 samples cost (the
    /// docs/error-driven.md's flythrough figures are with it).
    size_t searchSamples = 512;
};
/// Error fields "auto.texel_budget" ([16², 8 × 16384²], and enough for the maps asked for),
/// "auto.cascades" ([0, 8]), "auto.hysteresis" ([0, 1)), "auto.search_samples" ([20, 1,000,000]).
Status validate(const AutoOptions& options);

/// Every candidate the options allow — focused, psm, tsm and lispsm as one map, cascades of each
/// allowed count unwarped and with per-split LiSPSM — each with optimised parameters, best
/// (lowest objective) first; except that when the best is a family whose recommended bias has
/// no normal offset (focused, psm) and one that has it is within AutoOptions::hysteresis of it,
/// that one goes first (the model cannot see the acne the offset prevents). `base` gives the
/// camera, light, scene box and default options.
Result<std::vector<ParameterChoice>> rankCandidates(const ShadowSetupInputs& base, const AutoOptions& options,
                                                    const SamplingErrorModel& model);

/// The best candidate; with `previous` (the last frame's choice) that choice's family, map size
/// and parameters are predicted for this frame too and kept unless the best beats them by
/// AutoOptions::hysteresis. Without samples (nothing visible): the default technique with its
/// default parameters (N cascades when AutoOptions::cascades asks for them). Deterministic for
/// the same inputs and samples.
Result<ParameterChoice> chooseAuto(const ShadowSetupInputs& base, const AutoOptions& options,
                                   const SamplingErrorModel& model, const ParameterChoice* previous = nullptr);

} // namespace shadowkit::core
