#include "common.h"

#include "shadowkit/scene/file_write.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>

namespace shadowkit::app {

int fail(const std::string& message) {
    // One line whatever the message echoes of the input (a newline typed into --configs).
    std::string line = message;
    std::replace_if(
        line.begin(), line.end(), [](unsigned char c) { return c < 0x20; }, ' ');
    fmt::print(stderr, "shadowkit: error: {}\n", line);
    return kExitBadInput;
}

int fail(const core::Error& error) {
    fail(error.message);
    return error.kind == core::ErrorKind::Environment ? kExitEnvironment : kExitBadInput;
}

int parseErrorExit(const CLI::ParseError& e) {
    fmt::print(stderr, "shadowkit: error: {} (see shadowkit --help)\n", e.what());
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

} // namespace shadowkit::app
