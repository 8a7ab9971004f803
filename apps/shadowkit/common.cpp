#include "common.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>

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

namespace {

// Writes and closes `path`, every error checked: a short write, a failed flush (a full disk
// reports there) or close.
core::Status writeWhole(const std::string& path, const std::string& text) {
    std::FILE* out = std::fopen(path.c_str(), "wb");
    if (!out) return core::makeError(std::strerror(errno));
    const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size() && std::fflush(out) == 0;
    const int writeError = errno;
    const bool closed = std::fclose(out) == 0;
    if (!written) return core::makeError(std::strerror(writeError));
    if (!closed) return core::makeError(std::strerror(errno));
    return core::Ok{};
}

} // namespace

core::Status writeTextFile(const char* flag, const std::string& file, const std::string& text) {
    const auto failed = [&](const std::string& why) {
        return core::makeError(fmt::format("{}: {}: cannot write ({})", flag, file, why));
    };
    // A device, a pipe or a terminal is written in place: renaming over one would replace it.
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
        if (auto s = writeWhole(file, text); !s) return failed(s.error());
        return core::Ok{};
    }
    const std::string temporary = file + ".tmp-" + std::to_string(::getpid());
    if (auto s = writeWhole(temporary, text); !s) {
        std::remove(temporary.c_str());
        return failed(s.error());
    }
    std::filesystem::rename(temporary, file, ec);
    if (ec) {
        std::remove(temporary.c_str());
        return failed(ec.message());
    }
    return core::Ok{};
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
