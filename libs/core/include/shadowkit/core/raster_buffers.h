// What a rasterizer hands the evaluation, per pixel, as plain arrays (no GL types):
// the evaluation (libs/eval) compares these with ray-traced truth without touching GL.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace shadowkit::core {

/// Per-pixel buffers a renderer hands to the evaluation: shadow term, surface, depth, normal, texel coordinates.
struct RasterBuffers {
    int width = 0;  ///< pixels per row
    int height = 0; ///< rows
    /// All arrays are row-major with the top row first, width × height entries.
    std::vector<float> shadowTerm;   ///< 1 lit … 0 shadowed, the map's test alone (no N·L)
    std::vector<uint32_t> surfaceId; ///< global instance index + 1; 0 where nothing was drawn
    std::vector<float> viewDepth;    ///< metres along the view direction; 0 where nothing was drawn
    std::vector<glm::vec3> wsNormal; ///< geometric normal of the drawn triangle, unit, on the shading normal's side
    std::vector<glm::vec2> tsTexel;  ///< shadow-map texel coordinates (ts × map size)
    /// d(texel)/d(pixel): columns are the screen x and y derivatives of tsTexel
    /// (right and down), the Jacobian whose smallest singular value gives texels per pixel.
    std::vector<glm::mat2> texelFromPixel;
    int mapSize = 0; ///< texels per side of the map sampled

    /// The array index of pixel (x, y), y = 0 the top row.
    size_t index(int x, int y) const {
        return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
    }
};

} // namespace shadowkit::core
