// shadowkit bench: what a frame costs as the world grows — per pass, the instances,
// triangles and draw calls submitted and the GPU time, plus the CPU time of the set-up and
// of culling, with min / median / max over several frames, for several forest sizes or on a
// user's glTF or OBJ file (--scene).
#include "commands.h"
#include "frame_config_options.h"
#include "html_reports.h"
#include "timeline.h"

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/depth_limits.h"
#include "shadowkit/gl/read_backs.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/measure/frame_costs.h"
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/forest.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace shadowkit::app {
namespace {

struct BenchArgs {
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    LocalLightOptions lights; // --light: spot and point lights over every view (and the views' own)
    std::string trees = "1000,10000,100000", views = "perpendicular,aerial,paper", json, report;
    std::string forest = "simple"; // or leafy: branches and alpha-tested leaf cards
    uint64_t seed = 1;
    double terrainSize = 1024.0;
    int terrainResolution = 256;
    bool sameDensity = false;
    bool impostors = false; // --impostors (scene::ForestOptions::impostors)
    bool limits = false;    // --limits: this GL's depth fill and triangle rates, and each shadow pass against them
    // --frames: N frames per view, or with --path its first N, or a range a:b of its frames as
    // render's and eval's --frames take it (framesText as given; frames and pathFrames from it).
    std::string framesText = "5";
    int frames = 5;
    std::string pathFrames; // for TimelineOptions::frames; empty: every frame of the path
    bool framesGiven = false, viewsGiven = false;
    // --path: a moving camera (and sun) instead of still views — the frames an application
    // draws, so no cache of a still view flatters the CPU's figures.
    std::string path;
    std::string sunPath; // --sun-path: eval's; "off" holds the sun where the path starts
    // --scene: a glTF or OBJ file instead of the forest, one set of rows (each view framed over
    // it as eval frames it); forestFlag names a forest option given with it, which is an error.
    std::string scene, forestFlag;
    std::string sceneUp = "y"; // --scene's up axis (SceneOptions::sceneUp)
};

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

// One forest of the run: its options (--same-density: the terrain grows with the count so trees
// stand as densely as 10,000 on the given size, 100,000 trees on 3238 m for the default 1024 m).
core::Result<scene::ForestOptions> forestOptionsFor(const BenchArgs& args, int trees) {
    scene::ForestOptions forest;
    forest.kind = args.forest == "leafy" ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
    forest.seed = args.seed;
    forest.trees = trees;
    forest.terrainSize =
        args.sameDensity ? args.terrainSize * std::sqrt(std::max(trees, 1) / 10000.0) : args.terrainSize;
    forest.terrainResolution = args.terrainResolution;
    forest.impostors = args.impostors;
    if (auto s = scene::validate(forest); !s) return s.errorInfo();
    return forest;
}

// What a row is measured on: the forest (or --scene's file) and the view.
struct BenchRow {
    int trees = 0;
    double terrainSize = 0.0, forestSeconds = 0.0; // forestSeconds: the forest's build or the file's load
    std::string view;
    std::string scene; // --scene's file; empty: the forest
    // The first two columns: the forest's trees and terrain side, or "-" for a file.
    std::string treesSaid() const { return scene.empty() ? std::to_string(trees) : "-"; }
    std::string terrainSaid() const { return scene.empty() ? fmt::format("{:.0f}", terrainSize) : "-"; }
};

// A pass's fragment-shader invocations beside the samples it wrote, where the driver counts them.
std::string shadedSaid(const gl::PassStats& pass) {
    if (pass.fragmentsShaded == 0 || pass.samplesPassed == 0) return "";
    return fmt::format("; {} fragments shaded, {:.2f} per sample written (more: shaded, then rejected by a "
                       "late depth test or an alpha test; llvmpipe counts the samples written alone)",
                       pass.fragmentsShaded, double(pass.fragmentsShaded) / double(pass.samplesPassed));
}

// The lines under a view's two pass rows: the camera's culling pass, CHC++'s counts, culling's
// CPU time, the shadow pass's samples per texel, the main pass's per pixel of the frame
// (`pixels` of them) and the receiver masks', as they apply.
void printPassLines(const BenchArgs& args, gl::Culling culling, const measure::FrameCosts& costs, double pixels) {
    const measure::Spread prepass = costs.prepass(), cull = costs.cull();
    if (culling == gl::Culling::Gpu)
        fmt::print("{:>7} {:>7} {:<14} gpu     camera's two-phase pass (culling dispatches, depth pyramid, "
                   "early and late pre-pass draws) CPU ms med {:.2f} max {:.2f}\n",
                   "", "", "", prepass.median, prepass.max);
    if (culling == gl::Culling::Occlusion) {
        const measure::FrameCosts::Occlusion o = costs.occlusion();
        fmt::print("{:>7} {:>7} {:<14} chc     medians of the frames after the first: {} nodes visited, {} queries "
                   "over {} nodes ({} multi-queries failed), {} waits (max {}); pre-pass CPU ms med {:.2f} max {:.2f} "
                   "(incl. its draws and waits)\n",
                   "", "", "", o.nodesVisited.median, o.queries.median, o.nodesQueried.median,
                   o.multiQueryFailures.median, o.waits.median, o.waits.max, prepass.median, prepass.max);
    }
    if (!args.render.noCull) {
        const measure::Spread own = costs.cullOwn(), gl = costs.cullGl(), lists = costs.lists();
        fmt::print("{:>7} {:>7} {:<14} cull    CPU ms med {:.2f} max {:.2f}: in GL (pre-pass, queries, masks, waits) "
                   "med {:.2f} max {:.2f}; culling's own (thread CPU: queries of the hierarchy and masks, traversal) "
                   "med {:.3f} max {:.3f}; levels and lists med {:.3f} max {:.3f}\n",
                   "", "", "", cull.median, cull.max, gl.median, gl.max, own.median, own.max, lists.median, lists.max);
    }
    if (const gl::PassStats& shadow = costs.last().shadow; shadow.mapTexels > 0)
        fmt::print(
            "{:>7} {:>7} {:<14} depth   the shadow pass wrote {:.2f} samples per texel drawn ({} samples passed, "
            "{} texels of the maps, or of the virtual pages the last frame drew; 1 is no overdraw){}\n",
            "", "", "", double(shadow.samplesPassed) / double(shadow.mapTexels), shadow.samplesPassed, shadow.mapTexels,
            shadedSaid(shadow));
    if (const gl::PassStats& shadow = costs.last().shadow; shadow.mapTexels > 0 && shadow.leafFragments > 0)
        fmt::print("{:>7} {:>7} {:<14} leaves  the opacity layers' first leaf wrote {:.2f} samples per texel drawn "
                   "({} passed its depth test: one a covered texel when the leaves come nearest the sun first); "
                   "their transmittance blended {:.2f} leaf fragments per texel ({}: every leaf counts)\n",
                   "", "", "", double(shadow.firstLeafSamples) / double(shadow.mapTexels), shadow.firstLeafSamples,
                   double(shadow.leafFragments) / double(shadow.mapTexels), shadow.leafFragments);
    const gl::PassStats& main = costs.last().main;
    if (main.samplesPassed > 0)
        fmt::print("{:>7} {:>7} {:<14} camera  the main pass wrote {:.2f} samples per pixel of the frame ({} "
                   "passed its depth test; over the camera's depth pre-pass each covered pixel once, else every "
                   "fragment nearer than those drawn before it){}\n",
                   "", "", "", double(main.samplesPassed) / pixels, main.samplesPassed, shadedSaid(main));
    const measure::Spread frameCpu = costs.frameCpu(), animate = costs.animate();
    fmt::print("{:>7} {:>7} {:<14} cpu     the frame's CPU side ms med {:.3f} max {:.3f} (the frames after the "
               "first: movers placed and meshes posed, pre-passes, set-up, culling, levels and lists, every GL call; "
               "on a software rasteriser the drawing too), of which animation med {:.3f} max {:.3f}; GPU ms over the "
               "{} of {} frames whose times came back\n",
               "", "", "", frameCpu.median, frameCpu.max, animate.median, animate.max, costs.framesTimed(),
               costs.frames());
    const measure::Spread readBacks = costs.readBacks();
    fmt::print("{:>7} {:>7} {:<14} sync    {:.0f} synchronisations per frame (median; max {:.0f}; the frames after "
               "the first): GPU-to-CPU data reads and query waits, each a stall on a GPU (CHC++'s are counted "
               "above; the GPU's figures are read late)\n",
               "", "", "", readBacks.median, readBacks.max);
    const measure::Spread up = costs.bytesUploaded(), down = costs.bytesReadBack();
    fmt::print("{:>7} {:>7} {:<14} bus     {:.1f} KiB uploaded per frame (median; max {:.1f}: lists, uniforms, page "
               "table) and {:.1f} KiB read back (max {:.1f}: waited for, or copied to host memory for a late "
               "read)\n",
               "", "", "", up.median / 1024.0, up.max / 1024.0, down.median / 1024.0, down.max / 1024.0);
    const measure::Spread dispatches = costs.dispatches(), groups = costs.workGroups();
    fmt::print("{:>7} {:>7} {:<14} compute {:.0f} dispatches per frame (median; max {:.0f}: culling, marking, "
               "reductions) of {:.0f} work groups (max {:.0f})\n",
               "", "", "", dispatches.median, dispatches.max, groups.median, groups.max);
    if (costs.last().virtualPages) { // the frames drew virtual pages (auto may choose them too)
        const measure::Spread pages = costs.pagesRendered(), age = costs.requestsAge(), table = costs.tableBytes();
        const measure::Spread onGpu = costs.pagesCulledOnGpu();
        fmt::print(
            "{:>7} {:>7} {:<14} pages   drawn a frame med {:.0f} max {:.0f} (culled on the GPU med {:.0f}); page "
            "requests read {:.0f} frames late (median; max {:.0f}; 0: the frame's own, −1: none had arrived); "
            "page table {:.2f} KiB up (median; max {:.2f}: the entries that changed)\n",
            "", "", "", pages.median, pages.max, onGpu.median, age.median, age.max, table.median / 1024.0,
            table.max / 1024.0);
    }
    if (args.render.receiverMask && !args.render.noCull) {
        const measure::Spread masks = costs.masks();
        fmt::print("{:>7} {:>7} {:<14} masks   receiver masks CPU ms med {:.2f} max {:.2f} (compute + read-back + "
                   "mask)\n",
                   "", "", "", masks.median, masks.max);
    }
}

// Where the last frame's triangles went: each pass's instances and triangles per level of detail,
// the alpha-tested batches' (leaves and their clouds) in brackets. Levels no instance drew at are
// left out. A large mesh drawn by clusters counts whole here (LevelWork), so a line can exceed
// its pass's row.
void printLevelLines(const gl::WorkByLevel& work) {
    for (const auto& [pass, levels] : {std::pair{"shadow", &work.sun}, std::pair{"main", &work.camera}}) {
        std::string line;
        for (size_t level = 0; level < levels->size(); ++level) {
            const gl::LevelWork& w = (*levels)[level];
            if (w.instances == 0) continue;
            line +=
                fmt::format("{}{} {} inst {:.3f} M ({} / {:.3f} M alpha-tested)", line.empty() ? "" : "; ",
                            level == 0 ? std::string("full") : fmt::format("level {}", level), w.instances,
                            double(w.triangles) * 1e-6, w.alphaTestedInstances, double(w.alphaTestedTriangles) * 1e-6);
        }
        fmt::print("{:>7} {:>7} {:<14} levels  {} pass by level of detail (whole levels): {}\n", "", "", "", pass,
                   line.empty() ? "nothing drawn" : line);
    }
}

nlohmann::json levelsJson(const std::vector<gl::LevelWork>& levels) {
    nlohmann::json j = nlohmann::json::array();
    for (const gl::LevelWork& w : levels)
        j.push_back({{"instances", w.instances},
                     {"triangles", w.triangles},
                     {"alpha_tested_instances", w.alphaTestedInstances},
                     {"alpha_tested_triangles", w.alphaTestedTriangles}});
    return j;
}

// --limits: this GL's ceilings, measured once before the forests (gl/depth_limits.h).
void printLimits(const gl::DepthLimits& l) {
    fmt::print("limits: depth-only fill {:.3f} G samples/s ({} samples in {:.2f} ms); triangles {:.3g} M/s small "
               "(about 2 texels each, {} in {:.2f} ms), {:.3g} M/s large (half the map each, {:.2f} ms)\n",
               l.fillSamplesPerSecond * 1e-9, l.fillSamples, l.fillMilliseconds, l.smallTrianglesPerSecond * 1e-6,
               l.smallTriangles, l.smallMilliseconds, l.largeTrianglesPerSecond * 1e-6, l.largeMilliseconds);
}

nlohmann::json limitsJson(const gl::DepthLimits& l) {
    return {{"fill_samples_per_s", l.fillSamplesPerSecond},
            {"small_triangles_per_s", l.smallTrianglesPerSecond},
            {"large_triangles_per_s", l.largeTrianglesPerSecond},
            {"fill_samples", l.fillSamples},
            {"small_triangles", l.smallTriangles},
            {"large_triangles", l.largeTriangles}};
}

// --limits: the view's shadow pass against them.
void printShadowRates(const measure::FrameCosts::Rates& r) {
    fmt::print("{:>7} {:>7} {:<14} limits  the shadow pass wrote {:.3f} G samples/s ({:.1f} % of the fill rate) and "
               "set up {:.2f} M triangles/s ({:.1f} % of the triangle rate): {}\n",
               "", "", "", r.samplesPerSecond * 1e-9, 100.0 * r.ofFill, r.trianglesPerSecond * 1e-6,
               100.0 * r.ofTriangles, r.ofFill >= r.ofTriangles ? "fill-bound" : "triangle-bound");
}

// Prints a view's rows and adds them to --report's table.
void printRows(const BenchRow& row, const measure::FrameCosts& costs, eval::HtmlTable& table) {
    const measure::Spread setup = costs.setupRest(), cull = costs.cull();
    const gl::FrameStats& last = costs.last();
    for (const auto& [pass, stats, gpu] :
         {std::tuple{"shadow", &last.shadow, costs.shadowGpu()}, std::tuple{"local", &last.local, costs.localGpu()},
          std::tuple{"main", &last.main, costs.mainGpu()}}) {
        if (stats == &last.local && last.localMaps == 0) continue; // no local light
        const double megaTriangles = static_cast<double>(stats->triangles) * 1e-6;
        fmt::print("{:>7} {:>7} {:<14} {:<7} {:>9} {:>9.3f} {:>6} {:>8.1f} {:>8.1f} {:>8.1f} {:>10.3f} {:>9.3f} "
                   "{:>10.3f} {:>9.3f}\n",
                   row.treesSaid(), row.terrainSaid(), row.view, pass, stats->instances, megaTriangles,
                   stats->drawCalls, gpu.min, gpu.median, gpu.max, costs.setupFirst(), setup.median, cull.median,
                   cull.max);
        table.rows.push_back({row.treesSaid(), row.terrainSaid(), row.view, pass, std::to_string(stats->instances),
                              fmt::format("{:.3f}", megaTriangles), std::to_string(stats->drawCalls),
                              fmt::format("{:.1f} / {:.1f} / {:.1f}", gpu.min, gpu.median, gpu.max),
                              fmt::format("{:.3f} / {:.3f}", costs.setupFirst(), setup.median),
                              fmt::format("{:.2f} / {:.2f}", cull.median, cull.max)});
    }
}

// --report's table, before its rows.
// `frames`: "5 frames per row" or "240 frames of --path flythrough".
eval::HtmlTable reportTable(const BenchArgs& args, const std::string& machine, const std::string& frames) {
    return eval::HtmlTable{
        .title = "Frame cost per pass",
        .note =
            fmt::format("{} | technique {} | {}. GPU ms: timer queries around each pass (min / "
                        "median / max over the frames; on a CPU rasteriser only ratios within one run compare). "
                        "Set-up: CPU ms of the first frame, which computes the focus body, and the median of the rest, "
                        "which on a still view reuse it (shadowkit_setup_bench times a moving camera). Culling: "
                        "CPU ms per frame (median / max). Triangles and instances: what the "
                        "pass submitted in the last frame, after culling and levels of detail.",
                        machine, core::techniqueName(args.technique.technique), frames),
        .header = {"trees", "terrain m", "view", "pass", "instances", "M triangles", "draws", "GPU ms min / med / max",
                   "set-up ms first / rest", "cull ms med / max"},
        .rows = {},
        .pictures = {},
        .command = invocationWithout({"--report"}, {})};
}

// One view of one forest, or --path's frames over it: its frames drawn and their costs printed;
// its JSON row.
core::Result<nlohmann::json> benchView(const BenchArgs& args, const BenchRow& row, scene::Scene& forest,
                                       const Timeline& timeline, gl::Renderer& renderer, frame::FrameDriver& driver,
                                       eval::HtmlTable& table, const std::optional<gl::DepthLimits>& limits) {
    ViewOptions viewOptions = args.view;
    if (!timeline.path) viewOptions.view = row.view; // a path's frames take the default view's sun where it has none
    auto still = viewOptions.resolve(forest, /*sayFraming=*/!timeline.path);
    if (!still) return still.errorInfo();
    // Checked (and said) before the table for a path: here each row's forest is checked alone.
    if (auto s = timeline.prepareViews(*still, forest, !args.view.size.empty(), /*sayFraming=*/false); !s)
        return s.errorInfo();
    const int frames = timeline.path ? static_cast<int>(timeline.frames.size()) : args.frames;
    scene::ResolvedView view = *still;
    measure::FrameCosts costs;
    driver.reset(); // --stabilize with held lattices: kept over the view's frames
    std::vector<uint32_t> moved;
    for (int frame = 0; frame < frames; ++frame) {
        const gl::Traffic before = gl::trafficSoFar();
        // Along a path everything moves as the path's time says, the movers and deformed meshes
        // too: a scene held still would flatter every cache (a virtual page under a mover).
        double animateMs = 0.0;
        if (timeline.path) {
            const double t = timeline.frames[size_t(frame)].time;
            const auto start = std::chrono::steady_clock::now();
            moved.clear();
            scene::animate(forest, t, &moved);
            if (auto s = renderer.moveInstances(forest, moved); !s) return s.errorInfo();
            animateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            auto placed = timeline.viewAt(*still, forest, t, !args.view.size.empty());
            if (!placed) return placed.errorInfo();
            view = std::move(placed).value();
        }
        auto drawn = driver.draw(renderer, view);
        if (!drawn) return withFlagName(drawn.errorInfo());
        costs.add(*drawn, gl::trafficSoFar() - before, animateMs);
    }
    costs.addLate(renderer.finishGpuFigures()); // the last frames' figures, after the view's frames
    printRows(row, costs, table);
    const gl::Culling culling = renderer.culling(args.render.culling()); // auto resolved for this driver
    printPassLines(args, culling, costs, double(view.width) * double(view.height));
    const gl::WorkByLevel work = renderer.workByLevel(); // reads GPU-culled lists back: after the timed frames
    printLevelLines(work);
    nlohmann::json run = costs.json();
    run["levels"] = {{"shadow", levelsJson(work.sun)}, {"main", levelsJson(work.camera)}};
    if (limits) {
        const measure::FrameCosts::Rates rates = costs.shadowRates(*limits);
        printShadowRates(rates);
        run["shadow_rates"] = {{"samples_per_s", rates.samplesPerSecond},
                               {"triangles_per_s", rates.trianglesPerSecond},
                               {"of_fill", rates.ofFill},
                               {"of_triangles", rates.ofTriangles}};
    }
    const bool isForest = row.scene.empty();
    run.update({{"trees", isForest ? nlohmann::json(row.trees) : nlohmann::json(nullptr)},
                {"terrain_size", isForest ? nlohmann::json(row.terrainSize) : nlohmann::json(nullptr)},
                {"scene", isForest ? nlohmann::json(nullptr) : nlohmann::json(row.scene)},
                {"forest_seconds", row.forestSeconds},
                {"view", row.view},
                {"technique", core::techniqueName(args.technique.technique)},
                {"visibility", gl::cullingName(culling)},
                {"frames", frames},
                {"path", timeline.path ? nlohmann::json(args.path) : nlohmann::json(nullptr)},
                {"width", view.width},
                {"height", view.height},
                {"receiver_mask", args.render.receiverMask && !args.render.noCull}});
    if (!args.report.empty()) {
        const std::filesystem::path page(args.report);
        const std::string file =
            fmt::format("{}-{}-{}.png", page.stem().string(), isForest ? std::to_string(row.trees) : "scene", row.view);
        if (auto s = scene::writePng(renderer.readColor(), page.parent_path() / file); !s)
            return core::makeError("--report: " + s.error());
        table.pictures.push_back({file, isForest ? fmt::format("{} trees, {}", row.trees, row.view)
                                                 : fmt::format("{}, {}", row.scene, row.view)});
    }
    std::fflush(stdout);
    return run;
}

// The forest of `trees` as the options ask, and its row's first columns (its build time said).
core::Result<std::pair<scene::Scene, BenchRow>> buildForest(const BenchArgs& args, int trees) {
    auto forestOptions = forestOptionsFor(args, trees);
    if (!forestOptions) return forestOptions.errorInfo();
    const auto buildStart = std::chrono::steady_clock::now();
    scene::Scene forest = scene::makeForest(*forestOptions);
    const BenchRow row{trees, forestOptions->terrainSize,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count(), ""};
    fmt::print(stderr, "forest ({}): {} trees on {:.0f} m, {:.2f} M triangles, built in {:.2f} s\n", args.forest, trees,
               row.terrainSize, static_cast<double>(forest.triangleCount()) * 1e-6, row.forestSeconds);
    return std::pair{std::move(forest), row};
}

// The row's scene: --scene's file (loaded as render and eval load it: its warnings said, bad
// input one error), else the forest of `trees`.
core::Result<std::pair<scene::Scene, BenchRow>> buildScene(const BenchArgs& args, int trees) {
    if (args.scene.empty()) return buildForest(args, trees);
    SceneOptions options;
    options.scene = args.scene;
    options.sceneUp = args.sceneUp;
    const auto loadStart = std::chrono::steady_clock::now();
    auto loaded = options.load();
    if (!loaded) return core::makeError("--scene: " + loaded.error());
    BenchRow row{0, 0.0, std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count(), ""};
    row.scene = args.scene;
    return std::pair{std::move(loaded).value(), row};
}

// --frames, checked once: a count N (per view, or a path's first N), or with --path a range
// a:b (also a:, :b) of the path's frame numbers, which TimelineOptions checks against the path.
core::Status parseBenchFrames(BenchArgs& args) {
    const std::string& text = args.framesText;
    if (text.find(':') != std::string::npos) {
        if (args.path.empty())
            return core::makeError("--frames: a range '" + text +
                                   "' needs --path (without one --frames N is the frames per view)");
        args.pathFrames = text;
        return core::Ok{};
    }
    char* end = nullptr;
    const long n = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || n < 1 || n > 1000)
        return core::makeError("--frames: expected a count in [1, 1000]" +
                               std::string(args.path.empty() ? "" : " or a range a:b of the path's frames") +
                               ", got '" + text + "'");
    args.frames = int(n);
    if (args.framesGiven && !args.path.empty()) args.pathFrames = fmt::format(":{}", n); // the path's first N
    return core::Ok{};
}

int runBench(const BenchArgs& args) {
    if (!args.scene.empty() && !args.forestFlag.empty())
        return fail(args.forestFlag + ": the built-in forest's, and --scene benches a file instead");
    if (args.scene.empty() && args.sceneUp != "y") return fail("--scene-up: needs --scene (the forest is y-up)");
    auto counts = args.scene.empty() ? parseCounts(args.trees) : core::Result<std::vector<int>>(std::vector<int>{0});
    if (!counts) return fail(counts.errorInfo());
    if (auto s = args.technique.check(/*measuresFrames=*/false); !s) return fail(s.errorInfo());
    if (auto s = args.render.check(); !s) return fail(s.errorInfo());
    if (auto s = args.view.check(); !s) return fail(s.errorInfo());
    auto views = viewNamesOf(args.views);
    if (!views) return fail(views.errorInfo());
    std::vector<std::string> viewNames = std::move(views).value();
    TimelineOptions timelineOptions;
    timelineOptions.path = args.path;
    timelineOptions.sunPath = args.sunPath;
    if (!args.sunPath.empty() && args.path.empty()) return fail("--sun-path: needs --path");
    if (!args.path.empty()) {
        if (args.viewsGiven) return fail("--views: cannot be combined with --path (the path is the camera)");
        timelineOptions.frames = args.pathFrames;
    }
    auto timeline = timelineOptions.resolve();
    if (!timeline) return fail(timeline.errorInfo());
    if (timeline->path) viewNames = {args.path};
    if (auto s = checkReportWritable("--report", args.report); !s) return fail(s.errorInfo());
    if (auto s = checkJsonWritable("--json", args.json); !s) return fail(s.errorInfo());
    auto config = frameConfigOf(args.technique, args.render, args.lights);
    if (!config) return fail(config.errorInfo());
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    // The views, or a path's frames, over the first forest checked before any output, as render
    // and eval check theirs: a view that cannot be had (--far inside its near plane) or keys no
    // frame there can use fail here, not under the table's header. That forest is the loop's
    // first (the later forests' rows check their own ground). --scene's file is loaded here too,
    // so that a file that does not load fails before the header.
    auto firstForest = buildScene(args, counts->front());
    if (!firstForest) return fail(firstForest.errorInfo());
    for (const std::string& name : timeline->path ? std::vector<std::string>{args.view.view} : viewNames) {
        ViewOptions viewOptions = args.view;
        viewOptions.view = name;
        auto still = viewOptions.resolve(firstForest->first, /*sayFraming=*/false);
        if (!still) return fail(still.errorInfo());
        if (timeline->path)
            if (auto s = timeline->prepareViews(*still, firstForest->first, !args.view.size.empty()); !s)
                return fail(s.errorInfo());
    }
    auto context = gl::Context::createHeadless();
    if (!context) return fail(context.errorInfo());
    const std::string frames = timeline->path
                                   ? fmt::format("{} frames of --path {}", timeline->frames.size(), args.path)
                                   : fmt::format("{} frames per row", args.frames);
    fmt::print("{} | technique {} | {} | culling {}\n", (*context)->description(),
               core::techniqueName(args.technique.technique), frames,
               cullingSaid(args.render.culling(), (*context)->renderer()));
    fmt::print("caster culling {}\n", args.render.receiverMask ? "by visible receivers" : "by volume");
    if (args.technique.technique == core::Technique::Virtual)
        fmt::print("virtual page requests {}\n", args.technique.virtualRequestsLate
                                                     ? "read late (--virtual-requests wait: each frame waits)"
                                                     : "waited for each frame");
    std::optional<gl::DepthLimits> limits;
    if (args.limits) {
        auto measured = gl::measureDepthLimits();
        if (!measured) return fail(measured.errorInfo());
        limits = *measured;
        printLimits(*limits);
    }
    fmt::print("{:>7} {:>7} {:<14} {:<7} {:>9} {:>9} {:>6} {:>26} {:>20} {:>20}\n", "trees", "terrain", "view", "pass",
               "instances", "M tris", "draws", "GPU ms min/med/max", "set-up ms 1st/rest", "cull ms med/max");
    nlohmann::json runs = nlohmann::json::array();
    eval::HtmlTable table = reportTable(args, (*context)->description(), frames); // --report: the rows as printed
    for (size_t k = 0; k < counts->size(); ++k) {
        auto built = k == 0 ? std::move(firstForest) : buildScene(args, (*counts)[k]);
        if (!built) return fail(built.errorInfo());
        scene::Scene& forest = built->first;
        const BenchRow& row = built->second;
        auto renderer = gl::Renderer::create(forest);
        if (!renderer) return fail(renderer.errorInfo());
        // As an application loop: no frame waits for its own GPU times and counts.
        (*renderer)->readGpuFiguresLate(true);
        for (const std::string& name : viewNames) {
            BenchRow viewRow = row;
            viewRow.view = name;
            auto run = benchView(args, viewRow, forest, *timeline, **renderer, *driver, table, limits);
            if (!run) return fail(run.errorInfo());
            runs.push_back(std::move(run).value());
        }
    }
    if (!args.json.empty())
        if (auto s = writeTextFile(
                "--json", args.json,
                nlohmann::json{{"runs", runs}, {"limits", limits ? limitsJson(*limits) : nullptr}}.dump(2) + "\n");
            !s)
            return fail(s.errorInfo());
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
        "bench",
        "Frame cost per pass as the forest grows (or on a --scene file): instances, triangles, draws, GPU and CPU ms");
    CLI::Option* trees =
        cmd->add_option("--trees", args->trees, "forest sizes to measure, comma-separated")->capture_default_str();
    cmd->add_option("--scene", args->scene,
                    "bench a glTF (.gltf, .glb) or OBJ file instead of the forest: one set of rows, each view framed "
                    "over the file as eval frames it");
    cmd->add_option("--scene-up", args->sceneUp, "--scene's up axis: y (glTF's) or z")
        ->check(CLI::IsMember({"y", "z"}))
        ->capture_default_str();
    CLI::Option* views = cmd->add_option("--views", args->views,
                                         "standard views, comma-separated, or all (the six sunlit ones) or local")
                             ->capture_default_str();
    CLI::Option* frames = cmd->add_option("--frames", args->framesText,
                                          "frames per view: min / median / max over them (with --path: its first N, "
                                          "or a range a:b of its frames as render's --frames; default all)")
                              ->capture_default_str();
    cmd->add_option("--path", args->path,
                    "bench a moving camera instead of the views: a camera path's frames in order (a name from "
                    "data/paths, e.g. flythrough, or a .json file), the sun as the path moves it");
    cmd->add_option("--sun-path", args->sunPath,
                    "with --path: the sun's motion, a path name or .json file with sun keys, or 'off' to hold the "
                    "sun where it starts (default: the camera path's own)");
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
    cmd->add_flag("--impostors", args->impostors,
                  "forest, leafy: the shadow passes cast each far tree from an octahedral impostor (one card facing "
                  "the light) in place of its coarsest billboard cloud");
    args->view.addTo(*cmd);
    cmd->remove_option(cmd->get_option("--view"));
    args->technique.virtualRequestsLate = true; // as an application loop: no frame waits for its requests
    args->technique.addTo(*cmd);
    args->render.addTo(*cmd);
    args->lights.addTo(*cmd);
    cmd->add_flag("--limits", args->limits,
                  "first measure this GL's depth-only fill and triangle rates (a 2048² map: 16 full-map layers, "
                  "2 M small triangles, 64 large), then give each shadow pass's rates as fractions of them");
    cmd->add_option("--json", args->json, "write every row as JSON {\"runs\": [...], \"limits\": {...} or null}");
    cmd->add_option("--report", args->report, "also write an HTML page: the rows, what they mean, each view's frame");
    std::vector<CLI::Option*> forestOptions{trees};
    for (const char* flag :
         {"--forest", "--seed", "--terrain-size", "--terrain-resolution", "--same-density", "--impostors"})
        forestOptions.push_back(cmd->get_option(flag));
    return {cmd, [args, views, frames, forestOptions] {
                args->viewsGiven = views->count() > 0;
                args->framesGiven = frames->count() > 0;
                if (auto s = parseBenchFrames(*args); !s) return fail(s.errorInfo());
                for (const CLI::Option* option : forestOptions)
                    if (option->count() > 0 && args->forestFlag.empty()) args->forestFlag = option->get_name();
                return runBench(*args);
            }};
}

} // namespace shadowkit::app
