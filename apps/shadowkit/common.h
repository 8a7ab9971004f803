// Helpers of every shadowkit front end (the subcommands and the viewer).
#pragma once

#include "shadowkit/core/result.h"

#include <string>

namespace shadowkit::app {

// Prints "shadowkit: error: <message>" (one line) to stderr and returns 1.
int fail(const std::string& message);

// A file a command will write later: fails now, before minutes of work, naming the flag, if
// its directory is missing.
core::Status checkWritable(const char* flag, const std::string& file);

} // namespace shadowkit::app
