// shadowkit compare: a labelled grid of one view rendered with several configurations,
// each captioned with its settings and its wrong_pct against ray-traced truth.
#include "commands.h"
#include "local_light_options.h"
#include "options.h"

#include "shadowkit/eval/image_grid.h"
#include "shadowkit/measure/measurer.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

namespace shadowkit::app {
namespace {

using Cell = std::vector<std::pair<std::string, std::string>>; // render long options, without "--"

struct CompareArgs {
    SceneOptions scene;
    std::string view = "paper", configs, out = "compare.png", size;
    int columns = 0;
};

// "a=1,b=2;c=3" or a JSON file holding [{"a": 1, "b": 2}, {"c": 3}].
core::Result<std::vector<Cell>> parseConfigs(const std::string& text) {
    std::vector<Cell> cells;
    if (text.size() > 5 && text.substr(text.size() - 5) == ".json") {
        std::ifstream in(text);
        if (!in) return core::makeError("--configs: " + text + ": cannot open");
        try {
            const nlohmann::json list = nlohmann::json::parse(in);
            if (!list.is_array()) return core::makeError("--configs: " + text + ": expected a list of objects");
            for (const auto& object : list) {
                if (!object.is_object()) return core::makeError("--configs: " + text + ": expected a list of objects");
                Cell cell;
                for (const auto& [key, value] : object.items())
                    cell.emplace_back(key, value.is_string() ? value.get<std::string>() : value.dump());
                cells.push_back(cell);
            }
        } catch (const nlohmann::json::exception& e) {
            return core::makeError("--configs: " + text + ": not valid JSON (" + e.what() + ")");
        }
    } else {
        std::stringstream cellsText(text);
        for (std::string cellText; std::getline(cellsText, cellText, ';');) {
            Cell cell;
            std::stringstream pairs(cellText);
            for (std::string pair; std::getline(pairs, pair, ',');) {
                const size_t eq = pair.find('=');
                if (eq == std::string::npos || eq == 0)
                    return core::makeError(fmt::format("--configs: expected key=value, got '{}'", pair));
                cell.emplace_back(pair.substr(0, eq), pair.substr(eq + 1));
            }
            cells.push_back(cell);
        }
    }
    if (cells.empty()) return core::makeError("--configs: no configuration given");
    if (cells.size() > 64) return core::makeError("--configs: at most 64 cells");
    return cells;
}

// One cell's options, parsed by the same option groups as `render`.
struct CellOptions {
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    LocalLightOptions lights; // light=point:..., local-map-size=..., sun=off
};

core::Result<CellOptions> parseCell(const Cell& cell, const CompareArgs& args) {
    CellOptions o;
    CLI::App app{"cell"};
    o.view.addTo(app);
    o.technique.addTo(app);
    o.render.addTo(app);
    o.lights.addTo(app);
    std::vector<std::string> argv = {"--view=" + args.view};
    if (!args.size.empty()) argv.push_back("--size=" + args.size);
    for (const auto& [key, value] : cell) argv.push_back("--" + key + "=" + value);
    std::reverse(argv.begin(), argv.end()); // CLI11 takes the vector last argument first
    try {
        app.parse(argv);
    } catch (const CLI::ParseError& e) {
        return core::makeError(fmt::format("--configs: {}", e.what()));
    }
    if (auto t = o.technique.check(); !t) return core::makeError("--configs: " + t.error());
    if (auto s = o.render.check(); !s) return core::makeError("--configs: " + s.error());
    return o;
}

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
        auto o = parseCell(cell, args);
        if (!o) return fail(o.errorInfo());
        options.push_back(std::move(o).value());
    }
    if (args.columns < 0 || args.columns > 16) return fail("--columns: must be in [1, 16] (0: automatic)");
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    auto measurer = measure::Measurer::createHeadless(*sceneData);
    if (!measurer) return fail(measurer.errorInfo());

    std::vector<scene::Image> images;
    std::vector<std::string> captions;
    for (size_t i = 0; i < options.size(); ++i) {
        const CellOptions& o = options[i];
        auto view = o.view.resolve(*sceneData);
        if (!view) return fail(view.errorInfo());
        auto inputs = o.technique.inputsFor(*view, (*measurer)->renderer().wsSceneBounds());
        if (!inputs) return fail(inputs.errorInfo());
        auto settings = o.render.settingsFor(*view, *inputs);
        if (!settings) return fail(settings.errorInfo());
        o.lights.apply(*view, *settings);
        auto lighting = o.lights.lightingFor(*view, (*measurer)->renderer().wsSceneBounds());
        if (!lighting) return fail("--configs: " + withFlagName(lighting.errorInfo()).message);
        if (auto s = (*measurer)->renderer().setLocalLights(std::move(lighting).value()); !s)
            return fail("--configs: " + withFlagName(s.errorInfo()).message);
        // Cells that share camera, sun and size share one ray-traced truth (Measurer's cache).
        std::optional<core::SetupHysteresis> hysteresis = o.technique.newHysteresis(); // a still frame: the fresh fit
        auto measured = (*measurer)->measure(*inputs, *settings,
                                             {.shadedImage = true,
                                              .visibleDepthFromFrame = o.technique.visibleDepthFromFrame(),
                                              .hysteresis = hysteresis ? &*hysteresis : nullptr});
        if (!measured) {
            core::Error error = withFlagName(measured.errorInfo()); // keeps its kind: a driver limit exits 3
            error.message = "--configs: " + error.message;
            return fail(error);
        }
        images.push_back(std::move(measured->image));
        const eval::Figures& f = measured->figures();
        captions.push_back(fmt::format("{} - wrong {:.2f}% (shadow {:.2f}, lit {:.2f})", caption((*cells)[i]), f.wrongPct,
                                       f.falseShadowPct, f.falseLitPct));
        fmt::print("{:>2}  wrong {:6.2f} %  false shadow {:6.2f} %  false lit {:6.2f} %  {}\n", i + 1, f.wrongPct,
                   f.falseShadowPct, f.falseLitPct, caption((*cells)[i]));
    }
    if (auto s = scene::writePng(eval::captionedGrid(images, captions, args.columns), args.out); !s)
        return fail("--out: " + s.error());
    fmt::print("wrote {} ({} cells)\n", args.out, images.size());
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
    return {cmd, [args] { return runCompare(*args); }};
}

} // namespace shadowkit::app
