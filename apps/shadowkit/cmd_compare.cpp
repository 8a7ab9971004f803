// shadowkit compare: a labelled grid of one view rendered with several configurations,
// each captioned with its settings and its wrong_pct against ray-traced truth.
#include "commands.h"
#include "configs.h"
#include "frame_config_options.h"
#include "html_reports.h"

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/imaging/image_grid.h"
#include "shadowkit/measure/measurer.h"

#include <fmt/format.h>

#include <algorithm>

namespace shadowkit::app {
namespace {

struct CompareArgs {
    SceneOptions scene;
    std::string view = "paper", configs, out = "compare.png", size, report;
    int columns = 0;
};

std::string caption(const Cell& cell) {
    std::string text;
    for (const auto& [key, value] : cell) text += (text.empty() ? "" : " ") + key + "=" + value;
    return text.empty() ? "defaults" : text;
}

int runCompare(const CompareArgs& args) {
    auto cells = parseConfigs(args.configs);
    if (!cells) return fail(cells.errorInfo());
    std::vector<CellOptions> options;
    for (const Cell& cell : *cells) {
        auto o = parseCell(cell, args.view, args.size);
        if (!o) return fail(o.errorInfo());
        if (auto s = o->view.check(); !s) return fail(s.errorInfo());
        options.push_back(std::move(o).value());
    }
    if (args.columns < 0 || args.columns > 16) return fail("--columns: must be in [1, 16] (0: automatic)");
    if (auto s = checkReportWritable("--report", args.report); !s) return fail(s.errorInfo());
    if (auto s = checkPictureWritable("--out", args.out); !s) return fail(s.errorInfo());
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    auto measurer = measure::Measurer::createHeadless(*sceneData);
    if (!measurer) return fail(measurer.errorInfo());

    std::vector<scene::Image> images;
    std::vector<std::string> captions;
    eval::HtmlReport page{
        .title = "shadowkit compare: " + args.view, .command = invocation(), .machine = machineDescription(**measurer)};
    for (size_t i = 0; i < options.size(); ++i) {
        const CellOptions& o = options[i];
        auto view = o.view.resolve(*sceneData);
        if (!view) return fail(view.errorInfo());
        auto config = frameConfigOf(o.technique, o.render, o.lights);
        if (!config) return fail("--configs: " + config.error());
        auto driver = frame::FrameDriver::create(std::move(config).value()); // a still frame: the fresh fit
        if (!driver) return fail("--configs: " + withFlagName(driver.errorInfo()).message);
        auto prepared = driver->prepare((*measurer)->renderer(), *view);
        if (!prepared) {
            core::Error error = withFlagName(prepared.errorInfo()); // keeps its kind: a driver limit exits 3
            error.message = "--configs: " + error.message;
            return fail(error);
        }
        // Cells that share camera, sun and size share one ray-traced truth (Measurer's cache).
        auto measured = (*measurer)->measure(*prepared, {.shadedImage = true, .levelMap = true});
        if (!measured) {
            core::Error error = withFlagName(measured.errorInfo()); // keeps its kind: a driver limit exits 3
            error.message = "--configs: " + error.message;
            return fail(error);
        }
        if (!args.report.empty()) {
            // The cell alone is an eval of the view with the cell's settings as flags.
            std::vector<std::string> flags = {"--view", args.view};
            for (const auto& [key, value] : (*cells)[i]) flags.insert(flags.end(), {"--" + key, value});
            const std::string command =
                invocationWithout({"--configs", "--out", "--report", "--columns", "--view"}, flags, "eval");
            eval::ViewReport report =
                measure::viewReport(*measured, prepared->settings, args.view, args.scene.scene, args.scene.seed);
            auto entry = reportEntry(*measured, report, prepared->inputs.light, prepared->settings.sun, args.report,
                                     fmt::format("{}-cell{}", args.view, i + 1), caption((*cells)[i]), command);
            if (!entry) return fail(entry.errorInfo());
            page.entries.push_back(std::move(entry).value());
        }
        images.push_back(std::move(measured->image));
        const eval::Figures& f = measured->figures();
        // A cell with a sun of some size (--sun-angle) is also measured against the disk's soft truth.
        const std::string soft = measured->soft ? fmt::format(", penumbra {:.3f}, soft {:.4f}",
                                                              measured->soft->penumbraMae, measured->soft->softMae)
                                                : "";
        captions.push_back(fmt::format("{} - wrong {:.2f}% (shadow {:.2f}, lit {:.2f}){}", caption((*cells)[i]),
                                       f.wrongPct, f.falseShadowPct, f.falseLitPct, soft));
        fmt::print("{:>2}  wrong {:6.2f} %  false shadow {:6.2f} %  false lit {:6.2f} %{}  {}\n", i + 1, f.wrongPct,
                   f.falseShadowPct, f.falseLitPct,
                   measured->soft ? fmt::format("  penumbra_mae {:.3f}  soft_mae {:.4f}", measured->soft->penumbraMae,
                                                measured->soft->softMae)
                                  : "",
                   caption((*cells)[i]));
    }
    if (auto s = scene::writePng(imaging::captionedGrid(images, captions, args.columns), args.out); !s)
        return fail("--out: " + s.error());
    fmt::print("wrote {} ({} cells)\n", args.out, images.size());
    if (!args.report.empty()) {
        if (auto s = eval::writeHtmlReport(page, args.report); !s) return fail("--report: " + s.error());
        fmt::print("report: {}\n", args.report);
    }
    return 0;
}

} // namespace

Command addCompareCommand(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand("compare", "A captioned image grid of one view under several configurations");
    args->scene.addTo(*cmd);
    cmd->add_option("--view", args->view, "standard view")->capture_default_str();
    cmd->add_option("--size", args->size, "cell size WxH (default: the view's)");
    cmd->add_option("--configs", args->configs,
                    "cells separated by ';', settings by ',', keys = render's long options: "
                    "\"technique=lispsm,bias-slope=0;technique=lispsm\", or FILE.json (a list of objects)")
        ->required();
    cmd->add_option("--columns", args->columns, "cells per row (default: about square)");
    cmd->add_option("--out", args->out, "output PNG")->capture_default_str();
    cmd->add_option("--report", args->report,
                    "also write an HTML page comparing the cells side by side: pictures, figures explained, and the "
                    "eval command of each cell");
    return {cmd, [args] { return runCompare(*args); }};
}

} // namespace shadowkit::app
