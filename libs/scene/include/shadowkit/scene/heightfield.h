// Regular-grid heightfield centred on the origin.
#pragma once

#include <vector>

namespace shadowkit::scene {

struct Heightfield {
    double size = 1024.0;       // metres along x and z
    int resolution = 256;       // quads per side; (resolution+1)^2 samples
    std::vector<float> heights; // row-major, z rows of x samples

    // Height of the terrain mesh surface at world (x, z), linear over its triangles;
    // clamped to the edge outside the grid.
    double heightAt(double x, double z) const;
    double sample(int ix, int iz) const;
    double spacing() const { return size / resolution; }
};

} // namespace shadowkit::scene
