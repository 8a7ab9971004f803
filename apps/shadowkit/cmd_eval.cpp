// shadowkit eval: rasterized shadows against ray-traced truth, per standard view.
#include "auto_technique.h"
#include "commands.h"
#include "eval_path.h"
#include "eval_session.h"
#include "frame_config_options.h"
#include "html_reports.h"
#include "options.h"

#include "shadowkit/eval/maps.h"
#include "shadowkit/eval/report.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/measure/measurer.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace shadowkit::app {
namespace {

namespace fs = std::filesystem;

struct EvalArgs {
    SceneOptions scene;
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    TimelineOptions timeline;
    LocalLightOptions lights;
    std::string views; // "a,b" or "all"; empty: --view
    std::string json, errorMap, aliasingMap, dump, csv, plot, report;
    bool levelPops = false;                             // --level-pops, with --path
    int softSamples = eval::SoftTruthOptions{}.samples; // --soft-samples: rays a penumbra point takes
    // --depth-tolerance: how far, as a fraction of the view depth, the raster's surface may lie from the
    // ray's for a pixel to be compared (EVALUATION.md: 0.5 %)
    double depthTolerance = eval::CompareOptions{}.depthTolerance;
    bool check = false;             // --check: validate every option, render and measure nothing
    bool serve = false;             // --serve: evaluate each request read from stdin (eval_session.h)
    EvalSession* session = nullptr; // a request of --serve: the scene and measurer kept between requests
};

// "maps/err.png" for view "noon" among several -> "maps/err-noon.png".
fs::path perView(const std::string& file, const std::string& view, bool several) {
    if (!several) return file;
    const fs::path p(file);
    return p.parent_path() / (p.stem().string() + "-" + fileSafe(view) + p.extension().string());
}

core::Result<std::vector<std::string>> viewNames(const EvalArgs& args) {
    if (args.views.empty()) return std::vector<std::string>{args.view.view};
    return viewNamesOf(args.views);
}

// The per-view files asked for: error and aliasing maps (and with a sun of some size the signed
// error against its soft truth, NAME-soft.png), the raw buffers.
core::Status writeViewFiles(const EvalArgs& args, const measure::Measurement& measured, const std::string& name,
                            bool several) {
    if (!args.errorMap.empty())
        if (auto s =
                scene::writePng(eval::errorMapImage(measured.comparison, measured.raster.width, measured.raster.height),
                                perView(args.errorMap, name, several));
            !s)
            return core::makeError("--error-map: " + s.error());
    // With a sun of some size, also the signed error against its soft truth: NAME-soft.png.
    if (!args.errorMap.empty() && measured.softTruth) {
        const fs::path hard = perView(args.errorMap, name, several);
        if (auto s = scene::writePng(
                eval::softErrorMapImage(measured.raster.shadowTerm, *measured.softTruth, measured.comparison),
                hard.parent_path() / (hard.stem().string() + "-soft" + hard.extension().string()));
            !s)
            return core::makeError("--error-map: " + s.error());
    }
    if (!args.aliasingMap.empty())
        if (auto s = scene::writePng(
                eval::aliasingMapImage(measured.comparison, measured.raster.width, measured.raster.height),
                perView(args.aliasingMap, name, several));
            !s)
            return core::makeError("--aliasing-map: " + s.error());
    if (!args.dump.empty())
        if (auto s = eval::dumpBuffers(several ? fs::path(args.dump) / fileSafe(name) : fs::path(args.dump),
                                       measured.raster, *measured.truth, measured.comparison,
                                       measured.softTruth ? &*measured.softTruth : nullptr);
            !s)
            return core::makeError("--dump: " + s.error());

    return core::Ok{};
}

// The view's row, a row per local light with its soft figures, and the sun's soft figures.
void printViewRow(const eval::ViewReport& report) {
    const std::string& name = report.view;
    const eval::Figures& f = report.figures;
    fmt::print(
        "{:<14} {:<10} {:>5} {:>9} {:>8} {:>7.2f} {:>8.2f} {:>8.2f} {:>7.2f} {:>7.3f} {:>7.3f} {:>7.3f} {:>6.1f}\n",
        name, report.technique, report.mapSize, f.validPx, f.excludedPx, f.wrongPct, f.falseShadowPct, f.falseLitPct,
        f.undersampledPct, f.pixelsPerTexelP50, f.pixelsPerTexelP95, f.pixelsPerTexelP99, report.seconds);
    if (const std::string warning = eval::nothingComparedWarning(name, f); !warning.empty()) warn(warning);
    if (const std::string warning = eval::mostlyLeftOutWarning(name, f); !warning.empty()) warn(warning);
    // With spot and point lights the row above is every light together; each follows.
    for (const eval::LightReport& l : report.lights) {
        fmt::print("  {:<12} {:<10} {:>5} {:>9} {:>8} {:>7.2f} {:>8.2f} {:>8.2f} {:>7.2f} {:>7.3f} {:>7.3f} "
                   "{:>7.3f}   {} maps{}\n",
                   l.light, "", "", l.figures.validPx, "", l.figures.wrongPct, l.figures.falseShadowPct,
                   l.figures.falseLitPct, l.figures.undersampledPct, l.figures.pixelsPerTexelP50,
                   l.figures.pixelsPerTexelP95, l.figures.pixelsPerTexelP99, l.maps,
                   l.skippedFaces ? fmt::format(", {} faces skipped", l.skippedFaces) : "");
        if (const auto& s = l.soft)
            fmt::print("    soft truth, lamp {:.3g} m: {}\n", l.radiusMetres, eval::softFiguresLine(*s));
    }
    if (const auto& s = report.soft)
        fmt::print("  soft truth, sun {:.2f}°: {}\n", s->sunAngleDegrees, eval::softFiguresLine(*s));
}

// What can be checked before anything is loaded: the options, and the folders of every file to write.
core::Status checkEvalArgs(const EvalArgs& args) {
    if (auto s = args.technique.check(/*measuresFrames=*/true, /*takesAuto=*/true); !s) return s;
    if (auto s = args.render.check(); !s) return s;
    if (auto s = args.scene.check(); !s) return s;
    if (auto s = args.view.check(); !s) return s;
    if (auto s = args.lights.check(); !s) return s;
    if (args.softSamples < 16 || args.softSamples > 4096)
        return core::makeError(fmt::format("--soft-samples: must be in [16, 4096] rays, got {}", args.softSamples));
    if (!(args.depthTolerance >= 1e-5 && args.depthTolerance <= 0.1))
        return core::makeError(
            fmt::format("--depth-tolerance: must be in [0.00001, 0.1] of the view depth, got {}", args.depthTolerance));
    if (auto s = checkJsonWritable("--json", args.json); !s) return s;
    if (auto s = checkCsvWritable("--csv", args.csv); !s) return s;
    if (auto s = checkReportWritable("--report", args.report); !s) return s;
    for (auto [flag, file] :
         {std::pair{"--plot", &args.plot}, {"--error-map", &args.errorMap}, {"--aliasing-map", &args.aliasingMap}})
        if (auto s = checkPictureWritable(flag, *file); !s) return s;
    return core::Ok{};
}

int runEval(const EvalArgs& args) {
    if (args.serve) return serveEvaluations();
    if (auto s = checkEvalArgs(args); !s) return fail(s.errorInfo());
    if (!args.timeline.path.empty()) {
        if (!args.views.empty() || !args.errorMap.empty() || !args.aliasingMap.empty() || !args.dump.empty())
            return fail("--path: evaluates a path's frames, so --views, --error-map, --aliasing-map and --dump (still "
                        "views) do not apply");
        if (args.depthTolerance != eval::CompareOptions{}.depthTolerance)
            return fail("--depth-tolerance: still views only (a path's frames are compared at EVALUATION.md's 0.5 %)");
        // A path animates its scene frame by frame with a measurer (GL context) of its own, so
        // --serve's kept one goes first: when the path's context is destroyed none is current,
        // and the kept one would be drawn into unbound.
        if (args.session) args.session->reset();
        return runEvalPath({args.scene, args.view, args.technique, args.render, args.timeline, args.lights, args.csv,
                            args.plot, args.json, args.report, args.check, args.levelPops});
    }
    if (!args.csv.empty() || !args.plot.empty()) return fail("--csv and --plot need --path (figures per frame)");
    if (args.levelPops) return fail("--level-pops: needs --path (pops between consecutive frames)");
    auto timeline = args.timeline.resolve(); // still views: --time and --sun-path
    if (!timeline) return fail(timeline.errorInfo());
    auto names = viewNames(args);
    if (!names) return fail(names.errorInfo());
    if (args.views.empty())
        if (auto s = args.view.check(); !s) return fail(s.errorInfo());
    const bool several = names->size() > 1;

    auto config = frameConfigOf(args.technique, args.render, args.lights);
    if (!config) return fail(config.errorInfo());
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    if (args.check) return 0;
    const double time = timeline->frames.front().time;
    EvalSession single;
    EvalSession& session = args.session ? *args.session : single;
    if (auto s = session.prepare(args.scene, time); !s) return fail(s.errorInfo());
    scene::Scene& world = session.scene();
    measure::Measurer* const measurer = &session.measurer();

    std::vector<eval::ViewReport> reports;
    eval::HtmlReport page{.title = "shadowkit eval", .command = invocation(), .machine = machineDescription(*measurer)};
    // Every view resolved before the table's header, so a view that cannot be had stops the run
    // with its error alone, not under a header with no rows.
    std::vector<scene::ResolvedView> views;
    for (const std::string& name : *names) {
        ViewOptions viewOptions = args.view;
        viewOptions.view = name;
        auto view = viewOptions.resolve(world);
        if (!view) return fail(view.errorInfo());
        view = timeline->viewAt(*view, world, time); // the sun of --sun-path at --time
        if (!view) return fail(view.errorInfo());
        views.push_back(std::move(view).value());
    }
    fmt::print("{:<14} {:<10} {:>5} {:>9} {:>8} {:>7} {:>8} {:>8} {:>7} {:>7} {:>7} {:>7} {:>6}\n", "view", "technique",
               "map", "valid_px", "excl_px", "wrong%", "fshadow%", "flit%", "under%", "ppt50", "ppt95", "ppt99", "sec");
    for (size_t i = 0; i < names->size(); ++i) {
        const std::string& name = (*names)[i];
        const auto start = std::chrono::steady_clock::now();
        driver->reset(); // a still view is a first frame: the fresh fit, auto's full search
        auto prepared = driver->prepare(measurer->renderer(), views[i]);
        if (!prepared) return fail(withFlagName(prepared.errorInfo()));
        printAutoChoice(name, *prepared);

        // Progress only when the truth takes a while (large images, big scenes).
        measure::MeasureOptions options;
        options.shadedImage = !args.report.empty();
        options.levelMap = !args.report.empty(); // the report's level map
        options.softTruth.samples = args.softSamples;
        options.compare.depthTolerance = args.depthTolerance;
        options.truthProgress = [&, shown = false](double done) mutable {
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if ((elapsed < 2.0 && !shown) || !isatty(fileno(stderr))) return; // a log gets the table only
            shown = true;
            fmt::print(stderr, "\r{}: ray tracing {:3.0f} %", name, 100.0 * done);
            if (done >= 1.0) fmt::print(stderr, "\n");
        };
        auto measured = measurer->measure(*prepared, options);
        if (!measured) return fail(withFlagName(measured.errorInfo()));

        if (auto s = writeViewFiles(args, *measured, name, several); !s) return fail(s.errorInfo());
        eval::ViewReport report =
            measure::viewReport(*measured, prepared->settings, name, args.scene.scene, args.scene.seed);
        report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        report.depthTolerance = args.depthTolerance;
        if (prepared->autoChoice) report.autoChoice = core::describe(*prepared->autoChoice);
        printViewRow(report);
        std::fflush(stdout);
        if (!args.report.empty()) {
            const std::string label =
                report.virtualPages
                    ? fmt::format("{}, {} pages", report.technique, report.virtualPages->pagesResident)
                    : fmt::format("{} {}{}²", report.technique,
                                  report.maps > 1 ? fmt::format("{} × ", report.maps) : "", report.mapSize);
            auto entry = reportEntry(*measured, report, prepared->inputs.light, prepared->settings.sun, args.report,
                                     fileSafe(name), label,
                                     invocationWithout({"--views", "--view", "--report", "--json", "--error-map",
                                                        "--aliasing-map", "--dump"},
                                                       {"--view", name}));
            if (!entry) return fail(entry.errorInfo());
            page.entries.push_back(std::move(entry).value());
        }
        reports.push_back(std::move(report));
    }
    if (!args.json.empty())
        if (auto s = eval::writeReportJson(reports, args.json); !s) return fail("--json: " + s.error());
    if (!args.report.empty()) {
        if (auto s = eval::writeHtmlReport(page, args.report); !s) return fail("--report: " + s.error());
        fmt::print(stderr, "report: {}\n", args.report);
    }
    return 0;
}

} // namespace

Command addEvalCommand(CLI::App& app, EvalSession* session) {
    auto args = std::make_shared<EvalArgs>();
    args->session = session;
    CLI::App* cmd = app.add_subcommand("eval", "Measure a technique against ray-traced shadows on the standard views");
    args->scene.addTo(*cmd);
    args->view.addTo(*cmd);
    args->technique.addTo(*cmd);
    cmd->add_option("--views", args->views,
                    "views to evaluate: a,b,... 'all' (the six sunlit views) or 'local' (those with spot and point "
                    "lights; default: --view)");
    args->render.addTo(*cmd);
    args->lights.addTo(*cmd);
    cmd->add_option("--json", args->json, "write the figures as JSON {\"views\": [...]}");
    cmd->add_option("--error-map", args->errorMap,
                    "write the error map PNG (one per view: NAME-view.png); with --sun-angle also NAME-soft.png, "
                    "the signed error against the soft truth (red too dark, blue too light)");
    cmd->add_option("--aliasing-map", args->aliasingMap, "write the pixels-per-texel heat map PNG");
    cmd->add_option("--soft-samples", args->softSamples,
                    "--sun-angle and lamps with a radius: shadow rays per penumbra point of the soft truth, rounded up "
                    "to a square (its standard error about 1 / (2 sqrt(N)) at most)")
        ->capture_default_str();
    cmd->add_option("--depth-tolerance", args->depthTolerance,
                    "a pixel is compared when the raster's surface is the ray's instance within this fraction of the "
                    "view depth (EVALUATION.md's 0.5 %); tighter keeps apart two leaves of one tree")
        ->capture_default_str();
    cmd->add_option("--report", args->report,
                    "write an HTML page (pictures beside it): per view the frame, rendered and ray-traced shadows, "
                    "error and aliasing maps, the figures explained and the command that reproduces them");
    cmd->add_option("--dump", args->dump, "write per-pixel buffers as .npy files into this directory");
    args->timeline.addTo(*cmd);
    cmd->add_option("--csv", args->csv,
                    "with --path: the figures of every frame as CSV, flicker_pct and truth_change_pct included");
    cmd->add_option("--plot", args->plot, "with --path: a PNG plot of flicker_pct and truth_change_pct per frame");
    cmd->add_flag("--level-pops", args->levelPops,
                  "with --path: also draw each frame with the levels of detail the frame before chose, and report "
                  "level_pop_pct, the pixels whose surface or shadow changed only because levels changed (a camera "
                  "pass and a shadow pass more a frame)");
    cmd->add_flag("--check", args->check,
                  "check every option (scene's, view names, technique, filters, lights, path) and exit without "
                  "rendering: 0 when the evaluation would start, else the one-line error (shadowkit sweep checks its "
                  "cells so)");
    if (!session)
        cmd->add_flag("--serve", args->serve,
                      "evaluate requests read from stdin, one JSON array of eval arguments a line, keeping the scene, "
                      "GL context, BVHs and truths between them while the scene's options stay the same; after each, "
                      "a line 'shadowkit-serve: exit CODE' (shadowkit sweep's workers)");
    return {cmd, [args] { return runEval(*args); }};
}

} // namespace shadowkit::app
