// Synchronous GPU-to-CPU reads of data (buffers, textures) made by libs/gl in this process.
// Each one waits for the GPU to finish all the work before it — a stall on a real GPU — so
// tests and benches count them as work: a frame's claim that one read-back serves two uses is
// checked here against what GL was asked, not against the frame's own bookkeeping. Results of
// occlusion queries are not data read-backs and are not counted here (CHC++'s waits are in
// visibility::CoherentCullingStats).
#pragma once

#include <cstdint>

namespace shadowkit::gl {

// Read-backs made so far, by every renderer of the process; compare two readings.
int64_t readBacksMade();

namespace detail {
// Called next to every glGetTextureImage / glGetNamedBufferSubData in libs/gl.
void countReadBack();
} // namespace detail

} // namespace shadowkit::gl
