// `--report FILE.html` of eval and compare: the pictures of each measured view written beside
// the page, and the command lines that reproduce them (eval::HtmlReport draws the page).
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/eval/html_report.h"
#include "shadowkit/measure/measurer.h"

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace shadowkit::app {

// The arguments this process was started with (main sets them once), for reports.
void setInvocation(std::vector<std::string> args);
// "shadowkit ARGS..." with each argument quoted for a POSIX shell where it needs it.
std::string commandLine(const std::vector<std::string>& args);
// The invocation without the options named in `drop` (and their values, given as "--x v" or
// "--x=v"), with `add` appended and, when `subcommand` is given, that subcommand instead of the
// one run: the command that redoes one part of a report.
std::string invocationWithout(std::initializer_list<std::string_view> drop, const std::vector<std::string>& add,
                              std::string_view subcommand = {});
std::string invocation();

// Writes the pictures of one measured view beside `page` — the frame (when measured with
// MeasureOptions::shadedImage), the rendered and ray-traced shadows (when the sun shines),
// the error map and the aliasing map — and returns its entry. `slug` names the files.
core::Result<eval::HtmlEntry> reportEntry(const measure::Measurement& measured, const eval::ViewReport& report,
                                          const core::DirectionalLight& sun, bool sunShines,
                                          const std::filesystem::path& page, const std::string& slug,
                                          const std::string& label, const std::string& command);

// "<the GL renderer>, <UTC date>": where a report's figures were taken.
std::string machineDescription(const measure::Measurer& measurer);

} // namespace shadowkit::app
