// One HTML page for an evaluation (`shadowkit eval --report`, `compare --report`, `eval --path
// --report`, `bench --report`): per view the rendered frame, the rendered and the ray-traced shadows, the error
// and aliasing maps side by side; the figures with what each means; the command line that
// reproduces the view. Several entries of one view (techniques or configurations) share its
// section, one row of pictures and one column of figures each, so they compare at a glance.
//
// The page is self-contained but for its pictures, which lie beside it (relative links): a
// report directory can be moved or served as it is. A script on the page counts the images
// that failed to load into `data-images` / `data-broken-images` on <body>, which the browser
// test reads back (tests/report_browser_test.py).
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/eval/report.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadowkit::eval {

struct HtmlPicture {
    std::string file;    // relative to the page
    std::string caption; // "error map"
};

// One row of a view's section: what was measured, its pictures, and how to measure it again.
struct HtmlEntry {
    std::string label; // "tsm 2048²" or a configuration's settings
    ViewReport report;
    std::vector<HtmlPicture> pictures;
    std::string command; // one command line that reproduces this entry alone
};

// A camera path's figures over its frames (`eval --path`): a plot and a strip of frames.
struct HtmlPath {
    std::string name;    // "flythrough"
    std::string summary; // "flicker_pct mean 0.23 / p95 0.34 / max 0.36; ..."
    HtmlPicture plot;    // flicker_pct and truth_change_pct per frame
    HtmlPicture strip;   // a few frames side by side (may be empty)
    std::string command; // reproduces the path's evaluation
};

// A table of measurements that are not figures against truth (`bench --report`: triangles and
// times per pass), with what its columns mean and pictures of what was measured.
struct HtmlTable {
    std::string title;
    std::string note; // what the columns mean, where the times were taken
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::vector<HtmlPicture> pictures;
    std::string command; // reproduces the table
};

struct HtmlReport {
    std::string title = "shadowkit evaluation";
    std::string command; // the command that wrote the report
    std::string machine; // the GL renderer and the date, where the figures were taken
    std::vector<HtmlEntry> entries;
    std::vector<HtmlPath> paths;
    std::vector<HtmlTable> tables;
};

// What each figure of the evaluation means, one sentence each (docs/references.md, evaluation
// §3), in the order of the JSON report: the page's figures tables and the docs say the same.
struct FigureMeaning {
    std::string_view name; // the JSON field: "wrong_pct"
    std::string_view meaning;
    std::string (*text)(const Figures&) = nullptr; // the figure as the command line's table prints it
};
std::span<const FigureMeaning> figureMeanings();

std::string htmlReport(const HtmlReport& report);
// Writes the page (its directory must exist; the pictures are the caller's).
core::Status writeHtmlReport(const HtmlReport& report, const std::filesystem::path& file);

// Text made safe for HTML element content and quoted attributes.
std::string htmlEscape(std::string_view text);

} // namespace shadowkit::eval
