// Synchronisations made by libs/gl in this process: GPU-to-CPU reads of data (buffers, textures)
// and waits for a sample query or for a fence. Each one waits for the GPU to
// finish the work before it — a stall on a real GPU — so tests and benches count them as work:
// a frame's claim that one read-back serves two uses is checked here against what GL was asked,
// not against the frame's own bookkeeping. CHC++'s occlusion query waits are counted apart
// (visibility::CoherentCullingStats).
#pragma once

#include <cstdint>

namespace shadowkit::gl {

// Read-backs made so far, by every renderer of the process; compare two readings.
int64_t readBacksMade();

namespace detail {
// Called next to every glGetTextureImage / glGetNamedBufferSubData, blocking query read and
// fence wait in libs/gl.
void countReadBack();
} // namespace detail

} // namespace shadowkit::gl
