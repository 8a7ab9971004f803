#include "common.h"

#include <fmt/format.h>

#include <filesystem>

namespace shadowkit::app {

int fail(const std::string& message) {
    fmt::print(stderr, "shadowkit: error: {}\n", message);
    return kExitBadInput;
}

int fail(const core::Error& error) {
    fail(error.message);
    return error.kind == core::ErrorKind::Environment ? kExitEnvironment : kExitBadInput;
}

core::Status checkWritable(const char* flag, const std::string& file) {
    if (file.empty()) return core::Ok{};
    const std::filesystem::path dir = std::filesystem::path(file).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
        return core::makeError(fmt::format("{}: directory '{}' does not exist", flag, dir.string()));
    return core::Ok{};
}

} // namespace shadowkit::app
