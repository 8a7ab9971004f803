// This GL's ceilings for a depth pass, measured in the same run as the passes they judge
// (`shadowkit bench --limits`): how many depth samples a second it writes with no fragment
// work, and how many triangles a second it sets up. A shadow pass's achieved rates, divided
// by these, say how far from the hardware's limit it runs and which of the two bounds it.
#pragma once

#include "shadowkit/core/result.h"

#include <cstdint>

namespace shadowkit::gl {

struct DepthLimitsOptions {
    int mapTexels = 2048;    // side of the depth map drawn into, [16, 16384]
    int fillLayers = 16;     // full-map quads drawn back to front: each writes every texel, [1, 1024]
    int gridCells = 1024;    // small triangles: a grid of gridCells² cells, two triangles each, [1, 4096]
    int largeTriangles = 64; // large triangles: each covers half the map, [2, 65536], even
    int repeats = 3;         // each draw timed this many times, the fastest kept, [1, 100]
};

struct DepthLimits {
    // Depth-only fill: written samples a second (a depth map, depth test on, no fragment work).
    double fillSamplesPerSecond = 0.0;
    // Triangles a second, one draw each: many small ones (about two texels each) and a few
    // that each cover half the map (fill-bound on most GPUs: there for the ratio).
    double smallTrianglesPerSecond = 0.0;
    double largeTrianglesPerSecond = 0.0;
    // What the draws did, counted by GL (GL_SAMPLES_PASSED, once each): the fill draw must write
    // fillLayers × mapTexels² samples, the grid mapTexels² (it tiles the map once).
    uint64_t fillSamples = 0, gridSamples = 0;
    uint64_t smallTriangles = 0, largeTriangles = 0;
    double fillMilliseconds = 0.0, smallMilliseconds = 0.0, largeMilliseconds = 0.0;
};

// Fails, naming the field, for options out of range, and when GL cannot allocate the map.
// Needs a current OpenGL 4.5 context (gl::Context); leaves no GL state changed but the bound
// framebuffer (0), program (0) and vertex array (0).
core::Result<DepthLimits> measureDepthLimits(const DepthLimitsOptions& options = {});

} // namespace shadowkit::gl
