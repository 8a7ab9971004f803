// glTF and glb through the project's reader (libs/scene/src/gltf_read.cpp): any bytes give a
// scene or a one-line error, never a crash, a hang or a read outside a buffer. The first byte
// picks the container (even: JSON .gltf, odd: binary .glb). A file whose animations deform skins
// or morph weights is read again posed at another time, and played to a third.
#include "fuzz_support.h"

#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/scene_io.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const auto file = shadowkit::fuzz::writeInput(data + 1, size - 1, data[0] % 2 ? ".glb" : ".gltf");
    const auto scene = shadowkit::scene::loadScene(file);
    if (!scene && scene.error().find('\n') != std::string::npos) std::abort(); // errors are one line
    // Skins and morph weights posed between keys too (the load above posed them at t = 0).
    if (scene && !scene->deformations.empty()) {
        auto posed = shadowkit::scene::loadScene(file, {.poseSeconds = 0.37});
        if (!posed && posed.error().find('\n') != std::string::npos) std::abort();
        if (posed) shadowkit::scene::animate(*posed, 1.91);
    }
    return 0;
}
