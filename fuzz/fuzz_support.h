// What the fuzz targets share: the input as a file with the extension the loader dispatches on
// (in memory-backed /dev/shm where there is one, one file per process), and a small forest to
// resolve views over, with and without its ground.
#pragma once

#include "shadowkit/scene/forest.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace shadowkit::fuzz {

inline std::filesystem::path writeInput(const uint8_t* data, size_t size, const std::string& extension) {
    static const std::filesystem::path folder =
        std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    const std::filesystem::path file = folder / ("shadowkit_fuzz_" + std::to_string(getpid()) + extension);
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return file;
}

inline const scene::Scene& smallForest() {
    static const scene::Scene forest = [] {
        scene::ForestOptions o;
        o.trees = 20, o.terrainSize = 100, o.terrainResolution = 8, o.rocks = 1, o.buildings = 1, o.movers = 1;
        return scene::makeForest(o);
    }();
    return forest;
}

// The same meshes without their heightfield: a scene with no ground, as a loaded file is, which
// views and paths frame (scene/views.h) rather than stand on.
inline const scene::Scene& smallModel() {
    static const scene::Scene model = [] {
        scene::Scene m = smallForest();
        m.terrain.reset();
        return m;
    }();
    return model;
}

} // namespace shadowkit::fuzz
