// 8-bit RGBA images and PNG files: rendered frames, shadow-map views, error maps.
#pragma once

#include "shadowkit/core/result.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace shadowkit::scene {

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba; // row-major, top row first, 4 bytes per pixel

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0) {}
    uint8_t* pixel(int x, int y) {
        return rgba.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
    }
    const uint8_t* pixel(int x, int y) const {
        return rgba.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
    }
};

// Errors name the file (unwritable directory, disk full).
core::Status writePng(const Image& image, const std::filesystem::path& file);

} // namespace shadowkit::scene
