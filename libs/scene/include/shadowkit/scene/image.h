// 8-bit RGBA images: rendered frames, shadow-map views and error maps written as PNG; the
// textures of glTF materials decoded from PNG, JPEG and WebP.
#pragma once

#include "shadowkit/core/result.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadowkit::scene {

// A rectangle of an image's texels (the part of a texture a billboard cloud is baked into).
struct ImageRegion {
    int x = 0, y = 0, width = 0, height = 0;
};

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
    // Pixel (x, y) set to an opaque colour.
    void setOpaque(int x, int y, const uint8_t rgb[3]) {
        uint8_t* p = pixel(x, y);
        p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
    }
};

// The image as the bytes of a PNG file (RGBA8); an error names `what` (an empty image, or the
// encoder failing).
core::Result<std::string> encodePng(const Image& image, std::string_view what);

// Errors name the file (unwritable directory, disk full, a name ending in another format's
// extension than .png; none is taken as PNG).
core::Status writePng(const Image& image, const std::filesystem::path& file);
// The name writePng refuses: one that says another format (shot.jpg), whose PNG bytes tools that
// go by the name would misread; no extension, or .png in any case, passes. For front ends to
// check a picture's name before the work that draws it.
core::Status checkPictureName(const std::filesystem::path& file);

// Limits on a decoded image, checked from its header before any pixel is decoded: a side of
// at most 16384 texels (GL_MAX_TEXTURE_SIZE of the drivers we run on) and 2^26 texels (256 MiB
// of RGBA8) in all.
inline constexpr int kMaxImageSide = 16384;
inline constexpr int64_t kMaxImageTexels = int64_t(1) << 26;

// Decodes a PNG or JPEG (stb_image) or WebP (libwebp) image into RGBA8, grey and RGB given
// alpha 255. Anything else — another format (KTX2 named as such), an animated WebP, a truncated
// or corrupt file, a side or size past the limits — is an error of one line that starts with
// `what` (e.g. "scene.gltf: image 2 'leaf.png'").
core::Result<Image> decodeImage(std::span<const uint8_t> bytes, std::string_view what);

// One channel of an image at its full depth, as [0, 1] levels: a shadow mask another renderer
// drew (`shadowkit score`). PNG only — a lossy format would move the levels — of 8 or 16 bits,
// grey, grey and alpha, RGB or RGBA: `level` is the first channel (grey, or red), `alpha` the
// alpha channel (empty when the image has none); row-major, top row first. The same checks
// and limits as decodeImage, errors of one line that start with `what`.
struct LevelImage {
    int width = 0, height = 0;
    std::vector<float> level, alpha;
};
core::Result<LevelImage> decodeLevels(std::span<const uint8_t> bytes, std::string_view what);

} // namespace shadowkit::scene
