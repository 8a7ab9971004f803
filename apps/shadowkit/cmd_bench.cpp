// shadowkit bench: what a frame costs as the world grows — per pass, the instances,
// triangles and draw calls submitted and the GPU time, plus the CPU time of the set-up and
// of culling, with min / median / max over several frames, for several forest sizes.
#include "commands.h"
#include "frame_config_options.h"
#include "html_reports.h"

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/forest.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace shadowkit::app {
namespace {

struct BenchArgs {
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    std::string trees = "1000,10000,100000", views = "perpendicular,aerial,paper", json, report;
    std::string forest = "simple"; // or leafy: branches and alpha-tested leaf cards
    uint64_t seed = 1;
    double terrainSize = 1024.0;
    int terrainResolution = 256;
    bool sameDensity = false;
    int frames = 5;
};

struct Spread {
    double min = 0, median = 0, max = 0;
};
Spread spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return {v.front(), v[v.size() / 2], v.back()};
}
nlohmann::json toJson(const Spread& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

core::Result<std::vector<int>> parseCounts(const std::string& text) {
    std::vector<int> counts;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < 0 || v > 1'000'000)
            return core::makeError(
                fmt::format("--trees: expected counts in [0, 1000000] separated by commas, got '{}'", text));
        counts.push_back(static_cast<int>(v));
    }
    if (counts.empty()) return core::makeError("--trees: no count given");
    return counts;
}

int runBench(const BenchArgs& args) {
    auto counts = parseCounts(args.trees);
    if (!counts) return fail(counts.errorInfo());
    if (args.frames < 1 || args.frames > 1000) return fail("--frames: must be in [1, 1000]");
    if (auto s = args.technique.check(/*measuresFrames=*/false); !s) return fail(s.errorInfo());
    if (auto s = args.render.check(); !s) return fail(s.errorInfo());
    std::vector<std::string> viewNames;
    std::stringstream ss(args.views);
    for (std::string name; std::getline(ss, name, ',');) viewNames.push_back(name);
    if (viewNames.empty()) return fail("--views: no view named");

    if (auto s = checkWritable("--report", args.report); !s) return fail(s.errorInfo());
    auto config = frameConfigOf(args.technique, args.render, LocalLightOptions{});
    if (!config) return fail(config.errorInfo());
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    auto context = gl::Context::createHeadless();
    if (!context) return fail(context.errorInfo());
    fmt::print("{} | technique {} | {} frames per row | culling {}\n", (*context)->description(),
               core::techniqueName(args.technique.technique), args.frames,
               gl::cullingName(args.render.noCull ? gl::Culling::Off : args.render.visibility));
    fmt::print("caster culling {}\n", args.render.receiverMask ? "by visible receivers" : "by volume");
    fmt::print("{:>7} {:>7} {:<14} {:<7} {:>9} {:>9} {:>6} {:>26} {:>20} {:>20}\n", "trees", "terrain", "view", "pass",
               "instances", "M tris", "draws", "GPU ms min/med/max", "set-up ms 1st/rest", "cull ms med/max");
    nlohmann::json runs = nlohmann::json::array();
    // --report: the rows as printed, and each row's last frame.
    eval::HtmlTable table{
        .title = "Frame cost per pass",
        .note =
            fmt::format("{} | technique {} | {} frames per row. GPU ms: timer queries around each pass (min / "
                        "median / max over the frames; on a CPU rasteriser only ratios within one run compare). "
                        "Set-up: CPU ms of the first frame, which computes the focus body, and the median of the rest, "
                        "which on a still view reuse it (shadowkit_setup_bench times a moving camera). Culling: "
                        "CPU ms per frame (median / max). Triangles and instances: what the "
                        "pass submitted in the last frame, after culling and levels of detail.",
                        (*context)->description(), core::techniqueName(args.technique.technique), args.frames),
        .header = {"trees", "terrain m", "view", "pass", "instances", "M triangles", "draws", "GPU ms min / med / max",
                   "set-up ms first / rest", "cull ms med / max"},
        .rows = {},
        .pictures = {},
        .command = invocationWithout({"--report"}, {})};
    for (const int trees : *counts) {
        scene::ForestOptions forestOptions;
        forestOptions.kind = args.forest == "leafy" ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
        forestOptions.seed = args.seed;
        forestOptions.trees = trees;
        // --same-density: the terrain grows with the count so trees stand as densely as
        // 10,000 on the given size (100,000 trees on 3238 m for the default 1024 m).
        forestOptions.terrainSize =
            args.sameDensity ? args.terrainSize * std::sqrt(std::max(trees, 1) / 10000.0) : args.terrainSize;
        forestOptions.terrainResolution = args.terrainResolution;
        if (auto s = scene::validate(forestOptions); !s) return fail(s.errorInfo());
        const auto buildStart = std::chrono::steady_clock::now();
        const scene::Scene forest = scene::makeForest(forestOptions);
        const double buildSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
        fmt::print(stderr, "forest ({}): {} trees on {:.0f} m, {:.2f} M triangles, built in {:.2f} s\n", args.forest,
                   trees, forestOptions.terrainSize, static_cast<double>(forest.triangleCount()) * 1e-6, buildSeconds);
        auto renderer = gl::Renderer::create(forest);
        if (!renderer) return fail(renderer.errorInfo());

        for (const std::string& name : viewNames) {
            ViewOptions viewOptions = args.view;
            viewOptions.view = name;
            auto view = viewOptions.resolve(forest);
            if (!view) return fail(view.errorInfo());
            // CHC++'s counts over the steady frames (after the first, a camera cut).
            std::vector<double> nodesVisited, queries, nodesQueried, multiQueryFailures, waits;
            std::vector<double> setupMs, cullMs, cullOwnMs, cullGlMs, listMs, shadowMs, mainMs, occlusionMs, maskMs;
            gl::FrameStats last;
            driver->reset(); // --stabilize with held lattices: kept over the view's frames
            for (int frame = 0; frame < args.frames; ++frame) {
                auto drawn = driver->draw(**renderer, *view);
                if (!drawn) return fail(withFlagName(drawn.errorInfo()));
                setupMs.push_back(drawn->frame.setupMilliseconds);
                const gl::FrameStats* stats = &drawn->stats;
                cullMs.push_back(stats->cullMilliseconds);
                cullGlMs.push_back(stats->cullGlMilliseconds);
                cullOwnMs.push_back(stats->cullOwnCpuMilliseconds);
                listMs.push_back(stats->listCpuMilliseconds);
                occlusionMs.push_back(stats->occlusionMilliseconds);
                maskMs.push_back(stats->receiverMaskMilliseconds);
                shadowMs.push_back(stats->shadow.gpuMilliseconds);
                mainMs.push_back(stats->main.gpuMilliseconds);
                last = *stats;
                if (frame > 0 || args.frames == 1) {
                    const visibility::CoherentCullingStats& o = stats->occlusion;
                    nodesVisited.push_back(double(o.nodesVisited));
                    queries.push_back(double(o.queriesIssued));
                    nodesQueried.push_back(double(o.nodesQueried));
                    multiQueryFailures.push_back(double(o.multiQueryFailures));
                    waits.push_back(double(o.waits));
                }
            }
            // The first frame computes the focus body; the rest of a still view get it remembered.
            const double setupFirst = setupMs.front();
            const Spread setupSpread =
                spread(setupMs.size() > 1 ? std::vector<double>(setupMs.begin() + 1, setupMs.end()) : setupMs);
            const Spread cullSpread = spread(cullMs);
            nlohmann::json run = {
                {"trees", trees},
                {"terrain_size", forestOptions.terrainSize},
                {"forest_seconds", buildSeconds},
                {"view", name},
                {"technique", core::techniqueName(args.technique.technique)},
                {"visibility", gl::cullingName(args.render.noCull ? gl::Culling::Off : args.render.visibility)},
                {"frames", args.frames},
                {"width", view->width},
                {"height", view->height},
                {"setup_first_ms", setupFirst},
                {"setup_ms", toJson(setupSpread)},
                {"cull_ms", toJson(cullSpread)},
                {"cull_own_ms", toJson(spread(cullOwnMs))},
                {"cull_gl_ms", toJson(spread(cullGlMs))},
                {"list_ms", toJson(spread(listMs))}};
            for (const auto& [pass, stats, gpu] :
                 {std::tuple{"shadow", &last.shadow, &shadowMs}, {"main", &last.main, &mainMs}}) {
                const Spread g = spread(*gpu);
                fmt::print("{:>7} {:>7.0f} {:<14} {:<7} {:>9} {:>9.3f} {:>6} {:>8.1f} {:>8.1f} {:>8.1f} {:>10.3f} "
                           "{:>9.3f} {:>10.3f} {:>9.3f}\n",
                           trees, forestOptions.terrainSize, name, pass, stats->instances,
                           static_cast<double>(stats->triangles) * 1e-6, stats->drawCalls, g.min, g.median, g.max,
                           setupFirst, setupSpread.median, cullSpread.median, cullSpread.max);
                table.rows.push_back({std::to_string(trees), fmt::format("{:.0f}", forestOptions.terrainSize), name,
                                      pass, std::to_string(stats->instances),
                                      fmt::format("{:.3f}", static_cast<double>(stats->triangles) * 1e-6),
                                      std::to_string(stats->drawCalls),
                                      fmt::format("{:.1f} / {:.1f} / {:.1f}", g.min, g.median, g.max),
                                      fmt::format("{:.3f} / {:.3f}", setupFirst, setupSpread.median),
                                      fmt::format("{:.2f} / {:.2f}", cullSpread.median, cullSpread.max)});
                run[pass] = {{"instances", stats->instances},
                             {"triangles", stats->triangles},
                             {"draw_calls", stats->drawCalls},
                             {"gpu_ms", toJson(g)}};
            }
            const Spread occlusionSpread = spread(occlusionMs), maskSpread = spread(maskMs);
            const Spread visited = spread(nodesVisited), issued = spread(queries), inQueries = spread(nodesQueried),
                         failed = spread(multiQueryFailures), waited = spread(waits);
            if (args.render.visibility == gl::Culling::Gpu && !args.render.noCull)
                fmt::print("{:>7} {:>7} {:<14} gpu     camera's two-phase pass (culling dispatches, depth pyramid, "
                           "early and late pre-pass draws) CPU ms med {:.2f} max {:.2f}\n",
                           "", "", "", occlusionSpread.median, occlusionSpread.max);
            if (args.render.visibility == gl::Culling::Occlusion && !args.render.noCull)
                fmt::print(
                    "{:>7} {:>7} {:<14} chc     medians of the frames after the first: {} nodes visited, {} queries "
                    "over "
                    "{} nodes ({} multi-queries failed), {} waits (max {}); pre-pass CPU ms med {:.2f} max {:.2f} "
                    "(incl. its draws and waits)\n",
                    "", "", "", visited.median, issued.median, inQueries.median, failed.median, waited.median,
                    waited.max, occlusionSpread.median, occlusionSpread.max);
            if (!args.render.noCull) {
                const Spread own = spread(cullOwnMs), gl = spread(cullGlMs), lists = spread(listMs);
                fmt::print(
                    "{:>7} {:>7} {:<14} cull    CPU ms med {:.2f} max {:.2f}: in GL (pre-pass, queries, masks, waits) "
                    "med {:.2f} max {:.2f}; culling's own (thread CPU: queries of the hierarchy and masks, traversal) "
                    "med {:.3f} max {:.3f}; levels and lists med {:.3f} max {:.3f}\n",
                    "", "", "", cullSpread.median, cullSpread.max, gl.median, gl.max, own.median, own.max, lists.median,
                    lists.max);
            }
            const bool masked = args.render.receiverMask && !args.render.noCull;
            if (masked)
                fmt::print("{:>7} {:>7} {:<14} masks   receiver masks CPU ms med {:.2f} max {:.2f} (compute + "
                           "read-back + mask)\n",
                           "", "", "", maskSpread.median, maskSpread.max);
            run["receiver_mask"] = masked;
            run["receiver_mask_ms"] = toJson(maskSpread);
            run["occlusion"] = {{"nodes_visited", toJson(visited)},
                                {"queries", toJson(issued)},
                                {"nodes_queried", toJson(inQueries)},
                                {"multi_query_failures", toJson(failed)},
                                {"waits", toJson(waited)},
                                {"prepass_ms", toJson(occlusionSpread)}};
            if (!args.report.empty()) {
                const std::filesystem::path page(args.report);
                const std::string file = fmt::format("{}-{}-{}.png", page.stem().string(), trees, name);
                if (auto s = scene::writePng((*renderer)->readColor(), page.parent_path() / file); !s)
                    return fail("--report: " + s.error());
                table.pictures.push_back({file, fmt::format("{} trees, {}", trees, name)});
            }
            std::fflush(stdout);
            runs.push_back(run);
        }
    }
    if (!args.json.empty()) {
        std::ofstream out(args.json);
        out << nlohmann::json{{"runs", runs}}.dump(2) << "\n";
        if (!out) return fail("--json: " + args.json + ": cannot write");
    }
    if (!args.report.empty()) {
        eval::HtmlReport page{
            .title = "shadowkit bench", .command = invocation(), .machine = (*context)->description()};
        page.tables.push_back(std::move(table));
        if (auto s = eval::writeHtmlReport(page, args.report); !s) return fail("--report: " + s.error());
        fmt::print(stderr, "report: {}\n", args.report);
    }
    return 0;
}

} // namespace

Command addBenchCommand(CLI::App& app) {
    auto args = std::make_shared<BenchArgs>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Frame cost per pass as the forest grows: instances, triangles, draws, GPU and CPU ms");
    cmd->add_option("--trees", args->trees, "forest sizes to measure, comma-separated")->capture_default_str();
    cmd->add_option("--views", args->views, "standard views, comma-separated")->capture_default_str();
    cmd->add_option("--frames", args->frames, "frames per view: min / median / max over them")->capture_default_str();
    cmd->add_option("--forest", args->forest,
                    "forest: its trees, simple (opaque blobs) or leafy (alpha-tested leaf cards)")
        ->check(CLI::IsMember({"simple", "leafy"}))
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "forest: random seed")->capture_default_str();
    cmd->add_option("--terrain-size", args->terrainSize, "forest: terrain side in metres")->capture_default_str();
    cmd->add_option("--terrain-resolution", args->terrainResolution, "forest: terrain quads per side")
        ->capture_default_str();
    cmd->add_flag("--same-density", args->sameDensity,
                  "scale the terrain with the tree count (as dense as 10,000 trees on --terrain-size)");
    args->view.addTo(*cmd);
    cmd->remove_option(cmd->get_option("--view"));
    args->technique.addTo(*cmd);
    args->render.addTo(*cmd);
    cmd->add_option("--json", args->json, "write every row as JSON {\"runs\": [...]}");
    cmd->add_option("--report", args->report, "also write an HTML page: the rows, what they mean, each view's frame");
    return {cmd, [args] { return runBench(*args); }};
}

} // namespace shadowkit::app
