#include "shadowkit/eval/npy.h"

#include "shadowkit/scene/file_read.h"
#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>
#include <string>
#include <string_view>

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

// The value of `key` in a .npy header's dict ("'descr': '<f4'" -> "<f4", "'shape': (3, 4)" ->
// "3, 4", "'fortran_order': False" -> "False"), or empty when the header has no such key.
// Scanned by hand: libstdc++'s std::regex recurses once a character matched, and a header of
// 60,000 characters overflowed the stack.
std::string headerField(std::string_view header, std::string_view key) {
    std::string quotedKey(1, '\'');
    quotedKey.append(key).append(1, '\''); // not "'" + …: GCC 12 warns falsely of an overlap there
    const size_t at = header.find(quotedKey);
    if (at == std::string_view::npos) return {};
    size_t i = header.find_first_not_of(" \t", at + quotedKey.size());
    if (i == std::string_view::npos || header[i] != ':') return {};
    i = header.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos) return {};
    if (header[i] == '\'' || header[i] == '(') {
        const size_t close = header.find(header[i] == '\'' ? '\'' : ')', i + 1);
        return close == std::string_view::npos ? std::string() : std::string(header.substr(i + 1, close - i - 1));
    }
    for (const std::string_view word : {"True", "False"})
        if (header.substr(i, word.size()) == word) return std::string(word);
    return {};
}

// A header's value as a one-line message may show it: at most 40 bytes, control characters as '?'
// (a value may run over a newline to the next closing bracket).
std::string excerpt(const std::string& text) {
    std::string shown = text.substr(0, 40);
    for (char& c : shown)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text.size() <= 40 ? shown : shown + "…";
}

// The dimensions of a shape's "h, w" (a trailing comma allowed, as NumPy writes it), each a whole
// number of at most 9 digits; empty when any is not.
std::vector<long long> dimensionsOf(std::string_view dims) {
    const auto trimmed = [](std::string_view text) {
        const size_t first = text.find_first_not_of(" \t\r\n");
        return first == std::string_view::npos ? std::string_view()
                                               : text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
    };
    std::vector<long long> shape;
    for (size_t start = 0; start <= dims.size();) {
        const size_t comma = dims.find(',', start);
        const size_t end = comma == std::string_view::npos ? dims.size() : comma;
        const std::string_view token = trimmed(dims.substr(start, end - start));
        if (token.empty() && end == dims.size() && !shape.empty()) break; // the trailing comma
        if (token.empty() || token.size() > 9 ||
            !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return {};
        shape.push_back(std::stoll(std::string(token)));
        start = end + 1;
    }
    return shape;
}

} // namespace

core::Result<NpyImage> readNpyImage(const std::filesystem::path& file) {
    const std::string name = file.string();
    // The largest a file within the limits can be: its header and 2^26 float64 values.
    const auto read = scene::readFile(file, 65536 + 16 + sizeof(double) * uintmax_t(scene::kMaxImageTexels));
    if (!read) return read.errorInfo();
    const std::string& bytes = *read;
    if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0)
        return core::makeError(name + ": not a NumPy .npy file");
    const int major = static_cast<unsigned char>(bytes[6]);
    if (major != 1 && major != 2)
        return core::makeError(name + ": .npy format version " + std::to_string(major) + " (1 or 2 read)");
    const size_t lengthBytes = major == 1 ? 2 : 4;
    if (bytes.size() < 8 + lengthBytes) return core::makeError(name + ": truncated .npy header");
    size_t headerLength = 0;
    for (size_t k = 0; k < lengthBytes; ++k)
        headerLength |= size_t(static_cast<unsigned char>(bytes[8 + k])) << (8 * k);
    const size_t dataStart = 8 + lengthBytes + headerLength;
    if (headerLength > 65536 || dataStart > bytes.size()) return core::makeError(name + ": truncated .npy header");
    const std::string header = bytes.substr(8 + lengthBytes, headerLength);
    const std::string descr = headerField(header, "descr"), order = headerField(header, "fortran_order");
    if (descr.empty() || order.empty())
        return core::makeError(name + ": a .npy header without 'descr' or 'fortran_order' (cut short?)");
    if (order != "False") return core::makeError(name + ": a .npy array in Fortran order (C order read)");
    size_t elementSize = 0;
    if (descr == "<f4")
        elementSize = 4;
    else if (descr == "<f8")
        elementSize = 8;
    else if (descr == "|u1" || descr == "<u1")
        elementSize = 1;
    else if (descr == "<u2")
        elementSize = 2;
    else
        return core::makeError(name + ": .npy dtype '" + excerpt(descr) + "' (float32, float64, uint8 or uint16 read)");
    // "h, w" (a trailing comma allowed); one value per pixel.
    const std::string dims = headerField(header, "shape");
    const std::vector<long long> shape = dimensionsOf(dims);
    if (shape.size() != 2)
        return core::makeError(name + ": a .npy array of shape (" + excerpt(dims) + "), not (height, width)");
    const long long height = shape[0], width = shape[1];
    if (height < 1 || width < 1 || height > scene::kMaxImageSide || width > scene::kMaxImageSide ||
        height * width > scene::kMaxImageTexels)
        return core::makeError(name + ": a " + std::to_string(width) + "×" + std::to_string(height) +
                               " .npy array is over shadowkit's image limits (sides 1 to " +
                               std::to_string(scene::kMaxImageSide) + ", 2^26 values)");
    const size_t count = size_t(height) * size_t(width);
    if (bytes.size() - dataStart != count * elementSize)
        return core::makeError(name + ": " + std::to_string(bytes.size() - dataStart) + " bytes of data where shape (" +
                               excerpt(dims) + ") of " + descr + " needs " + std::to_string(count * elementSize));
    NpyImage out{int(height), int(width), std::vector<float>(count)};
    const char* data = bytes.data() + dataStart;
    for (size_t i = 0; i < count; ++i) {
        if (elementSize == 4) {
            float v;
            std::memcpy(&v, data + 4 * i, 4);
            out.values[i] = v;
        } else if (elementSize == 8) {
            double v;
            std::memcpy(&v, data + 8 * i, 8);
            out.values[i] = static_cast<float>(v);
        } else if (elementSize == 2) {
            uint16_t v;
            std::memcpy(&v, data + 2 * i, 2);
            out.values[i] = float(v) / 65535.0f;
        } else {
            out.values[i] = float(static_cast<unsigned char>(data[i])) / 255.0f;
        }
    }
    return out;
}

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
