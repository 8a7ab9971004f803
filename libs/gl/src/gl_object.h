// Move-only RAII owners of GL object names, one type per object kind. Private to
// shadowkit::gl: raw GLuint names never appear in a public header.
#pragma once

#include "shadowkit/gl/read_backs.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace shadowkit::gl {

template <void (*Destroy)(GLuint)>
class GlObject {
public:
    GlObject() = default;
    explicit GlObject(GLuint id) : m_id(id) {}
    GlObject(GlObject&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            m_id = std::exchange(other.m_id, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    ~GlObject() { reset(); }

    GLuint id() const { return m_id; }
    explicit operator bool() const { return m_id != 0; }
    void reset() {
        if (m_id) Destroy(m_id);
        m_id = 0;
    }

private:
    GLuint m_id = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }
inline void deleteProgram(GLuint id) { glDeleteProgram(id); }
inline void deleteShader(GLuint id) { glDeleteShader(id); }
inline void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }
} // namespace detail

using Buffer = GlObject<detail::deleteBuffer>;
using Texture = GlObject<detail::deleteTexture>;
using Framebuffer = GlObject<detail::deleteFramebuffer>;
using VertexArray = GlObject<detail::deleteVertexArray>;
using Query = GlObject<detail::deleteQuery>;
using Program = GlObject<detail::deleteProgram>;
using Shader = GlObject<detail::deleteShader>;
using Sampler = GlObject<detail::deleteSampler>;

// Immutable storage; buffers created without data, or `updatable`, take glNamedBufferSubData.
// Initial data counts as uploaded (read_backs.h).
inline Buffer createBuffer(const void* data, size_t bytes, bool updatable = false) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, data && !updatable ? 0 : GL_DYNAMIC_STORAGE_BIT);
    if (data) detail::countUpload(static_cast<int64_t>(bytes));
    return Buffer(id);
}

// GL's moves of data between CPU and GPU, each counting its bytes (read_backs.h): every buffer
// upload and read and every texture read of libs/gl goes through one of these. (The caller
// counts the synchronisation a read is, once per wait: detail::countReadBack.)
// glNamedBufferSubData.
inline void uploadToBuffer(GLuint buffer, GLintptr offset, GLsizeiptr bytes, const void* data) {
    glNamedBufferSubData(buffer, offset, bytes, data);
    detail::countUpload(static_cast<int64_t>(bytes));
}
// glGetNamedBufferSubData.
inline void readBuffer(GLuint buffer, GLintptr offset, GLsizeiptr bytes, void* out) {
    glGetNamedBufferSubData(buffer, offset, bytes, out);
    detail::countBytesReadBack(static_cast<int64_t>(bytes));
}
// glGetTextureImage.
inline void readTexture(GLuint texture, GLint level, GLenum format, GLenum type, GLsizei bytes, void* out) {
    glGetTextureImage(texture, level, format, type, bytes, out);
    detail::countBytesReadBack(static_cast<int64_t>(bytes));
}
// glCopyNamedBufferSubData into a buffer in host memory the CPU reads later (fenced_read.h).
inline void copyToHost(GLuint source, GLuint host, GLintptr readOffset, GLintptr writeOffset, GLsizeiptr bytes) {
    glCopyNamedBufferSubData(source, host, readOffset, writeOffset, bytes);
    detail::countBytesReadBack(static_cast<int64_t>(bytes));
}

// glDispatchCompute, counted (read_backs.h): every compute pass of libs/gl goes through it, so a
// frame's dispatches and work groups are what GL was asked to run.
inline void dispatchCompute(GLuint groupsX, GLuint groupsY, GLuint groupsZ) {
    glDispatchCompute(groupsX, groupsY, groupsZ);
    detail::countDispatch(int64_t(groupsX) * groupsY * groupsZ);
}

// A sampler that reads a depth texture's stored values, nearest texel, whatever the texture's
// own comparison mode: PCSS's blocker search reads the shadow maps so beside their comparisons.
inline Sampler createRawDepthSampler() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return Sampler(id);
}

inline Framebuffer createFramebuffer() {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    return Framebuffer(fbo);
}

inline Texture createTexture2D(GLenum internalFormat, int width, int height) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, 1, internalFormat, width, height);
    return Texture(id);
}

inline Texture createTexture2DArray(GLenum internalFormat, int width, int height, int layers, int levels = 1) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, levels, internalFormat, width, height, layers);
    return Texture(id);
}

// A view of one mip level of `source` (immutable storage), all `layers` of it: a texture of its
// own, so a pass may read that level while it draws into the next.
inline Texture createLevelView(const Texture& source, GLenum target, GLenum format, int level, int layers) {
    GLuint id = 0;
    glGenTextures(1, &id); // a view takes a name never bound
    glTextureView(id, target, source.id(), format, static_cast<GLuint>(level), 1, 0, static_cast<GLuint>(layers));
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return Texture(id);
}

// The levels of a full mip chain of width × height, 1 × 1 the last.
inline int fullMipLevels(int width, int height) {
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    return levels;
}

// Layers of width × height read through their own filter (GL_NEAREST or GL_LINEAR), clamped at
// the edges: the side textures of the sun's maps (moments, opacity layers) and of the virtual
// page atlas. With `levels` > 1, a mip chain of that many levels (at most a full one) read
// trilinearly (GL_LINEAR): means over squares of 2^k texels.
inline Texture createMapLayers(GLenum internalFormat, int width, int height, int layers, GLint filter, int levels) {
    levels = std::clamp(levels, 1, fullMipLevels(width, height));
    Texture t = createTexture2DArray(internalFormat, width, height, layers, levels);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : filter);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}
// Square layers, with a full mip chain when `mipmapped`.
inline Texture createMapLayers(GLenum internalFormat, int size, int layers, GLint filter, bool mipmapped = false) {
    return createMapLayers(internalFormat, size, size, layers, filter, mipmapped ? std::numeric_limits<int>::max() : 1);
}

} // namespace shadowkit::gl
