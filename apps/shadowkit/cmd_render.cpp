// shadowkit render: one shaded image of a scene with a shadow technique.
#include "auto_technique.h"
#include "commands.h"
#include "frame_config_options.h"
#include "options.h"
#include "timeline.h"

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/imaging/image_grid.h"
#include "shadowkit/scene/animation.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace shadowkit::app {
namespace {

struct RenderArgs {
    SceneOptions scene;
    ViewOptions view;
    TechniqueOptions technique;
    RenderOptions render;
    TimelineOptions timeline;
    LocalLightOptions lights;
    std::string out = "shadowkit.png";
    std::string shadowMapOut, localMapOut, video, strip;
};

// The report of a single frame: where the time went.
void printFrameReport(const RenderArgs& args, const gl::Context& context, const frame::PreparedFrame& frame,
                      const gl::FrameStats& stats, double frameMs) {
    const core::ShadowSetup& setup = frame.setup;
    const gl::RenderSettings& settings = frame.settings;
    fmt::print("{} | {} | {}x{} | map {}² | view {} | culling {}\n", core::techniqueName(setup.technique),
               context.description(), settings.width, settings.height, setup.mapSize,
               args.timeline.path.empty() ? args.view.view : "path " + args.timeline.path,
               cullingSaid(args.render.culling(), context.renderer()));
    fmt::print("  set-up (CPU)   {:8.3f} ms\n", frame.setupMilliseconds);
    if (frame.prePasses.submissions > 0)
        fmt::print(
            "  before it      {:8.1f} ms  {} GPU submissions, {} read-backs (--visible-depth auto, --technique auto)\n",
            frame.prePasses.milliseconds, frame.prePasses.submissions, frame.prePasses.readBacks);
    fmt::print("  culling (CPU)  {:8.3f} ms  ({:.3f} ms in GL: pre-pass, queries, masks; {:.3f} ms its own thread CPU; "
               "{:.3f} ms levels and lists)\n",
               stats.cullMilliseconds, stats.cullGlMilliseconds, stats.cullOwnCpuMilliseconds,
               stats.listCpuMilliseconds);
    if (settings.culling == gl::Culling::Occlusion) {
        const visibility::CoherentCullingStats& o = stats.occlusion;
        fmt::print("  occlusion      {:8.3f} ms pre-pass (CPU)  {} nodes visited  {} queries over {} nodes  {} waits\n",
                   stats.occlusionMilliseconds, o.nodesVisited, o.queriesIssued, o.nodesQueried, o.waits);
    }
    if (!settings.sun) fmt::print("  sun            off (night)\n");
    if (stats.localMaps > 0 || stats.skippedFaces > 0)
        fmt::print("  local lights   {} maps drawn ({} cube faces skipped: they see nothing of the view), {} pass\n",
                   stats.localMaps, stats.skippedFaces, gl::localPassName(settings.localPass));
    for (const auto& [name, pass] :
         {std::pair{"shadow pass", &stats.shadow}, {"local pass ", &stats.local}, {"main pass  ", &stats.main}})
        fmt::print("  {}    {:8.1f} ms GPU  {:6.2f} M triangles  {} instances  {} draws\n", name, pass->gpuMilliseconds,
                   static_cast<double>(pass->triangles) * 1e-6, pass->instances, pass->drawCalls);
    if (const auto& v = stats.virtualPages)
        fmt::print("  virtual pages  {} requested  {} rendered  {} resident  {} fell back  pool {} pages, {:.1f} MiB, "
                   "{} levels from {} m texels\n",
                   v->pagesRequested, v->pagesRendered, v->pagesResident, v->pagesFellBack, v->poolPages,
                   static_cast<double>(v->poolBytes) / (1024.0 * 1024.0), setup.views.size(),
                   setup.clipmap ? std::ldexp(1.0, setup.clipmap->firstExponent) : 0.0);
    if (const auto& v = stats.virtualPages; v && v->opacityBytes > 0)
        fmt::print("  opacity layers {:.1f} MiB beside the pool\n",
                   static_cast<double>(v->opacityBytes) / (1024.0 * 1024.0));
    if (const auto& v = stats.virtualPages; v && (v->pagesDeferred > 0 || v->lagFrames > 0))
        fmt::print("  page budget    {} pages deferred  {} levels behind  the sun of {} frames ago shown\n",
                   v->pagesDeferred, v->levelsBehind, v->lagFrames);
    fmt::print("  frame (wall)   {:8.1f} ms incl. readback\n", frameMs);
    if (const auto& v = frame.inputs.visibleDepth)
        fmt::print("  visible depth  {:.2f} .. {:.2f} m (LiSPSM n, csm splits)\n", v->x, v->y);
    for (const std::string& f : setup.fallbacks) fmt::print("  fallback: {}\n", f);
}

bool ffmpegInstalled() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

// Encodes the written frames with ffmpeg (installed: checked before drawing).
core::Status encodeVideo(const std::string& pattern, int firstFrame, double framesPerSecond, const std::string& video) {
    const std::string command = fmt::format(
        "ffmpeg -y -loglevel error -framerate {:.6g} -start_number {} -i '{}' -c:v libx264 -pix_fmt yuv420p '{}'",
        framesPerSecond, firstFrame, pattern, video);
    if (pattern.find('\'') != std::string::npos || video.find('\'') != std::string::npos)
        return core::makeError("--video: file names must not contain a single quote");
    if (std::system(command.c_str()) != 0) return core::makeError("--video: ffmpeg failed to write " + video);
    return core::Ok{};
}

// Where a frame's image goes: --out, or for a numbered frame of a path (every frame of a sequence,
// or one picked by --frames) --out's pattern with the frame's number, e.g. frames/0120.png.
std::string outFileOf(const RenderArgs& args, const Timeline& timeline, const TimedFrame& frame) {
    if (!timeline.framesNumbered()) return args.out;
    auto named = frameFileName(args.out, frame.number);
    return named ? *named : args.out;
}

// The outputs' flags agree with the timeline (--video and --strip need a path) and their
// folders exist, before the scene is loaded.
core::Status checkOutputs(const RenderArgs& args, const Timeline& timeline) {
    const bool sequence = timeline.isSequence();
    if (sequence || !args.video.empty())
        if (auto name = frameFileName(args.out, 0); !name) return name.errorInfo();
    // A frame pattern for one image: a frame of the path takes its number (outFileOf); an
    // image with none (--time, no --path) would be written under the pattern itself.
    if (frameFileName(args.out, 0) && !timeline.framesNumbered())
        return core::makeError("--out: '" + args.out + "' is a pattern for a path's frames, and " +
                               (timeline.path ? "--time draws one moment" : "without --path there is one image") +
                               ": name the file");
    if (!args.video.empty() && !timeline.path) return core::makeError("--video: needs --path (a sequence of frames)");
    if (!args.strip.empty() && !sequence) return core::makeError("--strip: needs --path (a sequence of frames)");
    if (auto s = checkWritable("--video", args.video); !s) return s;
    for (auto [flag, file] : {std::pair{"--strip", &args.strip},
                              {"--shadow-map-out", &args.shadowMapOut},
                              {"--local-map-out", &args.localMapOut}})
        if (auto s = checkPictureWritable(flag, *file); !s) return s;
    // Every frame's picture is named as the first is (the pattern with another number).
    if (auto s = checkPictureWritable("--out", outFileOf(args, timeline, timeline.frames.front())); !s) return s;
    if (!args.video.empty() && !ffmpegInstalled())
        return core::makeError(
            "--video: ffmpeg is not installed (apt install ffmpeg), write the frames with --out alone");
    return core::Ok{};
}

// A still frame's maps as pictures: --shadow-map-out, --local-map-out.
core::Status writeMaps(const RenderArgs& args, const gl::Renderer& renderer) {
    if (!args.shadowMapOut.empty())
        if (auto s = scene::writePng(renderer.readShadowMap(), args.shadowMapOut); !s)
            return core::makeError("--shadow-map-out: " + s.error());
    if (args.localMapOut.empty()) return core::Ok{};
    const scene::Image maps = renderer.readLocalShadowMaps();
    if (maps.width == 0) return core::makeError("--local-map-out: the view has no local light with a map");
    if (auto s = scene::writePng(maps, args.localMapOut); !s) return core::makeError("--local-map-out: " + s.error());
    return core::Ok{};
}

int runRender(const RenderArgs& args) {
    if (auto s = args.technique.check(/*measuresFrames=*/true, /*takesAuto=*/true); !s) return fail(s.errorInfo());
    if (auto s = args.render.check(); !s) return fail(s.errorInfo());
    if (auto s = args.view.check(); !s) return fail(s.errorInfo());
    if (auto s = args.lights.check(); !s) return fail(s.errorInfo());
    auto timeline = args.timeline.resolve();
    if (!timeline) return fail(timeline.errorInfo());
    const bool sequence = timeline->isSequence();
    if (auto s = checkOutputs(args, *timeline); !s) return fail(s.errorInfo());
    auto sceneData = args.scene.load(/*verbose=*/true, timeline->frames.front().time);
    if (!sceneData) return fail(sceneData.errorInfo());
    scene::Scene& world = *sceneData;
    auto still = args.view.resolve(world, /*sayFraming=*/!timeline->path);
    if (!still) return fail(still.errorInfo());
    if (auto s = timeline->prepareViews(*still, world, !args.view.size.empty()); !s) return fail(s.errorInfo());

    auto context = gl::Context::createHeadless();
    if (!context) return fail(context.errorInfo());
    auto renderer = gl::Renderer::create(world);
    if (!renderer) return fail(renderer.errorInfo());

    auto config = frameConfigOf(args.technique, args.render, args.lights);
    if (!config) return fail(config.errorInfo());
    // Across the frames: held lattices (--stabilize), auto's tracked choice.
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return fail(withFlagName(driver.errorInfo()));
    std::vector<uint32_t> moved;
    // --strip: six frames spread evenly over those drawn, first and last included.
    constexpr size_t kStripFrames = 6;
    std::vector<scene::Image> stripImages;
    std::vector<std::string> stripCaptions;
    auto inStrip = [&](size_t i) {
        const size_t n = timeline->frames.size();
        for (size_t k = 0; k < kStripFrames; ++k)
            if (i == k * (n - 1) / (kStripFrames - 1)) return true;
        return false;
    };
    const auto sequenceStart = std::chrono::steady_clock::now();
    for (size_t i = 0; i < timeline->frames.size(); ++i) {
        const TimedFrame& frame = timeline->frames[i];
        // Everything from this frame's time alone: movers, sun, camera, set-up, every map.
        const auto cpuStart = std::chrono::steady_clock::now();
        moved.clear();
        scene::animate(world, frame.time, &moved);
        if (auto s = (*renderer)->moveInstances(world, moved); !s) return fail(s.errorInfo());
        const double animateMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();
        auto view = timeline->viewAt(*still, world, frame.time, !args.view.size.empty());
        if (!view) return fail(view.errorInfo());
        auto drawn = driver->draw(**renderer, *view);
        if (!drawn) return fail(withFlagName(drawn.errorInfo()));
        const auto readStart = std::chrono::steady_clock::now();
        const scene::Image image = (*renderer)->readColor();
        // The passes and the read-back; the phases before them are reported on their own.
        const double frameMs =
            drawn->milliseconds +
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - readStart).count();
        const frame::PreparedFrame& f = drawn->frame;
        if (timeline->frames.size() == 1) printAutoChoice("auto", f);

        const std::string out = outFileOf(args, *timeline, frame);
        if (sequence || !args.video.empty()) {
            // A sequence's folder is made for it (frames/%04d.png); a single image's must exist.
            if (const auto dir = std::filesystem::path(out).parent_path(); !dir.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(dir, ec);
            }
        }
        if (auto s = scene::writePng(image, out); !s) return fail("--out: " + s.error());
        if (!args.strip.empty() && inStrip(i)) {
            stripImages.push_back(image);
            stripCaptions.push_back(fmt::format("frame {}, t = {:.2f} s", frame.number, frame.time));
        }
        if (!sequence) {
            if (auto s = writeMaps(args, **renderer); !s) return fail(s.errorInfo());
            printFrameReport(args, **context, f, drawn->stats, frameMs);
            fmt::print("wrote {}{}\n", out, args.shadowMapOut.empty() ? "" : " and " + args.shadowMapOut);
            continue;
        }
        fmt::print("frame {:4} ({}/{})  t {:7.3f} s  animate {:.3f} ms  set-up {:.3f} ms  shadow {:.2f} M / main "
                   "{:.2f} M tris  "
                   "{:.0f} ms  -> {}\n",
                   frame.number, i + 1, timeline->frames.size(), frame.time, animateMs, f.setupMilliseconds,
                   static_cast<double>(drawn->stats.shadow.triangles) * 1e-6,
                   static_cast<double>(drawn->stats.main.triangles) * 1e-6, frameMs, out);
        std::fflush(stdout);
    }
    if (sequence)
        fmt::print("wrote {} frames in {:.1f} s\n", timeline->frames.size(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - sequenceStart).count());
    if (!args.strip.empty()) {
        if (auto s = scene::writePng(imaging::captionedGrid(stripImages, stripCaptions, 3), args.strip); !s)
            return fail("--strip: " + s.error());
        fmt::print("wrote {}\n", args.strip);
    }
    if (!args.video.empty()) {
        if (auto s = encodeVideo(args.out, timeline->frames.front().number, timeline->framesPerSecond, args.video); !s)
            return fail(s.errorInfo());
        fmt::print("wrote {}\n", args.video);
    }
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
    args->timeline.addTo(*cmd);
    args->lights.addTo(*cmd);
    cmd->add_option("--out", args->out,
                    "output PNG; for a path's frames (--path) a pattern with the frame number, e.g. frames/%04d.png")
        ->capture_default_str();
    cmd->add_option("--shadow-map-out", args->shadowMapOut,
                    "also write the shadow map itself as a PNG (single frames)");
    cmd->add_option("--local-map-out", args->localMapOut,
                    "also write the local lights' maps as a PNG: spot maps, then each cube unfolded (single frames)");
    cmd->add_option("--video", args->video, "with --path: also encode the frames into this video (needs ffmpeg)");
    cmd->add_option("--strip", args->strip,
                    "with --path: also write six of the frames, evenly spread, as one captioned PNG");
    return {cmd, [args] { return runRender(*args); }};
}

} // namespace shadowkit::app
