// NumPy .npy files (format version 1.0), so users can analyse per-pixel buffers with
// their own tools: numpy.load("shadow_term.npy").
#pragma once

#include "shadowkit/core/result.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace shadowkit::eval {

// `shape` in C order (e.g. {height, width} or {height, width, 3}); the element count must match.
core::Status writeNpy(const std::filesystem::path& file, std::span<const float> data, std::vector<size_t> shape);
core::Status writeNpy(const std::filesystem::path& file, std::span<const uint8_t> data, std::vector<size_t> shape);
core::Status writeNpy(const std::filesystem::path& file, std::span<const uint32_t> data, std::vector<size_t> shape);

// A two-dimensional array read from a .npy file as floats (`shadowkit score`'s masks): format
// 1.0 or 2.0, C order, little-endian float32 or float64, or uint8 / uint16 scaled to [0, 1].
// The file is from outside: its header is parsed strictly, its shape checked against the image
// limits (scene::kMaxImageSide, kMaxImageTexels) and the file's size before anything is
// allocated; errors are one line naming the file.
struct NpyImage {
    int height = 0, width = 0;
    std::vector<float> values; // row-major
};
core::Result<NpyImage> readNpyImage(const std::filesystem::path& file);

} // namespace shadowkit::eval
