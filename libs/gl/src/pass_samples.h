// The work a pass did per fragment, read after the frame:
//   - samples written: fragments that passed the depth test (GL_SAMPLES_PASSED). In a
//     depth-only pass that is the work that reaches the depth buffer — one per texel with perfect
//     front-to-back order, more with every caster drawn over a nearer one — counted the same on
//     every driver;
//   - fragments shaded: fragment-shader invocations (GL_FRAGMENT_SHADER_INVOCATIONS,
//     ARB_pipeline_statistics_query, core in GL 4.6), where the driver counts them. Against the
//     samples written it says whether depth tests ran before the shader: a fragment an early
//     test rejects is never shaded, one a late test rejects (a shader that may discard, as an
//     alpha test does, can keep a GPU's test late) is shaded and thrown away. llvmpipe's
//     counter is no count of shaded fragments: the leafy forest's shadow pass gave exactly its
//     samples written (5,980,912 of each), and a probe with a shader discarding every other pixel
//     0 (docs/benchmarking.md): there it says nothing.
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
        if (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
            glCreateQueries(GL_FRAGMENT_SHADER_INVOCATIONS, 1, &id);
            m_invocations = Query(id);
        }
    }
    // One pass at a time: GL allows one active query per target (the camera's occlusion queries
    // run in its pre-pass, never inside a counted pass).
    void begin() {
        glBeginQuery(GL_SAMPLES_PASSED, m_query.id());
        if (m_invocations.id() != 0) glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, m_invocations.id());
        m_counted = true;
    }
    void end() const {
        glEndQuery(GL_SAMPLES_PASSED);
        if (m_invocations.id() != 0) glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
    }
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
    // This pass's queries, for a late read on the GPU (gpu_figures.h); counted() false: none.
    // shadedQuery() is 0 where the driver has no invocation counter.
    bool counted() const { return m_counted; }
    GLuint query() const { return m_query.id(); }
    GLuint shadedQuery() const { return m_invocations.id(); }

private:
    Query m_query;
    Query m_invocations;
    bool m_counted = false;
};

} // namespace shadowkit::gl
