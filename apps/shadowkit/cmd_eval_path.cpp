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
#include "shadowkit/measure/path_report.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>

namespace shadowkit::app {
namespace {

// The flicker and truth change per frame as a plot.
core::Status writePlot(const measure::PathReport& report, const std::string& path, const std::string& file) {
    imaging::PlotSeries flickerSeries{"flicker_pct", {200, 40, 40}, {}, {}},
        truthSeries{"truth_change_pct", {60, 60, 200}, {}, {}};
    for (const measure::PathRow& r : report.rows())
        if (r.temporal) {
            flickerSeries.x.push_back(r.frame), flickerSeries.y.push_back(r.temporal->flickerPct);
            truthSeries.x.push_back(r.frame), truthSeries.y.push_back(r.temporal->truthChangePct);
        }
    imaging::PlotOptions po;
    po.title = fmt::format("{} along {}: flicker and truth change per frame", report.technique(), path);
    po.xLabel = "frame";
    po.yLabel = "% of compared pixels";
    return scene::writePng(imaging::plotLines({flickerSeries, truthSeries}, po), file);
}

// --report: a section with the flicker plot and the strip of error maps along the path.
core::Status writePathReport(const EvalPathArgs& args, const measure::PathReport& report, const std::string& path,
                             const std::vector<scene::Image>& stripFrames,
                             const std::vector<std::string>& stripCaptions, const measure::Measurer& measurer) {
    const std::filesystem::path page(args.report);
    const std::string stem = page.stem().string() + "-" + path;
    const measure::PathReport::Summary fl = report.flicker(), tc = report.truthChange(), wr = report.wrong();
    eval::HtmlPath section{path,
                           fmt::format("{}, {} frames: flicker_pct mean {:.3f} / p95 {:.3f} / max {:.3f}; "
                                       "truth_change_pct mean {:.3f} / p95 {:.3f} / max {:.3f}; wrong_pct mean {:.3f}",
                                       report.technique(), report.rows().size(), fl.mean, fl.p95, fl.max, tc.mean,
                                       tc.p95, tc.max, wr.mean),
                           {stem + "-flicker.png", "flicker_pct and truth_change_pct per frame"},
                           {},
                           invocationWithout({"--report"}, {})};
    if (auto s = writePlot(report, path, (page.parent_path() / section.plot.file).string()); !s) return s;
    if (!stripFrames.empty()) {
        section.strip = {stem + "-frames.png", "error maps of frames along the path"};
        if (auto s = scene::writePng(imaging::captionedGrid(stripFrames, stripCaptions, int(stripFrames.size())),
                                     page.parent_path() / section.strip.file);
            !s)
            return s;
    }
    eval::HtmlReport html{
        .title = "shadowkit eval --path " + path, .command = invocation(), .machine = machineDescription(measurer)};
    html.paths.push_back(std::move(section));
    return eval::writeHtmlReport(html, page);
}

// The frames of a path measured for --report's strip: the middles of its quarters.
std::vector<size_t> stripFrameIndices(size_t frames) {
    std::vector<size_t> indices;
    for (size_t quarter = 0; quarter < 4; ++quarter)
        if (const size_t i = frames * (2 * quarter + 1) / 8; indices.empty() || indices.back() != i)
            indices.push_back(i);
    return indices;
}

void printRow(const measure::PathRow& row) {
    const eval::Figures& f = row.figures;
    if (row.temporal)
        fmt::print("{:>5} {:>7.3f} {:>9} {:>7.2f} {:>8.3f} {:>7.3f} {:>9.3f} {:>9} {:>6.1f}\n", row.frame, row.time,
                   f.validPx, f.wrongPct, row.temporal->flickerPct, row.temporal->truthChangePct, f.pixelsPerTexelP50,
                   row.temporal->comparedPx, row.seconds);
    else
        fmt::print("{:>5} {:>7.3f} {:>9} {:>7.2f} {:>8} {:>7} {:>9.3f} {:>9} {:>6.1f}\n", row.frame, row.time,
                   f.validPx, f.wrongPct, "-", "-", f.pixelsPerTexelP50, "-", row.seconds);
    std::fflush(stdout);
}

} // namespace

int runEvalPath(const EvalPathArgs& args) {
    auto timeline = args.timeline.resolve();
    if (!timeline) return fail(timeline.errorInfo());
    if (timeline->frames.size() < 2) {
        // Which flag left one frame: --frames takes frame numbers (bench's takes a count), --time one moment.
        const TimelineOptions& t = args.timeline;
        if (t.time) return fail("--time: one moment, and eval --path compares consecutive frames: drop --time");
        if (!t.frames.empty())
            return fail(fmt::format("--frames: '{}' selects one frame of the path (its frame numbers, not a "
                                    "count), and eval compares consecutive frames: give a range such as 0:{}",
                                    t.frames, std::max(2, std::atoi(t.frames.c_str()))));
        return fail("--path: " + t.path + " has one frame, and eval compares consecutive frames");
    }
    auto config = frameConfigOf(args.technique, args.render, args.lights);
    if (!config) return fail(config.errorInfo());
    // Across the path: held lattices (--stabilize), auto's tracked choice.
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    if (args.check) return 0;
    const bool held = driver->config().heldLattices.has_value(), automatic = driver->config().automatic.has_value();
    auto sceneData = args.scene.load(/*verbose=*/true, timeline->frames.front().time);
    if (!sceneData) return fail(sceneData.errorInfo());
    scene::Scene& world = *sceneData;
    auto still = args.view.resolve(world, /*sayFraming=*/false); // the path's frames say theirs
    if (!still) return fail(still.errorInfo());
    if (auto s = timeline->prepareViews(*still, world, !args.view.size.empty()); !s) return fail(s.errorInfo());
    auto measurer = measure::Measurer::createHeadless(world);
    if (!measurer) return fail(measurer.errorInfo());
    fmt::print(stderr, "ray tracer: built in {:.2f} s\n", (*measurer)->rayTracerBuildSeconds());

    measure::PathMeasurer path(**measurer, world, *driver);
    measure::MeasureOptions measureOptions;
    measureOptions.levelPops = args.levelPops;
    measure::PathReport report(timeline->path->name, held, automatic);
    // --report: the error maps of four frames spread over the path, for the strip.
    std::vector<scene::Image> stripFrames;
    std::vector<std::string> stripCaptions;
    const std::vector<size_t> stripIndices =
        args.report.empty() ? std::vector<size_t>{} : stripFrameIndices(timeline->frames.size());
    fmt::print("{:>5} {:>7} {:>9} {:>7} {:>8} {:>7} {:>9} {:>9} {:>6}\n", "frame", "t_s", "valid_px", "wrong%",
               "flicker%", "truth%", "ppt50", "compared", "sec");
    for (const TimedFrame& frame : timeline->frames) {
        const auto start = std::chrono::steady_clock::now();
        auto view = timeline->viewAt(*still, world, frame.time, !args.view.size.empty());
        if (!view) return fail(view.errorInfo());
        auto measured = path.next(frame.time, *view, measureOptions);
        if (!measured) return fail(withFlagName(measured.errorInfo()));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const size_t index = report.rows().size();
        const measure::PathRow& row = report.add(frame.number, frame.time, *measured, seconds);
        printRow(row);
        if (std::ranges::find(stripIndices, index) != stripIndices.end()) {
            stripFrames.push_back(eval::errorMapImage(measured->measurement.comparison, view->width, view->height));
            stripCaptions.push_back(fmt::format("frame {}: wrong {:.2f} %", row.frame, row.figures.wrongPct));
        }
    }
    fmt::print("{}", report.summaryText());
    const auto none =
        std::ranges::count_if(report.rows(), [](const measure::PathRow& r) { return r.figures.validPx == 0; });
    if (const std::string warning =
            eval::nothingComparedAlongWarning(timeline->path->name, size_t(none), report.rows().size());
        !warning.empty())
        warn(warning);
    const auto followers =
        std::ranges::count_if(report.rows(), [](const measure::PathRow& r) { return r.temporal.has_value(); });
    const auto uncompared = std::ranges::count_if(report.rows(), [](const measure::PathRow& r) {
        return r.temporal && r.temporal->comparedPx == 0 && r.figures.validPx > 0;
    });
    if (const std::string warning =
            eval::nothingComparedInTimeWarning(timeline->path->name, size_t(uncompared), size_t(followers));
        !warning.empty())
        warn(warning);
    if (!args.csv.empty())
        if (auto s = writeTextFile("--csv", args.csv, report.csv()); !s) return fail(s.errorInfo());
    if (!args.plot.empty())
        if (auto s = writePlot(report, timeline->path->name, args.plot); !s) return fail("--plot: " + s.error());
    if (!args.report.empty()) {
        if (auto s = writePathReport(args, report, timeline->path->name, stripFrames, stripCaptions, **measurer); !s)
            return fail("--report: " + s.error());
        fmt::print(stderr, "report: {}\n", args.report);
    }
    if (!args.json.empty())
        if (auto s = writeTextFile("--json", args.json, report.json().dump(2) + "\n"); !s) return fail(s.errorInfo());
    return 0;
}

} // namespace shadowkit::app
