// OBJ through the project's reader (tinyobjloader and libs/scene/src/obj_read.cpp): any bytes
// give a scene or a one-line error.
#include "fuzz_support.h"

#include "shadowkit/scene/scene_io.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto file = shadowkit::fuzz::writeInput(data, size, ".obj");
    const auto scene = shadowkit::scene::loadScene(file);
    if (!scene && scene.error().find('\n') != std::string::npos) std::abort();
    return 0;
}
