// Reports of an evaluation: the JSON file of `shadowkit eval --json` and the per-pixel
// dump of `--dump` (docs/commands.md, "shadowkit eval").
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/eval/truth.h"

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::eval {

// One light's figures in a view with several (the sun, "point[0]", "spot[1]", ...).
struct LightReport {
    std::string light;
    int maps = 1;         // maps drawn: cube faces kept for a point light
    int skippedFaces = 0; // point lights: faces that saw nothing of the view
    Figures figures;
    // A lamp with a size: its radius and the figures against its soft truth (JSON: "radius_m",
    // "soft_compared_px", "penumbra_px", "soft_mae", "penumbra_mae", "soft_wrong_pct", "penumbra_width_ratio",
    // "soft_truth_seconds").
    double radiusMetres = 0.0;
    std::optional<SoftFigures> soft;
};

// Technique virtual: a frame's pages (gl::VirtualPageStats, which eval does not see).
struct VirtualPagesReport {
    int pagesRequested = 0, pagesRendered = 0, pagesResident = 0, pagesFellBack = 0;
    int pagesDeferred = 0; // over the page budget, not drawn this frame
    int levelsBehind = 0;  // page budget: levels shown from the older generation of pages
    int lagFrames = 0;     // page budget: frames since the oldest sun shown was the current one
    int requestsAge = 0;   // frames since the requests read were marked (0: the frame's own; −1: none)
    int poolPages = 0;
    int64_t poolBytes = 0;
    int64_t opacityBytes = 0;   // the opacity layers' atlases (--foliage-opacity), 0 without
    size_t shadowTriangles = 0; // drawn into the pages rendered
};

struct ViewReport {
    std::string view;
    std::string technique;
    std::string scene; // "forest" or the file
    uint64_t seed = 0;
    int width = 0, height = 0;
    int mapSize = 0; // texels per side
    int maps = 1;    // shadow maps in the set-up
    core::BiasSettings bias;
    std::string filter = "hard"; // as given to --filter
    int blurIterations = 0;
    bool foliageOpacity = false; // leaves cast through opacity layers (--foliage-opacity)
    std::vector<std::string> fallbacks;
    std::string autoChoice; // "auto_choice": what --technique auto chose, with its parameters (else left out)
    std::optional<core::Vec2> visibleDepth; // the visible view-depth range the set-up used, when one was given
    double depthTolerance = CompareOptions{}.depthTolerance; // "depth_tolerance": raster and ray agree (metrics.h)
    Figures figures;                 // every light together (eval::combine); the sun's alone in a sunlit view
    std::vector<LightReport> lights; // per light, when the view has spot or point lights
    double seconds = 0.0;            // wall time of this view's evaluation
    // Computing the sun's truth (eval::TruthBuffers::seconds, rays): "truth_seconds",
    // "truth_rays_per_second" (primary and shadow rays).
    double truthSeconds = 0.0, truthRaysPerSecond = 0.0;
    std::optional<VirtualPagesReport> virtualPages; // "virtual": technique virtual's pages
    // Against the soft truth (eval --sun-angle): "sun_angle_deg", "soft_compared_px", "penumbra_px",
    // "soft_mae", "penumbra_mae", "soft_wrong_pct", "penumbra_width_ratio", "soft_truth_seconds".
    std::optional<SoftFigures> soft;
};

// {"pages_requested", ..., "shadow_triangles"}: the "virtual" object of a view or a path's frame.
nlohmann::json virtualPagesJson(const VirtualPagesReport& pages);

// {"views": [{view, technique, ..., valid_px, excluded_px, wrong_pct, ...}, ...]}
std::string reportJson(const std::vector<ViewReport>& views);
core::Status writeReportJson(const std::vector<ViewReport>& views, const std::filesystem::path& file);

// A mask another renderer drew, scored against the truth (`shadowkit score --json`): eval's
// keys for the same figures, no map's — {"scores": [{"mask", "view", "scene", "width",
// "height", "valid_px", "excluded_px", "wrong_pct", "false_shadow_pct", "false_lit_pct",
// "truth_seconds", and with a sun of some size "sun_angle_deg" and the soft keys above}]}.
struct ScoreReport {
    std::string mask, view, scene;
    int width = 0, height = 0;
    Figures figures;
    double truthSeconds = 0.0;
    std::optional<SoftFigures> soft;
};
std::string scoreReportJson(const ScoreReport& report);

// The soft figures as the command line prints them under a view's row (eval, score): "soft_mae
// 0.0118, penumbra_mae 0.425 over 161 px, soft_wrong% 1.49, penumbra width ×0.93 (0.4 s)"; a
// width of 0 (a hard test) as "penumbrae drawn hard (width ×0)".
std::string softFiguresLine(const SoftFigures& soft);

/// The warning for a view in which no pixel was compared (valid_px 0: the sky, a mask of a pixel
/// or two), whose 0.00 % would read as perfect shadows; empty when some pixel was.
std::string nothingComparedWarning(const std::string& view, const Figures& figures);
/// The warning for a view most of whose sunlit pixels were left out (excluded_px above
/// valid_px: raster and ray tracer showed different surfaces there — levels of detail far from
/// the full geometry, a surface drawn from the side the file did not mean), whose figures then
/// measure the smaller part of what is seen; empty when half or more was compared, or none
/// (nothingComparedWarning's case).
std::string mostlyLeftOutWarning(const std::string& view, const Figures& figures);
/// The same along a camera path: `none` of its `frames` compared no pixel (a path made for the
/// forest sees nothing of a small loaded scene), and their 0.00 % count in the path's means;
/// empty when every frame compared some.
std::string nothingComparedAlongWarning(const std::string& path, size_t none, size_t frames);
/// The same for flicker: `none` of the `frames` that follow another compared no pixel with the
/// frame before although they scored some (a cut, or all they show is surfaces that changed
/// their shape, which are not compared between frames: temporal.h), and their flicker of 0
/// counts in the means; empty when every such frame compared some.
std::string nothingComparedInTimeWarning(const std::string& path, size_t none, size_t frames);

// Writes shadow_term, truth_lit, class, world_position, normal, truth_normal,
// pixels_per_texel and surface_id as .npy files into `dir` (created if missing); with a soft
// truth also soft_visibility and soft_standard_error.
core::Status dumpBuffers(const std::filesystem::path& dir, const core::RasterBuffers& raster, const TruthBuffers& truth,
                         const Comparison& comparison, const SoftTruth* soft = nullptr);

} // namespace shadowkit::eval
