// `score --camera` files (apps/shadowkit/camera_file.h): a camera read is one any renderer can
// draw with — valid once it has an aspect, its sun's direction finite, its image within the
// limits — and a bad file gives a one-line error naming the file.
#include "fuzz_support.h"

#include "camera_file.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace shadowkit;
    const auto file = fuzz::writeInput(data, size, ".json");
    const auto read = app::loadCameraFile(file.string());
    if (!read) {
        if (read.error().find('\n') != std::string::npos || read.error().find(file.string()) == std::string::npos)
            std::abort();
        return 0;
    }
    core::PerspectiveCamera camera = read->camera;
    if (camera.aspect == 0.0) camera.aspect = 1.0; // score gives the mask's
    if (!camera.validate()) std::abort();
    if (read->light && !core::isFinite(read->light->wsDirection)) std::abort();
    for (const auto& side : {read->width, read->height})
        if (side && !(*side >= 1 && *side <= 16384)) std::abort();
    return 0;
}
