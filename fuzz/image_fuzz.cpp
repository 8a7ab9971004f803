// Images through the decoder glTF textures go through (scene::decodeImage: stb_image, PNG and
// JPEG only, limits read from the header before decoding): any bytes give an RGBA8 image of the
// size it states or a one-line error, never a crash, a hang or an allocation past the limits.
#include "shadowkit/scene/image.h"

#include <cstdlib>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto image = shadowkit::scene::decodeImage(std::span(data, size), "fuzz input");
    if (!image) {
        if (image.error().find('\n') != std::string::npos) std::abort(); // errors are one line
        return 0;
    }
    const size_t texels = size_t(image->width) * size_t(image->height);
    if (image->width <= 0 || image->height <= 0 || image->width > shadowkit::scene::kMaxImageSide ||
        image->height > shadowkit::scene::kMaxImageSide || image->rgba.size() != texels * 4)
        std::abort();
    return 0;
}
