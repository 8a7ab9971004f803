// Depth programs that draw several views of one pass at once: the virtual pages of a frame, each
// in its slot of the page atlas, and the fixed maps of a set-up (cascades), each in its layer of
// the maps' array. One multi-draw takes a batch's level for all of them; the vertex stage finds
// each draw's view — its matrix and dither origin in a block (PageBlock, kPagesBinding) — and
// sends the primitive to that view's viewport or layer (gl_ViewportIndex or gl_Layer from the
// vertex stage: GL_ARB_shader_viewport_layer_array; the draw's index: GL_ARB_shader_draw_parameters).
#pragma once

#include "gpu_scene.h"
#include "uniforms.h"

#include "shadowkit/core/result.h"

#include <span>

namespace shadowkit::gl {

// Where a view's primitives go: a viewport of one target (pages in an atlas) or a layer of a
// layered target (maps in an array texture).
enum class ViewTarget { Viewport, Layer };

// The depth programs (plain, materials) for `target`, hyperbolic layout; an empty pair where the
// GL cannot draw views together (the caller draws a view at a time).
core::Result<ProgramPair> buildDepthViewPrograms(ViewTarget target);

// Where the programs' next draws find their view (depth.vert's pagePerDraw): every draw of a
// call the same, each draw's index in the call, or each draw's entry in a table
// (GpuScene::drawTogether's second form).
enum class ViewOfDraw : uint32_t { Call = 0, DrawIndex = 1, Table = 2 };
// ... the views counted from block `firstView`, the first in viewport or layer `firstTarget`.
void setViewBases(const PassPrograms& programs, size_t firstView, int firstTarget, ViewOfDraw viewOfDraw);

// The views' blocks into `buffer` (grown to hold them; `capacity` in blocks), bound at kPagesBinding.
void uploadViewBlocks(std::span<const PageBlock> blocks, Buffer& buffer, size_t& capacity);

} // namespace shadowkit::gl
