// The samples a pass wrote: fragments that passed the depth test (GL_SAMPLES_PASSED), read
// after the frame. In a depth-only pass that is the work that reaches the depth buffer — one
// per texel with perfect front-to-back order, more with every caster drawn over a nearer one —
// and, unlike fragment-shader invocations, counted the same on every driver (llvmpipe counts
// every invocation whether or not early depth tests reject it).
#pragma once

#include "gl_object.h"

#include "shadowkit/gl/read_backs.h"

#include <cstdint>

namespace shadowkit::gl {

class PassSamples {
public:
    PassSamples() {
        GLuint id = 0;
        glCreateQueries(GL_SAMPLES_PASSED, 1, &id);
        m_query = Query(id);
    }
    // One pass at a time: GL allows one active GL_SAMPLES_PASSED query (the camera's occlusion
    // queries run in its pre-pass, never inside a shadow pass).
    void begin() {
        glBeginQuery(GL_SAMPLES_PASSED, m_query.id());
        m_counted = true;
    }
    void end() const { glEndQuery(GL_SAMPLES_PASSED); }
    // Waits for the result (a synchronisation, counted): call it after the frame is submitted.
    // 0 when nothing was counted.
    uint64_t samples() const {
        GLuint64 n = 0;
        if (!m_counted) return n;
        detail::countReadBack();
        glGetQueryObjectui64v(m_query.id(), GL_QUERY_RESULT, &n);
        return n;
    }
    void reset() { m_counted = false; }
    // This pass's query, for a late read on the GPU (gpu_figures.h); counted() false: none.
    bool counted() const { return m_counted; }
    GLuint query() const { return m_query.id(); }

private:
    Query m_query;
    bool m_counted = false;
};

} // namespace shadowkit::gl
