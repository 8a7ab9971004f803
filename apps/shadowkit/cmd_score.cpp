// shadowkit score: any renderer's shadows against the ray-traced truth. A shadow mask another
// engine drew (PNG of 8 or 16 bits, or .npy visibility) from a standard view or a camera given
// as JSON, of a scene shadowkit can load, is scored as `eval` scores its own rasterised term
// (eval/score.h): the same figures, error map and JSON keys. No GL: the truth is ray traced.
#include "camera_file.h"
#include "commands.h"
#include "local_light_options.h"
#include "options.h"

#include "shadowkit/core/light_size.h"
#include "shadowkit/eval/maps.h"
#include "shadowkit/eval/ray_scene.h"
#include "shadowkit/eval/report.h"
#include "shadowkit/eval/score.h"
#include "shadowkit/eval/soft_truth.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <variant>

namespace shadowkit::app {
namespace {

struct ScoreArgs {
    std::string mask;
    SceneOptions scene;
    ViewOptions view;
    std::string camera;      // --camera FILE: the engine's camera (and sun) as JSON
    LocalLightOptions light; // --light: the spot or point light the mask shows, not the sun
    double sunAngle = 0.0;   // --sun-angle: also against the sun disk's soft truth
    int softSamples = eval::SoftTruthOptions{}.samples;
    double threshold = eval::CompareOptions{}.shadowThreshold;
    std::string json, errorMap;
};

// The view the mask was drawn from: --view (and its flags), with --camera's camera and sun over
// it; the image's size from --size, --camera's, or the view's.
core::Result<scene::ResolvedView> viewOf(const ScoreArgs& args, const std::optional<CameraFile>& file,
                                         const scene::Scene& world, const eval::ShadowMask& mask) {
    auto view = args.view.resolve(world);
    if (!view) return view.errorInfo();
    if (!file) return view;
    if (file->width) {
        view->width = *file->width;
        view->height = *file->height;
    } else if (args.view.size.empty()) {
        view->width = mask.width; // the camera alone does not say: the mask's own size
        view->height = mask.height;
    }
    const double aspect = double(view->width) / double(view->height);
    if (file->camera.aspect != 0.0 && std::abs(file->camera.aspect - aspect) > 1e-3 * aspect)
        return core::makeError(fmt::format("--camera {}: aspect {:.4f}, but the image is {}×{} ({:.4f})", args.camera,
                                           file->camera.aspect, view->width, view->height, aspect));
    view->camera = file->camera;
    view->camera.aspect = aspect;
    if (file->light) view->light = *file->light;
    return view;
}

// The light the mask shows: --light's (one), or the view's own spot or point light where it has
// no sun and one such light; none for the sun. Fails in one line for anything else.
core::Result<std::optional<LocalLight>> lightOf(const ScoreArgs& args, const scene::ResolvedView& view) {
    auto given = args.light.lights(); // checked before the mask and scene were loaded: one at most
    if (!given) return given.errorInfo();
    if (given->size() == 1) return std::optional<LocalLight>(given->front());
    if (view.sun) return std::optional<LocalLight>();
    if (view.spots.size() + view.points.size() == 1) {
        if (args.sunAngle > 0.0)
            return core::makeError("--sun-angle: the sun's soft truth, but --view " + args.view.view +
                                   " has no sun: its light is scored against its hard truth");
        return std::optional<LocalLight>(view.spots.empty() ? LocalLight(view.points[0]) : LocalLight(view.spots[0]));
    }
    return core::makeError("--view: " + args.view.view +
                           " has no sun: give --light for the spot or point light the mask shows");
}

int runScore(const ScoreArgs& args) {
    if (auto s = core::validateSunAngle(args.sunAngle); !s) return fail("--sun-angle: " + s.error());
    if (!(args.threshold > 0.0 && args.threshold <= 1.0)) return fail("--threshold: must be in (0, 1]");
    if (args.softSamples < 1 || args.softSamples > 4096) return fail("--soft-samples: must be in [1, 4096]");
    if (auto s = checkJsonWritable("--json", args.json); !s) return fail(s.errorInfo());
    if (auto s = checkPictureWritable("--error-map", args.errorMap); !s) return fail(s.errorInfo());
    if (auto s = args.scene.check(); !s) return fail(s.errorInfo());
    if (auto s = args.view.check(); !s) return fail(s.errorInfo());
    if (auto s = args.light.check(); !s) return fail(s.errorInfo());
    if (args.light.specs.size() > 1) return fail("--light: a mask shows one light's shadows: give one --light");
    if (!args.light.specs.empty() && args.sunAngle > 0.0)
        return fail("--sun-angle: the sun's soft truth, but a --light mask is scored against its light's hard truth");
    auto mask = eval::loadShadowMask(args.mask);
    if (!mask) return fail(mask.errorInfo());
    std::optional<CameraFile> camera;
    if (!args.camera.empty()) {
        auto file = loadCameraFile(args.camera);
        if (!file) return fail(file.errorInfo());
        camera = *file;
    }
    auto world = args.scene.load();
    if (!world) return fail(world.errorInfo());
    auto view = viewOf(args, camera, *world, *mask);
    if (!view) return fail(view.errorInfo());
    auto local = lightOf(args, *view);
    if (!local) return fail(local.errorInfo());
    if (mask->width != view->width || mask->height != view->height)
        return fail(fmt::format("{}: {}×{} pixels, but the view is {}×{}: render the mask at the view's size, or give "
                                "--size {}x{}",
                                args.mask, mask->width, mask->height, view->width, view->height, mask->width,
                                mask->height));

    const auto start = std::chrono::steady_clock::now();
    auto rays = eval::RayScene::build(*world);
    if (!rays) return fail(rays.errorInfo());
    eval::TruthBuffers truth = eval::computeTruth(**rays, view->camera, view->light, view->width, view->height);
    // A local light's truth at the same surfaces: lit where it reaches them (range, cone, facing)
    // and the segment to it is free; the pixels it does not reach are not scored.
    if (*local) truth = std::visit([&](const auto& light) { return eval::underLight(**rays, truth, light); }, **local);
    eval::ScoreOptions options;
    options.compare.shadowThreshold = args.threshold;
    auto scored = eval::scoreMask(*mask, truth, options);
    if (!scored) return fail(args.mask + ": " + scored.error());

    const std::string viewName = args.camera.empty() ? args.view.view : "camera"; // --camera's, not the view's
    eval::ScoreReport report{args.mask,    viewName,        args.scene.scene, view->width,
                             view->height, scored->figures, truth.seconds,    std::nullopt};
    std::optional<eval::SoftTruth> soft;
    if (args.sunAngle > 0.0) {
        soft = eval::computeSoftTruth(**rays, truth, {-view->light.wsDirection, args.sunAngle},
                                      {.samples = args.softSamples});
        report.soft = eval::compareSoft(mask->visibility, *soft, scored->classes, args.sunAngle);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const eval::Figures& f = scored->figures;
    fmt::print("{:<14} {:<24} {:>9} {:>8} {:>7} {:>8} {:>8} {:>6}\n", "view", "mask", "valid_px", "excl_px", "wrong%",
               "fshadow%", "flit%", "sec");
    fmt::print("{:<14} {:<24} {:>9} {:>8} {:>7.2f} {:>8.2f} {:>8.2f} {:>6.1f}\n", viewName,
               std::filesystem::path(args.mask).filename().string(), f.validPx, f.excludedPx, f.wrongPct,
               f.falseShadowPct, f.falseLitPct, seconds);
    if (const std::string warning = eval::nothingComparedWarning(viewName, f); !warning.empty()) warn(warning);
    if (const auto& s = report.soft)
        fmt::print("  soft truth, sun {:.2f}°: {}\n", s->sunAngleDegrees, eval::softFiguresLine(*s));
    if (!args.errorMap.empty()) {
        if (auto s = scene::writePng(eval::errorMapImage(*scored, view->width, view->height), args.errorMap); !s)
            return fail("--error-map: " + s.error());
        if (soft) {
            const std::filesystem::path hard(args.errorMap);
            const auto softFile = hard.parent_path() / (hard.stem().string() + "-soft" + hard.extension().string());
            if (auto s = scene::writePng(eval::softErrorMapImage(mask->visibility, *soft, *scored), softFile); !s)
                return fail("--error-map: " + s.error());
        }
    }
    if (!args.json.empty())
        if (auto s = writeTextFile("--json", args.json, eval::scoreReportJson(report)); !s) return fail(s.errorInfo());
    return 0;
}

} // namespace

Command addScoreCommand(CLI::App& app) {
    auto args = std::make_shared<ScoreArgs>();
    CLI::App* cmd = app.add_subcommand(
        "score", "Score any renderer's shadows against the ray-traced truth: a mask it drew (PNG or .npy visibility, "
                 "1 lit ... 0 shadowed) from a standard view or a --camera");
    cmd->add_option("mask", args->mask,
                    "the mask: PNG of 8 or 16 bits (grey, or the red channel; alpha 0 where nothing was drawn) or "
                    ".npy (float visibility, or uint8/uint16 levels), the image's top row first")
        ->required();
    args->scene.addTo(*cmd);
    args->view.addTo(*cmd);
    cmd->add_option("--camera", args->camera,
                    "the camera the mask was drawn from, as JSON: what `shadowkit setup` prints, or {\"eye\", "
                    "\"direction\", \"up\", \"fov_y_degrees\", \"near\", \"far\"[, \"aspect\", \"width\", "
                    "\"height\"]}, with an optional \"light\": {\"direction\"} (else --view's sun and flags)");
    cmd->add_option("--light", args->light.specs,
                    "the mask shows this spot or point light's shadows instead of the sun's, scored against its "
                    "hard truth where it reaches: point:x,y,z[,range] or spot:x,y,z,dx,dy,dz,angle[,range] "
                    "(degrees, metres; range 30 m unless given); a view with no sun and one such light of its own "
                    "scores that one");
    cmd->add_option("--sun-angle", args->sunAngle,
                    "the sun's angular diameter in degrees (the real sun: 0.53): also the figures against the sun "
                    "disk's soft truth")
        ->capture_default_str();
    cmd->add_option("--soft-samples", args->softSamples, "--sun-angle: shadow rays a penumbra point takes")
        ->capture_default_str();
    cmd->add_option("--threshold", args->threshold, "a mask value at or above this counts as lit")
        ->capture_default_str();
    cmd->add_option("--json", args->json, "write the figures as JSON (eval's keys, under \"scores\")");
    cmd->add_option("--error-map", args->errorMap,
                    "write the error map (PNG, eval's colours; with --sun-angle also NAME-soft.png)");
    return {cmd, [args] { return runScore(*args); }};
}

} // namespace shadowkit::app
