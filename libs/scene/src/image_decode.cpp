// PNG and JPEG decoding through stb_image (libstb-dev), the one translation unit that holds
// its implementation. Decoded bytes come from files we did not write: the header is read and
// checked against the limits before stb allocates anything, and only the two formats glTF
// allows (§3.8.4) are compiled in.
#include "shadowkit/scene/image.h"

#include <algorithm>
#include <string>

#define STB_IMAGE_STATIC // private to this file: libtinygltf may carry its own copy
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace shadowkit::scene {

core::Result<Image> decodeImage(std::span<const uint8_t> bytes, std::string_view what) {
    const std::string name(what);
    if (bytes.empty()) return core::makeError(name + ": the image is empty");
    if (bytes.size() > size_t(1) << 30) return core::makeError(name + ": the encoded image is over 1 GiB");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = static_cast<int>(bytes.size());
    // The signatures: PNG's eight bytes (ISO 15948 §5.2), JPEG's start-of-image marker and the next marker's 0xFF.
    static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    const bool png = bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin());
    const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
    if (!png && !jpeg) return core::makeError(name + ": not a PNG or JPEG image");
    const char* format = png ? "PNG" : "JPEG";
    // stb's own side limit (2^24) is left alone: ours is checked here, with a message that says so.
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(data, length, &width, &height, &channels))
        return core::makeError(name + ": unreadable " + format + " header (" + stbi_failure_reason() + ")");
    if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
        int64_t(width) * height > kMaxImageTexels)
        return core::makeError(name + ": " + std::to_string(width) + "×" + std::to_string(height) + " " + format +
                               " is over shadowkit's limits (sides up to " + std::to_string(kMaxImageSide) +
                               ", 2^26 texels)");
    int w = 0, h = 0;
    stbi_uc* pixels = stbi_load_from_memory(data, length, &w, &h, &channels, 4);
    if (!pixels)
        return core::makeError(name + ": corrupt or truncated " + format + " (" + stbi_failure_reason() + ")");
    Image image(w, h);
    std::copy(pixels, pixels + image.rgba.size(), image.rgba.begin());
    stbi_image_free(pixels);
    return image;
}

} // namespace shadowkit::scene
