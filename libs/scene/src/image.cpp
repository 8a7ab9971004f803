#include "shadowkit/scene/image.h"

#include <stb/stb_image_write.h>

namespace shadowkit::scene {

core::Status writePng(const Image& image, const std::filesystem::path& file) {
    if (image.width <= 0 || image.height <= 0) return core::makeError(file.string() + ": cannot write an empty image");
    if (!stbi_write_png(file.string().c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
        return core::makeError(file.string() + ": cannot write PNG (does the directory exist and is it writable?)");
    return core::Ok{};
}

} // namespace shadowkit::scene
