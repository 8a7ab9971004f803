// Helpers of every shadowkit front end (the subcommands and the viewer).
#pragma once

#include "shadowkit/core/result.h"

#include <filesystem>
#include <string>

namespace CLI {
class ParseError;
}

namespace shadowkit::app {

// Exit codes (docs/commands.md): 1 a bad value, 2 a usage error (unknown flag, missing
// argument), 3 an environment that cannot do what was asked (no OpenGL 4.5, a driver limit or
// an allocation the driver refused, a shader the driver rejected).
inline constexpr int kExitBadInput = 1, kExitUsage = 2, kExitEnvironment = 3;

// `message` with every control character (a newline typed into a value or a saved --state, a
// control character in a glTF's image name) made a space: an error is one line whatever it echoes.
std::string oneLine(const std::string& message);
// A file name's extension as the formats are told apart: "shot.PNG" -> ".png"; "" where none.
std::string lowerExtension(const std::string& file);

// Prints "shadowkit: error: <message>" (one line) to stderr and returns kExitBadInput.
int fail(const std::string& message);
// The same for a library error, returning kExitEnvironment for ErrorKind::Environment.
int fail(const core::Error& error);
// Prints "shadowkit: warning: <message>" (one line, as fail's) to stderr after whatever stdout
// holds, so that where both go to one pipe the warning follows the row it is about.
void warn(const std::string& message);
// `name` as a part of a file name and of a relative URL: every character but letters, digits,
// '-', '_' and '.' made '_' ("file:Camera" -> "file_Camera"; a colon would read as a URL scheme).
std::string fileSafe(const std::string& name);

// The directory holding views.json, camera paths and golden figures: $SHADOWKIT_DATA_DIR, else
// share/shadowkit beside the running program's bin/ (an installed tree, wherever it was moved),
// else the source tree's data/ (builds run in place), else the configured install prefix's.
std::filesystem::path dataDirectory();

// A command line CLI11 could not parse, as one line "shadowkit: error: ... (see shadowkit --help)":
// 1 for a value that does not convert or is not one of the choices (bad input), else 2 (an
// unknown flag or a missing argument: a usage error).
int parseErrorExit(const CLI::ParseError& error);

// A file a command will write later: creates its missing directories now, or fails now,
// before minutes of work, naming the flag.
core::Status checkWritable(const char* flag, const std::string& file);
// The same for a picture, whose name must also say PNG (scene::checkPictureName): a render of
// minutes is not thrown away at the end for a name.
core::Status checkPictureWritable(const char* flag, const std::string& file);
// Likewise for a report's page, which is HTML: .html, .htm or no extension (its pictures go beside
// it under its stem); `--report results.png` would put a page where a picture is looked for.
core::Status checkReportWritable(const char* flag, const std::string& file);
// Likewise for figures written as JSON (.json or no extension) and rows written as CSV (.csv or
// none): `--json results.csv` would hand JSON to whatever opens a CSV by its name.
core::Status checkJsonWritable(const char* flag, const std::string& file);
core::Status checkCsvWritable(const char* flag, const std::string& file);

// Writes `text` to `file` whole or not at all (scene::writeFile), an error naming the flag
// and the file.
core::Status writeTextFile(const char* flag, const std::string& file, const std::string& text);

} // namespace shadowkit::app
