// Helpers for tests that write glTF files by hand.
#pragma once

#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace shadowkit::scene::testing {

// RFC 4648 base64, for data: URIs.
inline std::string base64(const std::vector<unsigned char>& data) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t n = uint32_t(data[i]) << 16 | (i + 1 < data.size() ? uint32_t(data[i + 1]) << 8 : 0) |
                           (i + 2 < data.size() ? uint32_t(data[i + 2]) : 0);
        out += digits[n >> 18 & 63];
        out += digits[n >> 12 & 63];
        out += i + 1 < data.size() ? digits[n >> 6 & 63] : '=';
        out += i + 2 < data.size() ? digits[n & 63] : '=';
    }
    return out;
}

// `text` as the temporary file `name`, loaded (with `options`) and removed; a file that could
// not be written is the test's failure, not the reader's.
inline core::Result<Scene> loadWritten(const std::string& name, const std::string& text,
                                       const LoadOptions& options = {}) {
    const auto file = shadowkit::test_support::scratchDir() / name;
    std::ofstream out(file);
    out << text;
    out.close();
    if (!out) return core::makeError(file.string() + ": the test could not write it");
    auto scene = loadScene(file, options);
    std::filesystem::remove(file);
    return scene;
}

} // namespace shadowkit::scene::testing
