#include "shadowkit/scene/image.h"

#include "scene_formats.h"

#include "shadowkit/scene/file_write.h"

#include <stb/stb_image_write.h>

#include <string>

namespace shadowkit::scene {

core::Result<std::string> encodePng(const Image& image, std::string_view what) {
    if (image.width <= 0 || image.height <= 0)
        return core::makeError(std::string(what) + ": cannot write an empty image");
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4))
        return core::makeError(std::string(what) + ": cannot encode PNG");
    return png;
}

core::Status checkPictureName(const std::filesystem::path& file) {
    if (const std::string extension = formats::lowerExtension(file); !extension.empty() && extension != ".png")
        return core::makeError(file.string() + ": pictures are written as PNG: name it .png, not " +
                               file.extension().string());
    return core::Ok{};
}

core::Status writePng(const Image& image, const std::filesystem::path& file) {
    // A name that says another format would hold PNG bytes under it ("wrote shot.jpg"), which
    // tools that go by the name then misread: refused, before anything is written.
    if (auto s = checkPictureName(file); !s) return s;
    // Encoded in memory, then written whole (file_write.h): stb's own file writer reports
    // neither a full disk nor a failed close.
    const core::Result<std::string> png = encodePng(image, file.string());
    if (!png) return png.errorInfo();
    return writeFile(file, *png);
}

} // namespace shadowkit::scene
