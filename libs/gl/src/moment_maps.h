// Moment shadow maps (Peters & Klein 2015): the sun's fixed maps (single maps and cascades; not
// virtual pages, which hold depth only) as four moments of depth per texel, prefiltered by a
// separable Gaussian blur, and looked up with one bilinear fetch (glsl/shadowkit_shadows.glsl's
// skMomentLit). 4 × 32-bit float per texel: 16 bytes, four times a depth map's.
#pragma once

#include "gl_object.h"

#include "shadowkit/core/result.h"

#include <memory>

namespace shadowkit::gl {

class MomentMaps {
public:
    static core::Result<std::unique_ptr<MomentMaps>> create();

    // The moments of `depth` (size² × layers, GL_DEPTH_COMPONENT32F) read through `rawSampler`
    // (no comparison), blurred `blurTexels` each side (0: none). Out of memory: an error naming
    // map_size.
    core::Status update(const Texture& depth, GLuint rawSampler, int size, int layers, int blurTexels);
    // The moments on kMomentsUnit, bilinearly filtered.
    void bind() const;

private:
    MomentMaps() = default;
    Program m_program;
    Texture m_moments, m_scratch; // the result, and the blur's other half
    int m_size = 0, m_layers = 0;
};

} // namespace shadowkit::gl
