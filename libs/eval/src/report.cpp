#include "shadowkit/eval/report.h"

#include "shadowkit/eval/npy.h"
#include "shadowkit/scene/file_write.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace shadowkit::eval {

nlohmann::json virtualPagesJson(const VirtualPagesReport& v) {
    nlohmann::json json = {{"pages_requested", v.pagesRequested},
                           {"pages_rendered", v.pagesRendered},
                           {"pages_resident", v.pagesResident},
                           {"pages_fell_back", v.pagesFellBack},
                           {"pages_deferred", v.pagesDeferred},
                           {"levels_behind", v.levelsBehind},
                           {"lag_frames", v.lagFrames},
                           {"requests_age", v.requestsAge},
                           {"pool_pages", v.poolPages},
                           {"pool_bytes", v.poolBytes},
                           {"shadow_triangles", v.shadowTriangles}};
    json["opacity_bytes"] = v.opacityBytes; // the opacity layers' atlases (--foliage-opacity)
    return json;
}

namespace {

// The figures against a soft truth, as JSON keys (the light's size is its caller's).
nlohmann::json softJson(const SoftFigures& s) {
    return {{"soft_compared_px", s.comparedPx},
            {"penumbra_px", s.penumbraPx},
            {"soft_mae", s.softMae},
            {"penumbra_mae", s.penumbraMae},
            {"soft_wrong_pct", s.softWrongPct},
            {"soft_truth_seconds", s.truthSeconds},
            {"penumbra_width_ratio", s.penumbraWidthRatio}};
}

} // namespace

std::string reportJson(const std::vector<ViewReport>& views) {
    nlohmann::json list = nlohmann::json::array();
    for (const ViewReport& v : views) {
        const Figures& f = v.figures;
        list.push_back({
            {"view", v.view},
            {"technique", v.technique},
            {"scene", v.scene},
            {"seed", v.seed},
            {"width", v.width},
            {"height", v.height},
            {"map_size", v.mapSize},
            {"maps", v.maps},
            {"bias_slope", v.bias.slope},
            {"bias_constant", v.bias.constant},
            {"normal_offset", v.bias.normalOffset},
            {"normal_offset_footprint", v.bias.normalOffsetFootprint},
            {"receiver_plane_bias", v.bias.receiverPlane},
            {"offset_guard", v.bias.offsetGuard},
            {"cull", v.bias.cull == core::CasterCull::None           ? "none"
                     : v.bias.cull == core::CasterCull::Back         ? "back"
                     : v.bias.cull == core::CasterCull::BackOfClosed ? "closed"
                                                                     : "front"},
            {"filter", v.filter},
            {"blur_iterations", v.blurIterations},
            {"foliage_opacity", v.foliageOpacity},
            {"fallbacks", v.fallbacks},
            {"depth_tolerance", v.depthTolerance},
            {"valid_px", f.validPx},
            {"excluded_px", f.excludedPx},
            {"wrong_pct", f.wrongPct},
            {"false_shadow_pct", f.falseShadowPct},
            {"false_lit_pct", f.falseLitPct},
            {"undersampled_pct", f.undersampledPct},
            {"pixels_per_texel_p50", f.pixelsPerTexelP50},
            {"pixels_per_texel_p95", f.pixelsPerTexelP95},
            {"pixels_per_texel_p99", f.pixelsPerTexelP99},
            {"seconds", v.seconds},
            {"truth_seconds", v.truthSeconds},
            {"truth_rays_per_second", v.truthRaysPerSecond},
        });
        if (v.visibleDepth) list.back()["visible_depth"] = {v.visibleDepth->x, v.visibleDepth->y};
        if (!v.autoChoice.empty()) list.back()["auto_choice"] = v.autoChoice;
        if (v.virtualPages) list.back()["virtual"] = virtualPagesJson(*v.virtualPages);
        if (v.soft) {
            list.back().update(softJson(*v.soft));
            list.back()["sun_angle_deg"] = v.soft->sunAngleDegrees;
        }
        if (!v.lights.empty()) {
            nlohmann::json lights = nlohmann::json::array();
            for (const LightReport& l : v.lights) {
                lights.push_back({{"light", l.light},
                                  {"maps", l.maps},
                                  {"skipped_faces", l.skippedFaces},
                                  {"valid_px", l.figures.validPx},
                                  {"wrong_pct", l.figures.wrongPct},
                                  {"false_shadow_pct", l.figures.falseShadowPct},
                                  {"false_lit_pct", l.figures.falseLitPct},
                                  {"undersampled_pct", l.figures.undersampledPct},
                                  {"pixels_per_texel_p50", l.figures.pixelsPerTexelP50},
                                  {"pixels_per_texel_p95", l.figures.pixelsPerTexelP95},
                                  {"pixels_per_texel_p99", l.figures.pixelsPerTexelP99}});
                if (l.soft) {
                    lights.back().update(softJson(*l.soft));
                    lights.back()["radius_m"] = l.radiusMetres;
                }
            }
            list.back()["lights"] = lights;
        }
    }
    return nlohmann::json{{"views", list}}.dump(2) + "\n";
}

std::string nothingComparedWarning(const std::string& view, const Figures& figures) {
    if (figures.validPx > 0) return {};
    return "view " + view +
           ": no pixel was compared (none shows a sunlit surface that raster and ray agree on): its figures measure "
           "nothing";
}

std::string mostlyLeftOutWarning(const std::string& view, const Figures& figures) {
    if (figures.validPx == 0 || figures.excludedPx <= figures.validPx) return {};
    const double leftOut = 100.0 * double(figures.excludedPx) / double(figures.excludedPx + figures.validPx);
    char shares[64];
    std::snprintf(shares, sizeof shares, "%.0f %% of its sunlit pixels", leftOut);
    return "view " + view + ": " + shares +
           " were left out (raster and ray tracer show different surfaces there): its figures measure the rest";
}

std::string nothingComparedAlongWarning(const std::string& path, size_t none, size_t frames) {
    if (none == 0) return {};
    return "--path " + path + ": " + std::to_string(none) + " of " + std::to_string(frames) +
           " frames compared no pixel (their camera sees no sunlit surface that raster and ray agree on: a path whose "
           "keys are written for another scene: \"on_loaded_scene\": \"frame\" frames a loaded one), and their 0.00 % "
           "counts in the means";
}

std::string nothingComparedInTimeWarning(const std::string& path, size_t none, size_t frames) {
    if (none == 0) return {};
    return "--path " + path + ": " + std::to_string(none) + " of " + std::to_string(frames) +
           " frames after the first compared no pixel with the frame before (none of their sunlit points was in "
           "view there on a surface that kept its shape: a cut, or only skinned or morphed surfaces, whose own "
           "pixels are not compared), and their flicker of 0 counts in the means";
}

std::string softFiguresLine(const SoftFigures& s) {
    // A width of 0 is a hard test or filter, which draws no penumbra at all: said in words, as
    // "×0.00" alone reads like a fault.
    char width[64];
    if (std::isnan(s.penumbraWidthRatio)) // no truth pixel between 10 and 90 % lit: nothing to compare a width with
        std::snprintf(width, sizeof width, "no penumbra in the truth");
    else if (s.penumbraWidthRatio == 0.0)
        std::snprintf(width, sizeof width, "penumbrae drawn hard (width ×0)");
    else
        std::snprintf(width, sizeof width, "penumbra width ×%.2f", s.penumbraWidthRatio);
    char text[256];
    std::snprintf(text, sizeof text, "soft_mae %.4f, penumbra_mae %.3f over %lld px, soft_wrong%% %.2f, %s (%.1f s)",
                  s.softMae, s.penumbraMae, static_cast<long long>(s.penumbraPx), s.softWrongPct, width,
                  s.truthSeconds);
    return text;
}

std::string scoreReportJson(const ScoreReport& r) {
    const Figures& f = r.figures;
    nlohmann::json score = {{"mask", r.mask},
                            {"view", r.view},
                            {"scene", r.scene},
                            {"width", r.width},
                            {"height", r.height},
                            {"valid_px", f.validPx},
                            {"excluded_px", f.excludedPx},
                            {"wrong_pct", f.wrongPct},
                            {"false_shadow_pct", f.falseShadowPct},
                            {"false_lit_pct", f.falseLitPct},
                            {"truth_seconds", r.truthSeconds}};
    if (r.soft) {
        score.update(softJson(*r.soft));
        score["sun_angle_deg"] = r.soft->sunAngleDegrees;
    }
    return nlohmann::json{{"scores", nlohmann::json::array({score})}}.dump(2) + "\n";
}

core::Status writeReportJson(const std::vector<ViewReport>& views, const std::filesystem::path& file) {
    return scene::writeFile(file, reportJson(views));
}

core::Status dumpBuffers(const std::filesystem::path& dir, const core::RasterBuffers& raster, const TruthBuffers& truth,
                         const Comparison& comparison, const SoftTruth* soft) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return core::makeError(dir.string() + ": cannot create directory (" + ec.message() + ")");
    const size_t h = static_cast<size_t>(raster.height), w = static_cast<size_t>(raster.width);
    auto flat = [](const auto& vectors) {
        std::vector<float> out;
        for (const auto& v : vectors)
            for (int k = 0; k < v.length(); ++k) out.push_back(static_cast<float>(v[k]));
        return out;
    };
    std::vector<uint8_t> classes(comparison.classes.size());
    for (size_t i = 0; i < classes.size(); ++i) classes[i] = static_cast<uint8_t>(comparison.classes[i]);
    for (auto status :
         {writeNpy(dir / "shadow_term.npy", std::span<const float>(raster.shadowTerm), {h, w}),
          writeNpy(dir / "truth_lit.npy", std::span<const uint8_t>(truth.lit), {h, w}),
          writeNpy(dir / "class.npy", std::span<const uint8_t>(classes), {h, w}),
          writeNpy(dir / "world_position.npy", std::span<const float>(flat(truth.wsPosition)), {h, w, 3}),
          writeNpy(dir / "normal.npy", std::span<const float>(flat(raster.wsNormal)), {h, w, 3}),
          writeNpy(dir / "truth_normal.npy", std::span<const float>(flat(truth.wsNormal)), {h, w, 3}),
          writeNpy(dir / "pixels_per_texel.npy", std::span<const float>(comparison.pixelsPerTexel), {h, w}),
          writeNpy(dir / "surface_id.npy", std::span<const uint32_t>(raster.surfaceId), {h, w})})
        if (!status) return status;
    if (soft)
        for (auto status :
             {writeNpy(dir / "soft_visibility.npy", std::span<const float>(soft->visibility), {h, w}),
              writeNpy(dir / "soft_standard_error.npy", std::span<const float>(soft->standardError), {h, w})})
            if (!status) return status;
    return core::Ok{};
}

} // namespace shadowkit::eval
