// shadowkit analyze: the perspective-aliasing analysis of Wimmer et al. 2004 (Figure 6), and what
// it predicts for a given camera and sun.
#include "auto_technique.h"
#include "commands.h"
#include "options.h"

#include "shadowkit/core/perspective_aliasing.h"
#include "shadowkit/imaging/plot.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>

namespace shadowkit::app {
namespace {

using nlohmann::json;

struct AnalyzeArgs {
    SceneOptions scene;
    ViewOptions view;
    TechniqueOptions technique;
    BoundsOptions bounds;
    double zNear = 1.0, zFar = 100.0;
    std::string csv = "analyze.csv", plot = "analyze.png";
    bool json = false;
    bool candidates = false;
};

int runAnalyze(const AnalyzeArgs& args) {
    if (args.candidates) {
        if (auto s = printAutoCandidates(args.scene, args.view, args.technique); !s) return fail(s.errorInfo());
        return 0;
    }
    if (!(args.zNear > 0.0 && args.zFar > args.zNear && std::isfinite(args.zFar)))
        return fail(fmt::format("--zn/--zf: need 0 < zn < zf, got {} and {}", args.zNear, args.zFar));
    if (auto s = args.technique.check(/*measuresFrames=*/false); !s) return fail(s.errorInfo());
    if (auto s = checkCsvWritable("--csv", args.csv); !s) return fail(s.errorInfo());
    if (auto s = checkPictureWritable("--plot", args.plot); !s) return fail(s.errorInfo());

    // 1. Figure 6: view perpendicular to the light, B = the view frustum.
    const double nOpt = core::lispsmOptimalN(args.zNear, args.zFar);
    const core::AliasingCurve uniform = core::sampleAliasing(args.zNear, args.zFar, core::kUniformN);
    const core::AliasingCurve psm = core::sampleAliasing(args.zNear, args.zFar, args.zNear);
    const core::AliasingCurve lispsm = core::sampleAliasing(args.zNear, args.zFar, nOpt);

    if (!args.csv.empty()) {
        std::string csv = "z,uniform,psm,lispsm\n";
        for (size_t i = 0; i < uniform.z.size(); ++i)
            csv += fmt::format("{},{},{},{}\n", uniform.z[i], uniform.dpds[i], psm.dpds[i], lispsm.dpds[i]);
        if (auto s = writeTextFile("--csv", args.csv, csv); !s) return fail(s.errorInfo());
    }
    if (!args.plot.empty()) {
        imaging::PlotOptions po;
        po.title = fmt::format("perspective aliasing, zn = {:g}, zf = {:g}", args.zNear, args.zFar);
        po.xLabel = "view depth z";
        po.yLabel = "dp/ds";
        po.yMax = std::max(uniform.max, psm.max) * 1.02;
        const std::vector<imaging::PlotSeries> series = {
            {"uniform", {40, 90, 200}, uniform.z, uniform.dpds},
            {"PSM", {220, 60, 40}, psm.z, psm.dpds},
            {fmt::format("LiSPSM (n = {:.3g})", nOpt), {30, 150, 60}, lispsm.z, lispsm.dpds},
        };
        if (auto s = scene::writePng(imaging::plotLines(series, po), args.plot); !s)
            return fail("--plot: " + s.error());
    }

    // 2. The given camera and sun: γ, the n LiSPSM chooses, predicted maximum errors.
    auto bounded = args.bounds.resolve(args.scene, args.view);
    if (!bounded) return fail(bounded.errorInfo());
    auto inputs = args.technique.inputsFor(bounded->view, bounded->wsBounds);
    if (!inputs) return fail(inputs.errorInfo());
    inputs->technique = core::Technique::Lispsm;
    auto setup = core::computeShadowSetup(*inputs);
    if (!setup) return fail(withFlagName(setup.errorInfo()));
    const core::ShadowView& sv = setup->views[0];
    const core::PerspectiveCamera& cam = inputs->camera;
    // No LiSPSM parameters when B is empty (the view misses the scene); no n or d when the
    // view is parallel to the light.
    const auto* warp = std::get_if<core::LispsmWarp>(&sv.warp);
    const double gamma = warp ? warp->gammaDegrees : NAN;
    const double n = warp && !warp->viewParallel ? warp->n : NAN, d = warp && !warp->viewParallel ? warp->d : NAN;
    const double sinGamma = std::sin(glm::radians(gamma));
    const bool warped = warp && !warp->uniform;
    auto predict = [&](double nValue) {
        return std::isnan(d) || sinGamma < 1e-12 ? NAN
                                                 : core::predictedMaxAliasing(cam.zNear, cam.zFar, d, sinGamma, nValue);
    };
    const double predictedUniform = predict(core::kUniformN), predictedPsm = predict(cam.zNear);
    const double predictedLispsm = predict(warped ? n : core::kUniformN);

    if (args.json) {
        auto nan = [](double v) { return std::isnan(v) ? json(nullptr) : json(v); };
        json out = {
            {"uniform", {{"max", uniform.max}, {"argmax_z", uniform.argmaxZ}}},
            {"psm", {{"max", psm.max}, {"argmax_z", psm.argmaxZ}}},
            {"lispsm", {{"n", nOpt}, {"max", lispsm.max}, {"argmax_z", lispsm.argmaxZ}}},
            {"camera",
             {{"view", args.view.view},
              {"gamma_degrees", nan(gamma)},
              {"n", nan(n)},
              {"d", nan(d)},
              {"warped", warped},
              {"predicted_max",
               {{"uniform", nan(predictedUniform)}, {"psm", nan(predictedPsm)}, {"lispsm", nan(predictedLispsm)}}}}},
        };
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    fmt::print("Figure 6 of Wimmer et al. 2004: perspective aliasing dp/ds, view perpendicular to the light, z_n = "
               "{:g}, z_f = {:g}\n",
               args.zNear, args.zFar);
    fmt::print("  uniform  max {:8.3f} at z = {:g}\n", uniform.max, uniform.argmaxZ);
    fmt::print("  psm      max {:8.3f} at z = {:g}\n", psm.max, psm.argmaxZ);
    fmt::print("  lispsm   max {:8.3f} at z = {:g} and {:g} (n_opt = {:.4g})\n", lispsm.max, args.zNear, args.zFar,
               nOpt);
    if (!args.csv.empty() || !args.plot.empty()) fmt::print("  wrote {} {}\n", args.csv, args.plot);
    fmt::print("View '{}' (z_n = {:g}, z_f = {:g}): gamma = {:.2f} deg, LiSPSM n = {:.4g} m over d = {:.4g} m{}\n",
               args.view.view, cam.zNear, cam.zFar, gamma, n, d, warped ? "" : " (uniform: no warp)");
    fmt::print("  predicted max dp/ds on the view axis: uniform {:.4g}, psm {:.4g}, lispsm {:.4g}\n", predictedUniform,
               predictedPsm, predictedLispsm);
    for (const std::string& f : setup->fallbacks) fmt::print("  fallback: {}\n", f);
    return 0;
}

} // namespace

Command addAnalyzeCommand(CLI::App& app) {
    auto args = std::make_shared<AnalyzeArgs>();
    CLI::App* cmd =
        app.add_subcommand("analyze", "Perspective aliasing of uniform, PSM and LiSPSM (Wimmer et al. 2004, Figure 6)");
    args->scene.addTo(*cmd);
    args->view.addTo(*cmd);
    args->technique.addTo(*cmd);
    args->bounds.addTo(*cmd);
    cmd->add_option("--zn", args->zNear, "near distance of the Figure 6 set-up")->capture_default_str();
    cmd->add_option("--zf", args->zFar, "far distance of the Figure 6 set-up")->capture_default_str();
    cmd->add_option("--csv", args->csv, "curves as CSV (z, uniform, psm, lispsm); empty: none")->capture_default_str();
    cmd->add_option("--plot", args->plot, "curves as a PNG plot; empty: none")->capture_default_str();
    cmd->add_flag("--json", args->json, "print the figures as JSON instead of text");
    cmd->add_flag(
        "--candidates", args->candidates,
        "instead: the predicted p50 / p95 of every --technique auto candidate for --view, default and optimised "
        "parameters (--texel-budget, --cascades as for auto; renders a read-back)");
    return {cmd, [args] { return runAnalyze(*args); }};
}

} // namespace shadowkit::app
