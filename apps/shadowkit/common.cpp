#include "common.h"

#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <string_view>

namespace shadowkit::app {

std::string oneLine(const std::string& message) {
    std::string line = message;
    std::replace_if(
        line.begin(), line.end(), [](unsigned char c) { return c < 0x20; }, ' ');
    return line;
}

std::string lowerExtension(const std::string& file) {
    std::string extension = std::filesystem::path(file).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

int fail(const std::string& message) {
    fmt::print(stderr, "shadowkit: error: {}\n", oneLine(message));
    return kExitBadInput;
}

void warn(const std::string& message) {
    std::fflush(stdout);
    fmt::print(stderr, "shadowkit: warning: {}\n", oneLine(message));
}

std::string fileSafe(const std::string& name) {
    std::string out = name;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    return out;
}

int fail(const core::Error& error) {
    fail(error.message);
    return error.kind == core::ErrorKind::Environment ? kExitEnvironment : kExitBadInput;
}

int parseErrorExit(const CLI::ParseError& e) {
    // CLI11 echoes the value as given: a newline in it (typed, or from a --state file) stays one line.
    fmt::print(stderr, "shadowkit: error: {} (see shadowkit --help)\n", oneLine(e.what()));
    const bool badValue =
        dynamic_cast<const CLI::ValidationError*>(&e) || dynamic_cast<const CLI::ConversionError*>(&e);
    return badValue ? kExitBadInput : kExitUsage;
}

core::Status writeTextFile(const char* flag, const std::string& file, const std::string& text) {
    if (auto s = scene::writeFile(file, text); !s) return core::makeError(fmt::format("{}: {}", flag, s.error()));
    return core::Ok{};
}

core::Status checkWritable(const char* flag, const std::string& file) {
    if (file.empty()) return core::Ok{};
    if (auto s = scene::prepareOutputDirectory(file); !s)
        return core::makeError(fmt::format("{}: {}", flag, s.error()));
    return core::Ok{};
}

namespace {

// A file whose name must say the format it is written in: one of `extensions` (lower case, the
// first the one to suggest) or none at all, which names no format.
core::Status checkNamedWritable(const char* flag, const std::string& file, const char* what,
                                std::initializer_list<std::string_view> extensions) {
    if (file.empty()) return core::Ok{};
    if (const std::string extension = lowerExtension(file);
        !extension.empty() && std::find(extensions.begin(), extensions.end(), extension) == extensions.end())
        return core::makeError(fmt::format("{}: {}: {}: name it {}, not {}", flag, file, what, *extensions.begin(),
                                           std::filesystem::path(file).extension().string()));
    return checkWritable(flag, file);
}

} // namespace

core::Status checkReportWritable(const char* flag, const std::string& file) {
    return checkNamedWritable(flag, file, "reports are written as HTML", {".html", ".htm"});
}

core::Status checkJsonWritable(const char* flag, const std::string& file) {
    return checkNamedWritable(flag, file, "figures are written as JSON", {".json"});
}

core::Status checkCsvWritable(const char* flag, const std::string& file) {
    return checkNamedWritable(flag, file, "rows are written as CSV", {".csv"});
}

core::Status checkPictureWritable(const char* flag, const std::string& file) {
    if (file.empty()) return core::Ok{};
    if (auto s = scene::checkPictureName(file); !s) return core::makeError(fmt::format("{}: {}", flag, s.error()));
    return checkWritable(flag, file);
}

} // namespace shadowkit::app
