#include "fenced_read.h"

namespace shadowkit::gl {
namespace {

bool passed(GLenum state) { return state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED; }

} // namespace

void FencedReadBuffer::reserve(size_t bytes) {
    if (bytes <= m_bytes) return;
    dropFence();
    GLuint id = 0;
    glCreateBuffers(1, &id);
    const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(id, GLsizeiptr(bytes), nullptr, access | GL_CLIENT_STORAGE_BIT);
    m_buffer = Buffer(id);
    m_mapped = glMapNamedBufferRange(id, 0, GLsizeiptr(bytes), access);
    m_bytes = bytes;
}

void FencedReadBuffer::fence() {
    dropFence();
    m_fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();
}

bool FencedReadBuffer::arrived() const { return m_fence && passed(glClientWaitSync(m_fence, 0, 0)); }

bool FencedReadBuffer::waited() const {
    if (!m_fence) return false;
    // In rounds of a second: a driver may turn a timeout near 2^64 ns into a deadline in the past.
    GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
    for (;;) {
        const GLenum state = glClientWaitSync(m_fence, flags, 1'000'000'000);
        if (passed(state)) return true;
        if (state != GL_TIMEOUT_EXPIRED) return false;
        flags = 0;
    }
}

void FencedReadBuffer::dropFence() {
    if (m_fence) glDeleteSync(m_fence);
    m_fence = nullptr;
}

} // namespace shadowkit::gl
