// `--state FILE`: a saved set of command-line options (what `shadowkit-viewer` writes with
// Ctrl+S), so anything seen in the viewer can be drawn or measured again headless:
//
//   {"shadowkit_state": 1, "options": {"eye": "0,22,0", "technique": "lispsm",
//                                      "map-size": "2048", "light": ["point:0,23,-10"], ...}}
//
// Each entry is a long option of `render` without its dashes; a list repeats the option.
// Options given on the command line win over the file's.
#pragma once

#include "shadowkit/core/result.h"

#include <map>
#include <string>
#include <vector>

namespace shadowkit::app {

// Option name → values (one for most, several for repeatable ones such as `light`).
using StateOptions = std::map<std::string, std::vector<std::string>>;

core::Result<StateOptions> loadState(const std::string& file);
core::Status saveState(const StateOptions& options, const std::string& file);

// argv with `--state FILE` (or `--state=FILE`) replaced by the file's options as
// `--name=value`, those the command line also gives left out. Unchanged without --state.
core::Result<std::vector<std::string>> expandState(const std::vector<std::string>& args);

} // namespace shadowkit::app
