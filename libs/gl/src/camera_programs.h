// The camera passes' programs — the main pass (main.frag) and the eval pass (eval.frag) —
// in two variants each: with and without virtual maps' lookup (SK_VIRTUAL_MAPS in
// shadow_lookup.glsl). One shader with a uniform branch between the two made llvmpipe run
// both for every technique (the camera pass cost 1.45x; docs/performance.md). The variants
// without virtual maps are built with the renderer, so a driver that rejects the shaders
// fails there; those with them on first use.
#pragma once

#include "gl_object.h"

#include "shadowkit/core/result.h"

namespace shadowkit::gl {

class CameraPrograms {
public:
    // Builds the variants without virtual maps.
    static core::Result<CameraPrograms> create();
    // Builds the variant `virtualMaps` of both passes, once; what the driver says if it cannot.
    core::Status prepare(bool virtualMaps);
    // A prepared program's name.
    GLuint main(bool virtualMaps) const { return m_programs[virtualMaps][0].id(); }
    GLuint eval(bool virtualMaps) const { return m_programs[virtualMaps][1].id(); }

private:
    Program m_programs[2][2]; // [virtual maps][eval pass]
};

} // namespace shadowkit::gl
