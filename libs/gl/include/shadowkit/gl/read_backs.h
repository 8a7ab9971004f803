// Synchronisations made by libs/gl in this process: GPU-to-CPU reads of data (buffers, textures)
// and waits for a sample query or for a fence. Each one waits for the GPU to
// finish the work before it — a stall on a real GPU — so tests and benches count them as work:
// a frame's claim that one read-back serves two uses is checked here against what GL was asked,
// not against the frame's own bookkeeping. CHC++'s occlusion query waits are counted apart
// (visibility::CoherentCullingStats).
//
// Beside them, the bytes libs/gl moves between CPU and GPU, counted where GL is asked to move
// them: uploaded into buffers and textures (a buffer's initial data included), and read back —
// by a synchronous read, or copied by the GPU into host memory for a read frames later
// (fenced_read.h); query results aside (eight bytes each). Per frame, what its lists, uniforms,
// page table and read-backs cost the bus. And the compute passes it dispatched: each dispatch
// and its work groups (the culling, marking and reduction passes' work beside the draws').
#pragma once

#include <cstdint>

namespace shadowkit::gl {

// Read-backs made so far, by every renderer of the process; compare two readings.
int64_t readBacksMade();
// Bytes uploaded and read back so far, by every renderer of the process; compare two readings.
int64_t bytesUploaded();
int64_t bytesReadBack();
// Compute dispatches and their work groups so far, likewise.
int64_t dispatchesMade();
int64_t workGroupsDispatched();

// The counts together: a frame's traffic is the difference of two readings around it.
struct Traffic {
    int64_t readBacks = 0, bytesUploaded = 0, bytesReadBack = 0;
    int64_t dispatches = 0, workGroups = 0;
};
inline Traffic trafficSoFar() {
    return {readBacksMade(), bytesUploaded(), bytesReadBack(), dispatchesMade(), workGroupsDispatched()};
}
inline Traffic operator-(const Traffic& after, const Traffic& before) {
    return {after.readBacks - before.readBacks, after.bytesUploaded - before.bytesUploaded,
            after.bytesReadBack - before.bytesReadBack, after.dispatches - before.dispatches,
            after.workGroups - before.workGroups};
}

namespace detail {
// Called once per wait in libs/gl: before the reads of data that wait (gl_object.h's
// readBuffer and readTexture, one call or several after one wait), a blocking query read, a
// fence wait.
void countReadBack();
// Called next to every upload (gl_object.h's uploadToBuffer and createBuffer, texture uploads)
// and every read (the synchronous reads above, the GPU's copies into fenced read buffers).
void countUpload(int64_t bytes);
void countBytesReadBack(int64_t bytes);
// Called by gl_object.h's dispatchCompute: one dispatch of `workGroups` groups.
void countDispatch(int64_t workGroups);
} // namespace detail

} // namespace shadowkit::gl
