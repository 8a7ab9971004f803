// shadowkit compare: a labelled grid of one view rendered with several configurations,
// each captioned with its settings and its wrong_pct against ray-traced truth.
#include "commands.h"
#include "options.h"

#include "shadowkit/eval/bitmap_font.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/ray_scene.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"

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
};

core::Result<CellOptions> parseCell(const Cell& cell, const CompareArgs& args) {
    CellOptions o;
    CLI::App app{"cell"};
    o.view.addTo(app);
    o.technique.addTo(app);
    o.render.addTo(app);
    std::vector<std::string> argv = {"--view=" + args.view};
    if (!args.size.empty()) argv.push_back("--size=" + args.size);
    for (const auto& [key, value] : cell) argv.push_back("--" + key + "=" + value);
    std::reverse(argv.begin(), argv.end()); // CLI11 takes the vector last argument first
    try {
        app.parse(argv);
    } catch (const CLI::ParseError& e) {
        return core::makeError(fmt::format("--configs: {}", e.what()));
    }
    if (auto t = o.technique.resolve(); !t) return core::makeError("--configs: " + t.error());
    if (auto s = o.render.check(); !s) return core::makeError("--configs: " + s.error());
    return o;
}

std::string caption(const Cell& cell) {
    std::string text;
    for (const auto& [key, value] : cell) text += (text.empty() ? "" : " ") + key + "=" + value;
    return text.empty() ? "defaults" : text;
}

// Greedy word wrap to `width` pixels of the 5x7 font at `scale`.
std::vector<std::string> wrap(const std::string& text, int width, int scale) {
    std::vector<std::string> lines(1);
    std::stringstream words(text);
    for (std::string word; words >> word;) {
        const std::string candidate = lines.back().empty() ? word : lines.back() + " " + word;
        if (eval::textWidth(candidate, scale) > width && !lines.back().empty()) lines.push_back(word);
        else lines.back() = candidate;
    }
    return lines;
}

int runCompare(const CompareArgs& args) {
    auto cells = parseConfigs(args.configs);
    if (!cells) return fail(cells.error());
    std::vector<CellOptions> options;
    for (const Cell& cell : *cells) {
        auto o = parseCell(cell, args);
        if (!o) return fail(o.error());
        options.push_back(std::move(o).value());
    }
    if (args.columns < 0 || args.columns > 16) return fail("--columns: must be in [1, 16] (0: automatic)");
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.error());
    auto rays = eval::RayScene::build(*sceneData);
    if (!rays) return fail(rays.error());
    auto context = gl::Context::createHeadless();
    if (!context) return fail(context.error());
    auto renderer = gl::Renderer::create(*sceneData);
    if (!renderer) return fail(renderer.error());

    std::map<std::string, eval::TruthBuffers> truths; // by camera + sun + size: cells often share them
    std::vector<scene::Image> images;
    std::vector<std::string> captions;
    for (size_t i = 0; i < options.size(); ++i) {
        const CellOptions& o = options[i];
        auto view = o.view.resolve(*sceneData);
        if (!view) return fail(view.error());
        auto inputs = o.technique.inputsFor(*view, sceneData->wsBounds());
        if (!inputs) return fail(inputs.error());
        auto setup = core::computeShadowSetup(*inputs);
        if (!setup) return fail(setup.error());
        auto settings = o.render.settingsFor(*view, o.technique.mapSize, *setup);
        if (!settings) return fail(settings.error());
        if (auto stats = (*renderer)->render(view->camera, view->light, *setup, *settings); !stats) return fail(stats.error());
        images.push_back((*renderer)->readColor());
        auto raster = (*renderer)->renderEvalBuffers(view->camera, view->light, *setup, *settings);
        if (!raster) return fail(raster.error());
        const core::PerspectiveCamera& cam = view->camera;
        const std::string key = fmt::format("{} {} {} {} {} {} {} {} {}", cam.wsEye.x, cam.wsEye.y, cam.wsEye.z, cam.wsDirection.x,
                                            cam.wsDirection.y, cam.wsDirection.z, view->light.wsDirection.x,
                                            view->light.wsDirection.y, view->light.wsDirection.z) +
                                fmt::format(" {}x{} {} {} {}", view->width, view->height, cam.fovYDegrees, cam.zNear, cam.zFar);
        if (!truths.count(key)) truths[key] = eval::computeTruth(**rays, cam, view->light, view->width, view->height);
        auto comparison = eval::compare(*raster, truths[key]);
        if (!comparison) return fail(comparison.error());
        const eval::Figures& f = comparison->figures;
        captions.push_back(fmt::format("{} - wrong {:.2f}% (shadow {:.2f}, lit {:.2f})", caption((*cells)[i]), f.wrongPct,
                                       f.falseShadowPct, f.falseLitPct));
        fmt::print("{:>2}  wrong {:6.2f} %  false shadow {:6.2f} %  false lit {:6.2f} %  {}\n", i + 1, f.wrongPct,
                   f.falseShadowPct, f.falseLitPct, caption((*cells)[i]));
    }

    // Grid: cells left to right, top to bottom, each with its caption underneath.
    const int n = static_cast<int>(images.size());
    const int columns = args.columns > 0 ? args.columns : static_cast<int>(std::ceil(std::sqrt(double(n))));
    const int rows = (n + columns - 1) / columns;
    const int cellW = images[0].width, cellH = images[0].height, gap = 6, scale = cellW >= 600 ? 2 : 1;
    size_t captionLines = 1;
    for (const std::string& c : captions) captionLines = std::max(captionLines, wrap(c, cellW - 8, scale).size());
    const int captionH = static_cast<int>(captionLines) * (eval::kGlyphHeight + 3) * scale + 8;
    scene::Image grid(columns * (cellW + gap) + gap, rows * (cellH + captionH + gap) + gap);
    std::fill(grid.rgba.begin(), grid.rgba.end(), uint8_t{255});
    static constexpr uint8_t ink[3] = {20, 20, 20};
    for (int i = 0; i < n; ++i) {
        const int x0 = gap + (i % columns) * (cellW + gap), y0 = gap + (i / columns) * (cellH + captionH + gap);
        for (int y = 0; y < std::min(cellH, images[size_t(i)].height); ++y)
            std::copy_n(images[size_t(i)].pixel(0, y), 4 * std::min(cellW, images[size_t(i)].width), grid.pixel(x0, y0 + y));
        int lineY = y0 + cellH + 4;
        for (const std::string& line : wrap(captions[size_t(i)], cellW - 8, scale)) {
            eval::drawText(grid, x0 + 4, lineY, line, ink, scale);
            lineY += (eval::kGlyphHeight + 3) * scale;
        }
    }
    if (auto s = scene::writePng(grid, args.out); !s) return fail("--out: " + s.error());
    fmt::print("wrote {} ({} cells)\n", args.out, n);
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
