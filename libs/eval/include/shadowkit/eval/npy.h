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

} // namespace shadowkit::eval
