#include "shadowkit/measure/path_report.h"

#include "shadowkit/eval/report.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace shadowkit::measure {
namespace {

nlohmann::json toJson(const PathReport::Summary& s) { return {{"mean", s.mean}, {"p95", s.p95}, {"max", s.max}}; }

nlohmann::json frameJson(const PathRow& r) {
    nlohmann::json j = {{"frame", r.frame},
                        {"time_s", r.time},
                        {"valid_px", r.figures.validPx},
                        {"wrong_pct", r.figures.wrongPct},
                        {"pixels_per_texel_p50", r.figures.pixelsPerTexelP50},
                        {"shadow_triangles", r.shadowTriangles}};
    if (r.temporal)
        j.update({{"compared_px", r.temporal->comparedPx},
                  {"flicker_pct", r.temporal->flickerPct},
                  {"truth_change_pct", r.temporal->truthChangePct}});
    if (r.temporal && r.temporal->levelPops) {
        const eval::LevelPops& p = *r.temporal->levelPops;
        j["level_pops"] = {
            {"drawn_px", p.drawnPx}, {"pop_pct", p.popPct}, {"surface_pct", p.surfacePct}, {"shadow_pct", p.shadowPct}};
    }
    if (r.refittedViews) j["refitted_views"] = *r.refittedViews;
    if (r.soft)
        j.update({{"soft_mae", r.soft->softMae},
                  {"penumbra_mae", r.soft->penumbraMae},
                  {"penumbra_px", r.soft->penumbraPx},
                  {"sun_angle_deg", r.soft->sunAngleDegrees}});
    if (r.autoChoice) j.update({{"auto_choice", *r.autoChoice}, {"auto_ms", r.autoMilliseconds}});
    if (const auto& v = r.virtualPages) j["virtual"] = eval::virtualPagesJson(virtualPagesReport(*v));
    return j;
}

} // namespace

const PathRow& PathReport::add(int number, double time, const PathFrame& measured, double seconds) {
    const frame::PreparedFrame& prepared = measured.frame;
    m_technique = core::techniqueName(prepared.setup.technique);
    PathRow row{number, time, measured.measurement.figures()};
    row.temporal = measured.temporal;
    row.virtualPages = measured.measurement.virtualPages;
    row.shadowTriangles = measured.measurement.shadowPass.triangles;
    row.soft = measured.measurement.soft;
    if (prepared.refits) {
        m_refitFrames += prepared.refits->views > 0;
        m_toCover += prepared.refits->toCover, m_stale += prepared.refits->stale;
        row.refittedViews = prepared.refits->views;
    }
    if (prepared.autoChoice) {
        row.autoChoice = core::describe(*prepared.autoChoice);
        row.autoMilliseconds = prepared.autoMilliseconds;
        m_autoChosen.push_back(prepared.inputs);
    }
    row.seconds = seconds;
    m_rows.push_back(std::move(row));
    return m_rows.back();
}

PathReport::Summary PathReport::summarise(std::vector<double> v) {
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    Summary s;
    for (const double x : v) s.mean += x / double(v.size());
    s.p95 = v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.95 * double(v.size()))) - 1)];
    s.max = v.back();
    return s;
}

std::string PathReport::technique() const { return m_automatic ? "auto" : m_technique; }

PathReport::Summary PathReport::flicker() const {
    std::vector<double> v;
    for (const PathRow& r : m_rows)
        if (r.temporal) v.push_back(r.temporal->flickerPct);
    return summarise(v);
}

PathReport::Summary PathReport::truthChange() const {
    std::vector<double> v;
    for (const PathRow& r : m_rows)
        if (r.temporal) v.push_back(r.temporal->truthChangePct);
    return summarise(v);
}

std::optional<PathReport::Summary> PathReport::levelPops() const {
    std::vector<double> v;
    for (const PathRow& r : m_rows)
        if (r.temporal && r.temporal->levelPops) v.push_back(r.temporal->levelPops->popPct);
    if (v.empty()) return std::nullopt;
    return summarise(v);
}

PathReport::Summary PathReport::wrong() const {
    std::vector<double> v;
    for (const PathRow& r : m_rows) v.push_back(r.figures.wrongPct);
    return summarise(v);
}

PathReport::Summary PathReport::autoMilliseconds() const {
    std::vector<double> v;
    for (size_t i = 1; i < m_rows.size() && m_automatic; ++i) v.push_back(m_rows[i].autoMilliseconds);
    return summarise(v);
}

std::vector<double> PathReport::softValues(double eval::SoftFigures::*field) const {
    std::vector<double> v;
    for (const PathRow& r : m_rows)
        if (r.soft) v.push_back((*r.soft).*field);
    return v;
}

int PathReport::familySwitches() const {
    int switches = 0;
    for (size_t i = 1; i < m_autoChosen.size(); ++i) {
        const core::ShadowSetupInputs &a = m_autoChosen[i - 1], &b = m_autoChosen[i];
        const bool csm = b.technique == core::Technique::Csm;
        switches += a.technique != b.technique ||
                    (csm && (a.cascades.count != b.cascades.count || a.cascades.warp != b.cascades.warp));
    }
    return switches;
}

std::string PathReport::summaryText() const {
    std::string text;
    const size_t frames = m_rows.size();
    if (m_automatic && frames > 0) {
        const Summary ms = autoMilliseconds();
        text += fmt::format("--technique auto: the family changed in {} of {} frames; the choice took {:.2f} ms on the "
                            "first frame (the full search), then mean {:.3f} p95 {:.3f} max {:.3f} ms (CPU: model + "
                            "search, not the read-back)\n",
                            familySwitches(), frames, m_rows.front().autoMilliseconds, ms.mean, ms.p95, ms.max);
    }
    if (m_held)
        text += fmt::format(
            "--stabilize: the set-up was refitted in {} of {} frames ({} maps to cover the view, {} grown stale)\n",
            m_refitFrames, frames, m_toCover, m_stale);
    const Summary fl = flicker(), tc = truthChange(), wr = wrong();
    text += fmt::format("{} along {} ({} frames): flicker_pct mean {:.3f} p95 {:.3f} max {:.3f} | truth_change_pct "
                        "mean {:.3f} p95 {:.3f} max {:.3f} | wrong_pct mean {:.3f}\n",
                        technique(), m_path, frames, fl.mean, fl.p95, fl.max, tc.mean, tc.p95, tc.max, wr.mean);
    if (const std::optional<Summary> pops = levelPops())
        text +=
            fmt::format("  levels of detail: level_pop_pct mean {:.3f} p95 {:.3f} max {:.3f} (pixels whose surface or "
                        "shadow changed only because the levels changed since the frame before)\n",
                        pops->mean, pops->p95, pops->max);
    const std::vector<double> sunAngles = softValues(&eval::SoftFigures::sunAngleDegrees);
    if (sunAngles.empty()) return text;
    // A path's sun keys may change the sun's size (and to 0, where a frame has no soft truth).
    const auto [smallest, largest] = std::minmax_element(sunAngles.begin(), sunAngles.end());
    const std::string sunSize = *smallest == *largest ? fmt::format("sun {:.2f}°", *smallest)
                                                      : fmt::format("{} of {} frames, sun {:.2f}–{:.2f}°",
                                                                    sunAngles.size(), frames, *smallest, *largest);
    const Summary sm = summarise(softValues(&eval::SoftFigures::softMae)),
                  pm = summarise(softValues(&eval::SoftFigures::penumbraMae));
    text += fmt::format("  soft truth, {}: soft_mae mean {:.4f} p95 {:.4f} max {:.4f} | penumbra_mae mean {:.3f} "
                        "p95 {:.3f} max {:.3f}\n",
                        sunSize, sm.mean, sm.p95, sm.max, pm.mean, pm.p95, pm.max);
    return text;
}

std::string PathReport::csv() const {
    std::string out = "frame,time_s,valid_px,wrong_pct,false_shadow_pct,false_lit_pct,pixels_per_texel_p50,compared_"
                      "px,flicker_pct,truth_change_pct,refitted_views,soft_mae,penumbra_mae,sun_angle_deg\n";
    for (const PathRow& r : m_rows) {
        out += fmt::format("{},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g}", r.frame, r.time, r.figures.validPx,
                           r.figures.wrongPct, r.figures.falseShadowPct, r.figures.falseLitPct,
                           r.figures.pixelsPerTexelP50);
        out += r.temporal ? fmt::format(",{},{:.6g},{:.6g}", r.temporal->comparedPx, r.temporal->flickerPct,
                                        r.temporal->truthChangePct)
                          : std::string(",,,");
        out += r.refittedViews ? fmt::format(",{}", *r.refittedViews) : std::string(",");
        out += r.soft ? fmt::format(",{:.6g},{:.6g},{:.6g}\n", r.soft->softMae, r.soft->penumbraMae,
                                    r.soft->sunAngleDegrees)
                      : std::string(",,,\n");
    }
    return out;
}

nlohmann::json PathReport::json() const {
    nlohmann::json frames = nlohmann::json::array();
    for (const PathRow& r : m_rows) frames.push_back(frameJson(r));
    nlohmann::json root = {{"path", m_path},
                           {"technique", technique()},
                           {"refits", m_held ? nlohmann::json(m_refitFrames) : nlohmann::json(nullptr)},
                           {"summary",
                            {{"flicker_pct", toJson(flicker())},
                             {"truth_change_pct", toJson(truthChange())},
                             {"wrong_pct", toJson(wrong())}}},
                           {"frames", frames}};
    if (const std::optional<Summary> pops = levelPops()) root["summary"]["level_pop_pct"] = toJson(*pops);
    const std::vector<double> sunAngles = softValues(&eval::SoftFigures::sunAngleDegrees);
    if (!sunAngles.empty()) {
        root["summary"]["soft_mae"] = toJson(summarise(softValues(&eval::SoftFigures::softMae)));
        root["summary"]["penumbra_mae"] = toJson(summarise(softValues(&eval::SoftFigures::penumbraMae)));
        const auto [smallest, largest] = std::minmax_element(sunAngles.begin(), sunAngles.end());
        root["sun_angle_deg"] = {{"min", *smallest}, {"max", *largest}};
    }
    if (m_automatic && !m_rows.empty())
        root["auto"] = {{"family_switches", familySwitches()},
                        {"first_frame_ms", m_rows.front().autoMilliseconds},
                        {"ms", toJson(autoMilliseconds())}};
    return root;
}

} // namespace shadowkit::measure
