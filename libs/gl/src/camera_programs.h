// The camera passes' programs — the main pass (main.frag) and the eval pass (eval.frag) —
// each plain and with materials (gpu_scene.h's PassPrograms), and in two variants each:
// with and without virtual maps' lookup (SK_VIRTUAL_MAPS in
// shadow_lookup.glsl). One shader with a uniform branch between the two made llvmpipe run
// both for every technique (the camera pass cost 1.45x; docs/performance.md). The variants
// without virtual maps are built with the renderer, so a driver that rejects the shaders
// fails there; those with them on first use.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"

#include "shadowkit/core/result.h"

namespace shadowkit::gl {

// The camera depth pre-pass of occlusion and GPU culling (camera_depth.frag): view depth for
// the queries, the receiver masks and the visible depth range; alpha-tested holes left open.
core::Result<ProgramPair> buildCameraDepthPrePass(std::string_view name);

class CameraPrograms {
public:
    // Builds the variants without virtual maps.
    static core::Result<CameraPrograms> create();
    // Builds the variant `virtualMaps` of both passes, once; what the driver says if it cannot.
    core::Status prepare(bool virtualMaps);
    // A prepared variant's programs. The main pass shades colour (textures matter to every
    // textured batch); the eval pass only coverage.
    PassPrograms main(bool virtualMaps) const {
        return {m_programs[virtualMaps][0][0].id(), m_programs[virtualMaps][0][1].id(), true};
    }
    PassPrograms eval(bool virtualMaps) const {
        return {m_programs[virtualMaps][1][0].id(), m_programs[virtualMaps][1][1].id(), false};
    }

private:
    Program m_programs[2][2][2]; // [virtual maps][eval pass][material]
};

} // namespace shadowkit::gl
