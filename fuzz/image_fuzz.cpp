// Images through the decoders of files from outside: glTF textures (scene::decodeImage: stb_image
// for PNG and JPEG, libwebp) and `shadowkit score`'s masks (scene::decodeLevels: PNG of 8 or 16
// bits), limits read from the header before decoding: any bytes give an image of the size it
// states or a one-line error, never a crash, a hang or an allocation past the limits.
#include "shadowkit/scene/image.h"

#include <cstdlib>
#include <span>

namespace {

void checkSize(int width, int height) {
    if (width <= 0 || height <= 0 || width > shadowkit::scene::kMaxImageSide ||
        height > shadowkit::scene::kMaxImageSide)
        std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto bytes = std::span(data, size);
    if (const auto image = shadowkit::scene::decodeImage(bytes, "fuzz input"); image) {
        checkSize(image->width, image->height);
        if (image->rgba.size() != size_t(image->width) * size_t(image->height) * 4) std::abort();
    } else if (image.error().find('\n') != std::string::npos) {
        std::abort(); // errors are one line
    }
    if (const auto levels = shadowkit::scene::decodeLevels(bytes, "fuzz input"); levels) {
        checkSize(levels->width, levels->height);
        const size_t texels = size_t(levels->width) * size_t(levels->height);
        if (levels->level.size() != texels || (!levels->alpha.empty() && levels->alpha.size() != texels)) std::abort();
        for (float v : levels->level)
            if (!(v >= 0.0f && v <= 1.0f)) std::abort();
    } else if (levels.error().find('\n') != std::string::npos) {
        std::abort();
    }
    return 0;
}
