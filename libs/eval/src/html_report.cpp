#include "shadowkit/eval/html_report.h"

#include "shadowkit/eval/maps.h"
#include "shadowkit/scene/file_write.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <sstream>

namespace shadowkit::eval {
namespace {

std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// Each figure's name, meaning and printed form, in one place.
constexpr std::array<FigureMeaning, 9> kMeanings = {{
    {"valid_px", "pixels evaluated: the surface faces the sun and raster and ray tracer agree on it",
     [](const Figures& f) { return std::to_string(f.validPx); }},
    {"excluded_px", "pixels facing the sun where raster and ray tracer see different surfaces (silhouettes)",
     [](const Figures& f) { return std::to_string(f.excludedPx); }},
    {"wrong_pct", "% of valid pixels whose rendered lit/shadowed state differs from the ray-traced truth",
     [](const Figures& f) { return fixed(f.wrongPct, 2); }},
    {"false_shadow_pct", "% rendered shadowed where the truth is lit: acne, aliasing that darkens (red)",
     [](const Figures& f) { return fixed(f.falseShadowPct, 2); }},
    {"false_lit_pct", "% rendered lit where the truth is shadowed: peter-panning, leaks, missed casters (blue)",
     [](const Figures& f) { return fixed(f.falseLitPct, 2); }},
    {"undersampled_pct", "% of valid pixels where one shadow texel covers more than one pixel",
     [](const Figures& f) { return fixed(f.undersampledPct, 2); }},
    {"pixels_per_texel_p50", "median pixels one texel covers along its worst direction; above 1 shows stair steps",
     [](const Figures& f) { return fixed(f.pixelsPerTexelP50, 2); }},
    {"pixels_per_texel_p95", "95th percentile of the same: the coarsest texels most of the screen sees",
     [](const Figures& f) { return fixed(f.pixelsPerTexelP95, 2); }},
    {"pixels_per_texel_p99", "99th percentile of the same: mostly surfaces edge-on to the sun",
     [](const Figures& f) { return fixed(f.pixelsPerTexelP99, 1); }},
}};

// The figures against the soft truth (a sun of some size), likewise.
struct SoftMeaning {
    std::string_view name, meaning;
    std::string (*text)(const SoftFigures&);
};
constexpr std::array<SoftMeaning, 5> kSoftMeanings = {{
    {"sun_angle_deg", "the sun's angular diameter: the disk the soft truth sees (the real sun 0.53)",
     [](const SoftFigures& s) { return fixed(s.sunAngleDegrees, 2); }},
    {"soft_mae",
     "mean absolute difference of the rendered term and the true visible fraction of the sun over the valid pixels",
     [](const SoftFigures& s) { return fixed(s.softMae, 4); }},
    {"penumbra_mae", "the same where the truth is a penumbra (visible fraction in 0.02–0.98)",
     [](const SoftFigures& s) { return fixed(s.penumbraMae, 3); }},
    {"soft_wrong_pct", "% of valid pixels off by more than 0.25",
     [](const SoftFigures& s) { return fixed(s.softWrongPct, 2); }},
    {"penumbra_width_ratio", "rendered penumbrae's width over the true ones' (10–90 % bands): 1 as wide, 0 hard",
     [](const SoftFigures& s) { return fixed(s.penumbraWidthRatio, 2); }},
}};

constexpr std::string_view kStyle = R"(
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 1500px; padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border: 1px solid #ddd; padding: 0.25em 0.6em; text-align: right; }
th:first-child, td:first-child, td.meaning { text-align: left; }
td.meaning { color: #555; font-size: 0.92em; }
.row { display: flex; gap: 0.5em; overflow-x: auto; }
figure { margin: 0; flex: 1 1 0; min-width: 220px; }
figure img { width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
figcaption { font-size: 0.9em; color: #444; }
code, pre { background: #f4f4f4; } pre { padding: 0.5em; white-space: pre-wrap; word-break: break-all; }
.swatch { display: inline-block; width: 0.9em; height: 0.9em; vertical-align: middle; border: 1px solid #999; }
#broken { color: #b00; }
)";

// Counts the images that did not load, for readers and for the browser test.
constexpr std::string_view kScript = R"(
window.addEventListener('load', () => {
  const images = Array.from(document.images);
  const broken = images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'));
  document.body.dataset.images = images.length;
  document.body.dataset.brokenImages = broken.length;
  if (broken.length) document.getElementById('broken').textContent = 'Missing pictures: ' + broken.join(', ');
});
)";

std::string swatch(const uint8_t rgb[3]) {
    return "<span class=\"swatch\" style=\"background: rgb(" + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) +
           "," + std::to_string(rgb[2]) + ")\"></span>";
}

void writeLegend(std::ostringstream& out) {
    using C = ErrorMapColors;
    out << "<p><b>Error map:</b> " << swatch(C::litCorrect) << " lit and correct, " << swatch(C::shadowCorrect)
        << " shadowed and correct, " << swatch(C::falseShadow) << " false shadow, " << swatch(C::falseLit)
        << " false lit, " << swatch(C::excluded) << " excluded (raster and ray disagree on the surface), "
        << swatch(C::notEvaluated) << " not evaluated (sky, or facing away from the sun). "
        << "<b>Aliasing map:</b> pixels per texel on a log scale from 1/64 (dark violet) to 64 (yellow); the white "
           "tick marks 1. <b>Shadows</b> pictures shade the ray tracer's surfaces by the sun alone, with the "
           "rendered or the ray-traced visibility, so they differ exactly where the shadows do.</p>\n";
}

void writeFiguresTable(std::ostringstream& out, const std::vector<const HtmlEntry*>& entries) {
    out << "<table class=\"figures\"><tr><th>figure</th>";
    for (const HtmlEntry* e : entries) out << "<th>" << htmlEscape(e->label) << "</th>";
    out << "<th>what it means</th></tr>\n";
    for (const FigureMeaning& m : kMeanings) {
        out << "<tr><td><code>" << m.name << "</code></td>";
        for (const HtmlEntry* e : entries) out << "<td>" << m.text(e->report.figures) << "</td>";
        out << "<td class=\"meaning\">" << htmlEscape(m.meaning) << "</td></tr>\n";
    }
    if (std::any_of(entries.begin(), entries.end(), [](const HtmlEntry* e) { return e->report.soft.has_value(); }))
        for (const SoftMeaning& m : kSoftMeanings) {
            out << "<tr><td><code>" << m.name << "</code></td>";
            for (const HtmlEntry* e : entries)
                out << "<td>" << (e->report.soft ? m.text(*e->report.soft) : "—") << "</td>";
            out << "<td class=\"meaning\">" << htmlEscape(m.meaning) << "</td></tr>\n";
        }
    out << "</table>\n";
    for (const HtmlEntry* e : entries) {
        if (e->report.lights.empty()) continue;
        out << "<table class=\"lights\"><tr><th>" << htmlEscape(e->label)
            << ": light</th><th>maps</th><th>valid_px</th><th>wrong_pct</th><th>false_shadow_pct</th>"
               "<th>false_lit_pct</th><th>pixels_per_texel_p50</th></tr>\n";
        for (const LightReport& l : e->report.lights)
            out << "<tr><td>" << htmlEscape(l.light) << "</td><td>" << l.maps << "</td><td>" << l.figures.validPx
                << "</td><td>" << fixed(l.figures.wrongPct, 2) << "</td><td>" << fixed(l.figures.falseShadowPct, 2)
                << "</td><td>" << fixed(l.figures.falseLitPct, 2) << "</td><td>"
                << fixed(l.figures.pixelsPerTexelP50, 2) << "</td></tr>\n";
        out << "</table>\n";
    }
}

void writePicture(std::ostringstream& out, const HtmlPicture& p, const std::string& alt) {
    out << "<figure><a href=\"" << htmlEscape(p.file) << "\"><img src=\"" << htmlEscape(p.file) << "\" alt=\""
        << htmlEscape(alt + ", " + p.caption) << "\" loading=\"eager\"></a><figcaption>" << htmlEscape(p.caption)
        << "</figcaption></figure>";
}

std::string settingsText(const ViewReport& r) {
    // A virtual clipmap's levels are not maps of their own: say how many pages it kept.
    const std::string maps = r.virtualPages ? std::to_string(r.maps) + " levels of " + std::to_string(r.mapSize) +
                                                  "² virtual texels, " + std::to_string(r.virtualPages->pagesResident) +
                                                  " pages resident"
                                            : std::to_string(r.maps) + " × " + std::to_string(r.mapSize) + "²";
    std::string text =
        r.technique + ", " + maps + ", bias slope " + fixed(r.bias.slope, 2) + " / constant " +
        fixed(r.bias.constant, 2) + " / normal offset " + fixed(r.bias.normalOffset, 2) +
        (r.bias.normalOffsetFootprint > 0.0 ? " + footprint " + fixed(r.bias.normalOffsetFootprint, 2) : "") +
        (r.bias.offsetGuard ? ", guarded" : "") + ", filter " + r.filter + ", " + std::to_string(r.width) + " × " +
        std::to_string(r.height) + ", scene " + r.scene + " (seed " + std::to_string(r.seed) + ")";
    if (!r.autoChoice.empty()) text += "; auto chose " + r.autoChoice;
    for (const std::string& f : r.fallbacks) text += "; fallback: " + f;
    return text;
}

} // namespace

std::span<const FigureMeaning> figureMeanings() { return kMeanings; }

std::string htmlEscape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&#39;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

std::string htmlReport(const HtmlReport& report) {
    // Entries grouped by view, views in their first appearance's order.
    std::vector<std::string> views;
    std::map<std::string, std::vector<const HtmlEntry*>> byView;
    for (const HtmlEntry& e : report.entries) {
        auto& list = byView[e.report.view];
        if (list.empty()) views.push_back(e.report.view);
        list.push_back(&e);
    }

    std::ostringstream out;
    out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<meta name=\"viewport\" "
           "content=\"width=device-width, initial-scale=1\">\n<title>"
        << htmlEscape(report.title) << "</title>\n<style>" << kStyle << "</style>\n<script>" << kScript
        << "</script>\n</head><body>\n<h1>" << htmlEscape(report.title) << "</h1>\n<p id=\"broken\"></p>\n";
    if (!report.command.empty())
        out << "<p>The command that wrote this page:</p><pre>" << htmlEscape(report.command) << "</pre>\n";
    if (!report.machine.empty()) out << "<p>Measured on " << htmlEscape(report.machine) << ".</p>\n";

    if (!views.empty()) {
        // The summary: wrong_pct (median pixels per texel) per view and entry label.
        std::vector<std::string> labels;
        for (const HtmlEntry& e : report.entries)
            if (std::find(labels.begin(), labels.end(), e.label) == labels.end()) labels.push_back(e.label);
        out << "<h2>Summary</h2>\n<p><code>wrong_pct</code> (<code>pixels_per_texel_p50</code>) against ray-traced "
               "truth; lower is better for both.</p>\n<table class=\"summary\"><tr><th>view</th>";
        for (const std::string& l : labels) out << "<th>" << htmlEscape(l) << "</th>";
        out << "</tr>\n";
        for (const std::string& v : views) {
            out << "<tr><td><a href=\"#view-" << htmlEscape(v) << "\">" << htmlEscape(v) << "</a></td>";
            for (const std::string& l : labels) {
                const auto& list = byView[v];
                auto it = std::find_if(list.begin(), list.end(), [&](const HtmlEntry* e) { return e->label == l; });
                out << "<td>"
                    << (it == list.end() ? std::string("–")
                                         : fixed((*it)->report.figures.wrongPct, 2) + " (" +
                                               fixed((*it)->report.figures.pixelsPerTexelP50, 1) + ")")
                    << "</td>";
            }
            out << "</tr>\n";
        }
        out << "</table>\n";
        writeLegend(out);
    }

    for (const std::string& v : views) {
        const auto& list = byView[v];
        out << "<section class=\"view\" id=\"view-" << htmlEscape(v) << "\">\n<h2>" << htmlEscape(v) << "</h2>\n";
        for (const HtmlEntry* e : list) {
            out << "<h3>" << htmlEscape(e->label) << "</h3>\n<p>" << htmlEscape(settingsText(e->report)) << "</p>\n";
            out << "<div class=\"row\">";
            for (const HtmlPicture& p : e->pictures) writePicture(out, p, v + ", " + e->label);
            out << "</div>\n";
            if (!e->command.empty()) out << "<pre>" << htmlEscape(e->command) << "</pre>\n";
        }
        writeFiguresTable(out, list);
        out << "</section>\n";
    }

    for (const HtmlPath& p : report.paths) {
        out << "<section class=\"path\" id=\"path-" << htmlEscape(p.name) << "\">\n<h2>Path <code>"
            << htmlEscape(p.name) << "</code></h2>\n<p>" << htmlEscape(p.summary) << "</p>\n<div class=\"row\">";
        writePicture(out, p.plot, p.name);
        out << "</div>\n";
        if (!p.strip.file.empty()) {
            out << "<div class=\"row\">";
            writePicture(out, p.strip, p.name);
            out << "</div>\n";
        }
        out << "<p><code>flicker_pct</code>: % of the pixels seen in two consecutive frames at the same world point "
               "whose rendered lit/shadowed state changed while the truth's did not. "
               "<code>truth_change_pct</code>: % whose truth changed (a moving sun or moving casters).</p>\n";
        if (!p.command.empty()) out << "<pre>" << htmlEscape(p.command) << "</pre>\n";
        out << "</section>\n";
    }
    for (size_t i = 0; i < report.tables.size(); ++i) {
        const HtmlTable& table = report.tables[i];
        out << "<section class=\"table\" id=\"table-" << i + 1 << "\">\n<h2>" << htmlEscape(table.title) << "</h2>\n<p>"
            << htmlEscape(table.note) << "</p>\n<table class=\"measurements\"><tr>";
        for (const std::string& h : table.header) out << "<th>" << htmlEscape(h) << "</th>";
        out << "</tr>\n";
        for (const auto& row : table.rows) {
            out << "<tr>";
            for (const std::string& cell : row) out << "<td>" << htmlEscape(cell) << "</td>";
            out << "</tr>\n";
        }
        out << "</table>\n";
        if (!table.pictures.empty()) {
            out << "<div class=\"row\">";
            for (const HtmlPicture& p : table.pictures) writePicture(out, p, table.title);
            out << "</div>\n";
        }
        if (!table.command.empty()) out << "<pre>" << htmlEscape(table.command) << "</pre>\n";
        out << "</section>\n";
    }
    out << "<p>The evaluation protocol is explained in shadowkit's <code>docs/evaluation.md</code>; every figure "
           "here is reproduced by the command shown with it.</p>\n</body></html>\n";
    return out.str();
}

core::Status writeHtmlReport(const HtmlReport& report, const std::filesystem::path& file) {
    return scene::writeFile(file, htmlReport(report));
}

} // namespace shadowkit::eval
