// The camera passes' programs — the main pass (main.frag), the eval pass (eval.frag) and the
// eval pass that shades the main pass's colour too (eval.frag with SK_EVAL_SHADED, built on
// first use) — each plain and with materials (gpu_scene.h's PassPrograms), and in two variants each:
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
    // Builds the variant `virtualMaps` of the main and eval passes, once; what the driver says
    // if it cannot.
    core::Status prepare(bool virtualMaps);
    // Builds the variant `virtualMaps` of the shaded eval pass, once.
    core::Status prepareShadedEval(bool virtualMaps);
    // A prepared variant's programs. The main pass shades colour (textures matter to every
    // textured batch); the eval pass only coverage.
    PassPrograms main(bool virtualMaps) const {
        return {m_programs[virtualMaps][0][0].id(), m_programs[virtualMaps][0][1].id(), true};
    }
    PassPrograms eval(bool virtualMaps) const {
        return {m_programs[virtualMaps][1][0].id(), m_programs[virtualMaps][1][1].id(), false};
    }
    // The eval pass's buffers and the main pass's colour: textures matter as in the main pass.
    PassPrograms shadedEval(bool virtualMaps) const {
        return {m_programs[virtualMaps][2][0].id(), m_programs[virtualMaps][2][1].id(), true};
    }

private:
    // The programs of one pass and variant, plain and with materials, unless built already.
    core::Status build(bool virtualMaps, int pass);
    Program m_programs[2][3][2]; // [virtual maps][main, eval, shaded eval][material]
};

} // namespace shadowkit::gl
