// Reading what the GPU wrote without waiting for it: a buffer the CPU keeps mapped while the GPU
// copies into it, and a fence after the copy that the CPU polls with a zero timeout. What engines
// do for anything read back every frame (statistics, virtual page requests): the data arrive a
// frame or more late, and the pipeline never drains. The GPU's figures (gpu_figures.h) and the
// virtual pages' requests (virtual_pages.h) read this way.
#pragma once

#include "gl_object.h"

#include <cstddef>

namespace shadowkit::gl {

// A persistently and coherently mapped buffer for the GPU to copy into and the CPU to read
// (GL_CLIENT_STORAGE_BIT: host memory, where a CPU read is cheap), with the fence of its last
// copy.
class FencedReadBuffer {
public:
    FencedReadBuffer() = default;
    FencedReadBuffer(const FencedReadBuffer&) = delete;
    FencedReadBuffer& operator=(const FencedReadBuffer&) = delete;
    ~FencedReadBuffer() { dropFence(); } // the buffer unmaps as it is deleted

    // At least `bytes` of room; a larger buffer replaces the old one, what it held is lost.
    void reserve(size_t bytes);
    GLuint id() const { return m_buffer.id(); }
    size_t bytes() const { return m_bytes; }
    // What the GPU wrote, once arrived() (or waited()) says its copy is done.
    const void* data() const { return m_mapped; }

    // After the commands that write it: a fence, flushed so that it reaches the GPU and a
    // zero-timeout poll can see it pass.
    void fence();
    bool pending() const { return m_fence != nullptr; }
    // Whether the fence has passed, without waiting (false when none is pending).
    bool arrived() const;
    // Waits until the fence passes (not counted here: the caller counts its read-back); false
    // when the wait fails (a lost context) or none is pending.
    bool waited() const;
    // Forgets the fence: what it guarded is read, or no longer wanted.
    void dropFence();

private:
    Buffer m_buffer;
    void* m_mapped = nullptr;
    size_t m_bytes = 0;
    GLsync m_fence = nullptr;
};

} // namespace shadowkit::gl
