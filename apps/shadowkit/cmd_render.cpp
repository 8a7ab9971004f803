// shadowkit render: one shaded image of a scene with a shadow technique.
#include "commands.h"
#include "options.h"

#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"

#include <fmt/format.h>

#include <chrono>

namespace shadowkit::app {
namespace {

struct RenderArgs {
    SceneOptions scene;
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    std::string out = "shadowkit.png";
    std::string shadowMapOut;
};

int runRender(const RenderArgs& args) {
    if (auto s = args.technique.check(); !s) return fail(s.error());
    if (auto s = args.render.check(); !s) return fail(s.error());
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.error());
    auto view = args.view.resolve(*sceneData);
    if (!view) return fail(view.error());

    auto context = gl::Context::createHeadless();
    if (!context) return fail(context.error());
    auto renderer = gl::Renderer::create(*sceneData);
    if (!renderer) return fail(renderer.error());

    auto inputs = args.technique.inputsFor(*view, (*renderer)->wsSceneBounds()); // bounds O(1): the hierarchy's
    if (!inputs) return fail(inputs.error());
    auto settingsOr = args.render.settingsFor(*view, *inputs);
    if (!settingsOr) return fail(settingsOr.error());
    const gl::RenderSettings& settings = *settingsOr;
    if (args.technique.visibleDepthFromFrame()) {
        auto refined = gl::withVisibleDepth(**renderer, *inputs, settings);
        if (!refined) return fail(withFlagName(refined.errorInfo()).message);
        inputs = std::move(refined).value();
    }

    // What a frame costs on the CPU before drawing: the set-up.
    const auto cpuStart = std::chrono::steady_clock::now();
    auto setup = core::computeShadowSetup(*inputs);
    if (!setup) return fail(withFlagName(setup.errorInfo()).message);
    const double setupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();

    const auto frameStart = std::chrono::steady_clock::now();
    auto stats = (*renderer)->render(view->camera, view->light, *setup, settings);
    if (!stats) return fail(withFlagName(stats.errorInfo()).message);
    const scene::Image image = (*renderer)->readColor();
    const double frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();

    if (auto s = scene::writePng(image, args.out); !s) return fail("--out: " + s.error());
    if (!args.shadowMapOut.empty())
        if (auto s = scene::writePng((*renderer)->readShadowMap(), args.shadowMapOut); !s) return fail("--shadow-map-out: " + s.error());

    fmt::print("{} | {} | {}x{} | map {}² | view {}\n", core::techniqueName(setup->technique), (*context)->description(),
               settings.width, settings.height, setup->mapSize, args.view.view);
    fmt::print("  set-up (CPU)   {:8.3f} ms\n", setupMs);
    fmt::print("  culling (CPU)  {:8.3f} ms  ({:.3f} ms in GL: pre-pass, queries, masks; {:.3f} ms its own thread CPU; "
               "{:.3f} ms levels and lists)\n",
               stats->cullMilliseconds, stats->cullGlMilliseconds, stats->cullOwnCpuMilliseconds, stats->listCpuMilliseconds);
    if (settings.culling == gl::Culling::Occlusion) {
        const core::CoherentCullingStats& o = stats->occlusion;
        fmt::print("  occlusion      {:8.3f} ms pre-pass (CPU)  {} nodes visited  {} queries over {} nodes  {} waits\n",
                   stats->occlusionMilliseconds, o.nodesVisited, o.queriesIssued, o.nodesQueried, o.waits);
    }
    for (const auto& [name, pass] : {std::pair{"shadow pass", &stats->shadow}, {"main pass  ", &stats->main}})
        fmt::print("  {}    {:8.1f} ms GPU  {:6.2f} M triangles  {} instances  {} draws\n", name, pass->gpuMilliseconds,
                   static_cast<double>(pass->triangles) * 1e-6, pass->instances, pass->drawCalls);
    fmt::print("  frame (wall)   {:8.1f} ms incl. readback\n", frameMs);
    if (const auto& v = inputs->visibleDepth) fmt::print("  visible depth  {:.2f} .. {:.2f} m (LiSPSM n, csm splits)\n", v->x, v->y);
    for (const std::string& f : setup->fallbacks) fmt::print("  fallback: {}\n", f);
    fmt::print("wrote {}{}\n", args.out, args.shadowMapOut.empty() ? "" : " and " + args.shadowMapOut);
    return 0;
}

} // namespace

Command addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a shaded image with shadows (headless) and write a PNG");
    args->scene.addTo(*cmd);
    args->view.addTo(*cmd);
    args->technique.addTo(*cmd);
    args->render.addTo(*cmd);
    cmd->add_option("--out", args->out, "output PNG")->capture_default_str();
    cmd->add_option("--shadow-map-out", args->shadowMapOut, "also write the shadow map itself as a PNG");
    return {cmd, [args] { return runRender(*args); }};
}

} // namespace shadowkit::app
