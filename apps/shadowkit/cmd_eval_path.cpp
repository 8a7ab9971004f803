#include "eval_path.h"
#include "frame_config_options.h"
#include "html_reports.h"

#include "commands.h"

#include "shadowkit/eval/maps.h"
#include "shadowkit/eval/report.h"
#include "shadowkit/eval/temporal.h"
#include "shadowkit/imaging/image_grid.h"
#include "shadowkit/imaging/plot.h"
#include "shadowkit/measure/path_measurer.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>

namespace shadowkit::app {
namespace {

struct FrameRow {
    int frame = 0;
    double time = 0.0;
    eval::Figures figures;
    std::optional<eval::TemporalFigures> temporal;    // none for the first frame
    std::optional<int> refittedViews;                 // --stabilize with held lattices: maps refitted (pops)
    std::optional<std::string> autoChoice;            // --technique auto: what it chose (core::describe)
    double autoMilliseconds = 0.0;                    // and the CPU time of the choice (model + search)
    std::optional<gl::VirtualPageStats> virtualPages; // --technique virtual: the frame's pages
    size_t shadowTriangles = 0;                       // drawn by the frame's sun shadow pass
    std::optional<eval::SoftFigures> soft;            // --sun-angle: against the sun disk's soft truth
    double seconds = 0.0;
};

// --technique auto: frames whose family (technique, maps, per-split warp) differs from the last's.
int familySwitches(const std::vector<core::ShadowSetupInputs>& chosen) {
    int switches = 0;
    for (size_t i = 1; i < chosen.size(); ++i) {
        const core::ShadowSetupInputs &a = chosen[i - 1], &b = chosen[i];
        const bool csm = b.technique == core::Technique::Csm;
        switches += a.technique != b.technique ||
                    (csm && (a.cascades.count != b.cascades.count || a.cascades.warp != b.cascades.warp));
    }
    return switches;
}

struct Summary {
    double mean = 0.0, p95 = 0.0, max = 0.0;
};
Summary summarise(std::vector<double> v) {
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    Summary s;
    for (const double x : v) s.mean += x / double(v.size());
    s.p95 = v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.95 * double(v.size()))) - 1)];
    s.max = v.back();
    return s;
}

core::Status writeCsv(const std::string& file, const std::vector<FrameRow>& rows) {
    std::ofstream out(file);
    out << "frame,time_s,valid_px,wrong_pct,false_shadow_pct,false_lit_pct,pixels_per_texel_p50,compared_px,flicker_"
           "pct,"
           "truth_change_pct,refitted_views,soft_mae,penumbra_mae,sun_angle_deg\n";
    for (const FrameRow& r : rows) {
        out << fmt::format("{},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g}", r.frame, r.time, r.figures.validPx,
                           r.figures.wrongPct, r.figures.falseShadowPct, r.figures.falseLitPct,
                           r.figures.pixelsPerTexelP50);
        if (r.temporal)
            out << fmt::format(",{},{:.6g},{:.6g}", r.temporal->comparedPx, r.temporal->flickerPct,
                               r.temporal->truthChangePct);
        else
            out << ",,,";
        out << (r.refittedViews ? fmt::format(",{}", *r.refittedViews) : std::string(","));
        out << (r.soft ? fmt::format(",{:.6g},{:.6g},{:.6g}\n", r.soft->softMae, r.soft->penumbraMae,
                                     r.soft->sunAngleDegrees)
                       : std::string(",,,\n"));
    }
    if (!out) return core::makeError(file + ": cannot write");
    return core::Ok{};
}

} // namespace

int runEvalPath(const EvalPathArgs& args) {
    auto timeline = args.timeline.resolve();
    if (!timeline) return fail(timeline.errorInfo());
    if (timeline->frames.size() < 2)
        return fail("--path: eval compares consecutive frames: give a path with at least two frames (or drop --time)");
    auto config = frameConfigOf(args.technique, args.render, args.lights);
    if (!config) return fail(config.errorInfo());
    // Across the path: held lattices (--stabilize), auto's tracked choice.
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    if (args.check) return 0;
    const bool held = driver->config().heldLattices.has_value(), automatic = driver->config().automatic.has_value();
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    scene::Scene& world = *sceneData;
    auto still = args.view.resolve(world);
    if (!still) return fail(still.errorInfo());
    auto measurer = measure::Measurer::createHeadless(world);
    if (!measurer) return fail(measurer.errorInfo());
    fmt::print(stderr, "ray tracer: built in {:.2f} s\n", (*measurer)->rayTracerBuildSeconds());

    measure::PathMeasurer path(**measurer, world, *driver);
    std::vector<FrameRow> rows;
    std::string technique;
    int refits = 0, toCover = 0, stale = 0; // frames with a refit; views refitted for each reason
    std::vector<core::ShadowSetupInputs> autoChosen;
    // --report: the error maps of four frames spread over the path (the middles of its quarters), for the strip.
    std::vector<scene::Image> stripFrames;
    std::vector<std::string> stripCaptions;
    std::vector<size_t> stripIndices;
    if (!args.report.empty())
        for (size_t quarter = 0; quarter < 4; ++quarter)
            if (const size_t i = timeline->frames.size() * (2 * quarter + 1) / 8;
                stripIndices.empty() || stripIndices.back() != i)
                stripIndices.push_back(i);
    fmt::print("{:>5} {:>7} {:>9} {:>7} {:>8} {:>7} {:>9} {:>9} {:>6}\n", "frame", "t_s", "valid_px", "wrong%",
               "flicker%", "truth%", "ppt50", "compared", "sec");
    for (const TimedFrame& frame : timeline->frames) {
        const auto start = std::chrono::steady_clock::now();
        auto view = timeline->viewAt(*still, world, frame.time, !args.view.size.empty());
        if (!view) return fail(view.errorInfo());
        auto measured = path.next(frame.time, *view);
        if (!measured) return fail(withFlagName(measured.errorInfo()));
        const frame::PreparedFrame& prepared = measured->frame;
        technique = core::techniqueName(prepared.setup.technique);
        FrameRow row{frame.number, frame.time, measured->measurement.figures()};
        row.temporal = measured->temporal;
        row.virtualPages = measured->measurement.virtualPages;
        row.shadowTriangles = measured->measurement.shadowPass.triangles;
        row.soft = measured->measurement.soft;
        if (prepared.refits) {
            refits += prepared.refits->views > 0;
            toCover += prepared.refits->toCover, stale += prepared.refits->stale;
            row.refittedViews = prepared.refits->views;
        }
        if (prepared.autoChoice) {
            row.autoChoice = core::describe(*prepared.autoChoice);
            row.autoMilliseconds = prepared.autoMilliseconds;
            autoChosen.push_back(prepared.inputs);
        }
        row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const eval::Figures& f = row.figures;
        if (row.temporal)
            fmt::print("{:>5} {:>7.3f} {:>9} {:>7.2f} {:>8.3f} {:>7.3f} {:>9.3f} {:>9} {:>6.1f}\n", row.frame, row.time,
                       f.validPx, f.wrongPct, row.temporal->flickerPct, row.temporal->truthChangePct,
                       f.pixelsPerTexelP50, row.temporal->comparedPx, row.seconds);
        else
            fmt::print("{:>5} {:>7.3f} {:>9} {:>7.2f} {:>8} {:>7} {:>9.3f} {:>9} {:>6.1f}\n", row.frame, row.time,
                       f.validPx, f.wrongPct, "-", "-", f.pixelsPerTexelP50, "-", row.seconds);
        std::fflush(stdout);
        if (std::find(stripIndices.begin(), stripIndices.end(), rows.size()) != stripIndices.end()) {
            stripFrames.push_back(eval::errorMapImage(measured->measurement.comparison, view->width, view->height));
            stripCaptions.push_back(fmt::format("frame {}: wrong {:.2f} %", row.frame, f.wrongPct));
        }
        rows.push_back(row);
    }

    std::vector<double> flicker, truthChange, wrong, autoMs, softMae, penumbraMae, sunAngles;
    for (const FrameRow& r : rows) {
        wrong.push_back(r.figures.wrongPct);
        if (r.soft)
            softMae.push_back(r.soft->softMae), penumbraMae.push_back(r.soft->penumbraMae),
                sunAngles.push_back(r.soft->sunAngleDegrees);
        if (r.temporal) flicker.push_back(r.temporal->flickerPct), truthChange.push_back(r.temporal->truthChangePct);
        if (automatic && &r != &rows.front()) autoMs.push_back(r.autoMilliseconds); // the first frame searches in full
    }
    const Summary fl = summarise(flicker), tc = summarise(truthChange), wr = summarise(wrong), ms = summarise(autoMs);
    if (automatic) {
        technique = "auto";
        fmt::print("--technique auto: the family changed in {} of {} frames; the choice took {:.2f} ms on the first "
                   "frame (the full "
                   "search), then mean {:.3f} p95 {:.3f} max {:.3f} ms (CPU: model + search, not the read-back)\n",
                   familySwitches(autoChosen), rows.size(), rows.front().autoMilliseconds, ms.mean, ms.p95, ms.max);
    }
    if (held)
        fmt::print(
            "--stabilize: the set-up was refitted in {} of {} frames ({} maps to cover the view, {} grown stale)\n",
            refits, rows.size(), toCover, stale);
    fmt::print("{} along {} ({} frames): flicker_pct mean {:.3f} p95 {:.3f} max {:.3f} | truth_change_pct mean {:.3f} "
               "p95 {:.3f} "
               "max {:.3f} | wrong_pct mean {:.3f}\n",
               technique, timeline->path->name, rows.size(), fl.mean, fl.p95, fl.max, tc.mean, tc.p95, tc.max, wr.mean);
    const Summary sm = summarise(softMae), pm = summarise(penumbraMae);
    // A path's sun keys may change the sun's size (and to 0, where a frame has no soft truth).
    const auto [smallestSun, largestSun] = std::minmax_element(sunAngles.begin(), sunAngles.end());
    const std::string sunSize = sunAngles.empty() || *smallestSun == *largestSun
                                    ? fmt::format("sun {:.2f}°", sunAngles.empty() ? 0.0 : *smallestSun)
                                    : fmt::format("{} of {} frames, sun {:.2f}–{:.2f}°", sunAngles.size(), rows.size(),
                                                  *smallestSun, *largestSun);
    if (!softMae.empty())
        fmt::print("  soft truth, {}: soft_mae mean {:.4f} p95 {:.4f} max {:.4f} | penumbra_mae mean {:.3f} "
                   "p95 {:.3f} max {:.3f}\n",
                   sunSize, sm.mean, sm.p95, sm.max, pm.mean, pm.p95, pm.max);

    if (!args.csv.empty())
        if (auto s = writeCsv(args.csv, rows); !s) return fail("--csv: " + s.error());
    auto writePlot = [&](const std::string& file) -> core::Status {
        imaging::PlotSeries flickerSeries{"flicker_pct", {200, 40, 40}, {}, {}},
            truthSeries{"truth_change_pct", {60, 60, 200}, {}, {}};
        for (const FrameRow& r : rows)
            if (r.temporal) {
                flickerSeries.x.push_back(r.frame), flickerSeries.y.push_back(r.temporal->flickerPct);
                truthSeries.x.push_back(r.frame), truthSeries.y.push_back(r.temporal->truthChangePct);
            }
        imaging::PlotOptions po;
        po.title = fmt::format("{} along {}: flicker and truth change per frame", technique, timeline->path->name);
        po.xLabel = "frame";
        po.yLabel = "% of compared pixels";
        return scene::writePng(imaging::plotLines({flickerSeries, truthSeries}, po), file);
    };
    if (!args.plot.empty())
        if (auto s = writePlot(args.plot); !s) return fail("--plot: " + s.error());
    if (!args.report.empty()) {
        const std::filesystem::path page(args.report);
        const std::string stem = page.stem().string() + "-" + timeline->path->name;
        eval::HtmlPath section{timeline->path->name,
                               fmt::format("{}, {} frames: flicker_pct mean {:.3f} / p95 {:.3f} / max {:.3f}; "
                                           "truth_change_pct mean {:.3f} / p95 {:.3f} / max {:.3f}; wrong_pct mean "
                                           "{:.3f}",
                                           technique, rows.size(), fl.mean, fl.p95, fl.max, tc.mean, tc.p95, tc.max,
                                           wr.mean),
                               {stem + "-flicker.png", "flicker_pct and truth_change_pct per frame"},
                               {},
                               invocationWithout({"--report"}, {})};
        if (auto s = writePlot((page.parent_path() / section.plot.file).string()); !s)
            return fail("--report: " + s.error());
        if (!stripFrames.empty()) {
            section.strip = {stem + "-frames.png", "error maps of frames along the path"};
            if (auto s = scene::writePng(imaging::captionedGrid(stripFrames, stripCaptions, int(stripFrames.size())),
                                         page.parent_path() / section.strip.file);
                !s)
                return fail("--report: " + s.error());
        }
        eval::HtmlReport html{.title = "shadowkit eval --path " + timeline->path->name,
                              .command = invocation(),
                              .machine = machineDescription(**measurer)};
        html.paths.push_back(std::move(section));
        if (auto s = eval::writeHtmlReport(html, page); !s) return fail("--report: " + s.error());
        fmt::print(stderr, "report: {}\n", args.report);
    }
    if (!args.json.empty()) {
        nlohmann::json frames = nlohmann::json::array();
        for (const FrameRow& r : rows) {
            nlohmann::json j = {{"frame", r.frame},
                                {"time_s", r.time},
                                {"valid_px", r.figures.validPx},
                                {"wrong_pct", r.figures.wrongPct},
                                {"pixels_per_texel_p50", r.figures.pixelsPerTexelP50},
                                {"shadow_triangles", r.shadowTriangles}};
            if (r.temporal)
                j.update({{"compared_px", r.temporal->comparedPx},
                          {"flicker_pct", r.temporal->flickerPct},
                          {"truth_change_pct", r.temporal->truthChangePct}});
            if (r.refittedViews) j["refitted_views"] = *r.refittedViews;
            if (r.soft)
                j.update({{"soft_mae", r.soft->softMae},
                          {"penumbra_mae", r.soft->penumbraMae},
                          {"penumbra_px", r.soft->penumbraPx},
                          {"sun_angle_deg", r.soft->sunAngleDegrees}});
            if (r.autoChoice) j.update({{"auto_choice", *r.autoChoice}, {"auto_ms", r.autoMilliseconds}});
            if (const auto& v = r.virtualPages) j["virtual"] = eval::virtualPagesJson(measure::virtualPagesReport(*v));
            frames.push_back(j);
        }
        auto summary = [](const Summary& s) {
            return nlohmann::json{{"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
        };
        nlohmann::json root = {
            {"path", timeline->path->name},
            {"technique", technique},
            {"refits", held ? nlohmann::json(refits) : nlohmann::json(nullptr)},
            {"summary", {{"flicker_pct", summary(fl)}, {"truth_change_pct", summary(tc)}, {"wrong_pct", summary(wr)}}},
            {"frames", frames}};
        if (!softMae.empty()) {
            root["summary"]["soft_mae"] = summary(sm);
            root["summary"]["penumbra_mae"] = summary(pm);
            root["sun_angle_deg"] = {{"min", *smallestSun}, {"max", *largestSun}};
        }
        if (automatic)
            root["auto"] = {{"family_switches", familySwitches(autoChosen)},
                            {"first_frame_ms", rows.front().autoMilliseconds},
                            {"ms", summary(ms)}};
        std::ofstream out(args.json);
        out << root.dump(2) << "\n";
        if (!out) return fail("--json: " + args.json + ": cannot write");
    }
    return 0;
}

} // namespace shadowkit::app
