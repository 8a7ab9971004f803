#include "shadowkit/eval/npy.h"

#include "shadowkit/scene/file_write.h"

#include <functional>
#include <numeric>
#include <string>

namespace shadowkit::eval {
namespace {

core::Status write(const std::filesystem::path& file, const void* data, size_t elementSize, size_t count,
                   const char* descr, const std::vector<size_t>& shape) {
    const size_t expected = std::accumulate(shape.begin(), shape.end(), size_t{1}, std::multiplies<>());
    if (expected != count) return core::makeError(file.string() + ": shape does not match the data");
    std::string dims;
    for (size_t d : shape) dims += std::to_string(d) + ",";
    if (shape.size() > 1) dims.pop_back(); // "(h,w)" but "(n,)" for one dimension
    std::string header = std::string("{'descr': '") + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
    // Magic (6) + version (2) + length (2) + header, padded with spaces to a multiple of 64, ending in '\n'.
    const size_t total = (10 + header.size() + 1 + 63) / 64 * 64;
    header.append(total - 10 - header.size() - 1, ' ');
    header += '\n';
    const auto len = static_cast<uint16_t>(header.size());
    std::string bytes("\x93NUMPY\x01\x00", 8);
    bytes += static_cast<char>(len & 0xff);
    bytes += static_cast<char>(len >> 8);
    bytes += header;
    bytes.append(static_cast<const char*>(data), elementSize * count);
    return scene::writeFile(file, bytes);
}

} // namespace

// Little-endian descriptors: the machines we build for (x86-64, arm64) are little-endian.
core::Status writeNpy(const std::filesystem::path& file, std::span<const float> data, std::vector<size_t> shape) {
    return write(file, data.data(), sizeof(float), data.size(), "<f4", shape);
}
core::Status writeNpy(const std::filesystem::path& file, std::span<const uint8_t> data, std::vector<size_t> shape) {
    return write(file, data.data(), 1, data.size(), "|u1", shape);
}
core::Status writeNpy(const std::filesystem::path& file, std::span<const uint32_t> data, std::vector<size_t> shape) {
    return write(file, data.data(), sizeof(uint32_t), data.size(), "<u4", shape);
}

} // namespace shadowkit::eval
