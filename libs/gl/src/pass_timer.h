// The GPU time of one pass, read after the frame.
#pragma once

#include "gl_object.h"

#include "shadowkit/gl/read_backs.h"

namespace shadowkit::gl {

// Measures the GPU time of the commands between begin() and end() with two timestamp
// queries. (A GL_TIME_ELAPSED query around the layered shadow pass came back as an absolute
// time on Mesa llvmpipe, ~4e6 ms; timestamps do not depend on how the driver splits the work.)
class PassTimer {
public:
    PassTimer() {
        GLuint ids[2] = {0, 0};
        glCreateQueries(GL_TIMESTAMP, 2, ids);
        m_start = Query(ids[0]);
        m_end = Query(ids[1]);
    }
    void begin() const { glQueryCounter(m_start.id(), GL_TIMESTAMP); }
    void end() {
        glQueryCounter(m_end.id(), GL_TIMESTAMP);
        m_stamped = true;
    }
    // Waits for the end stamp (a synchronisation, counted): call it after the frame is
    // submitted, not between its passes. 0 before the first end().
    double milliseconds() const {
        if (!m_stamped) return 0.0;
        detail::countReadBack();
        GLuint64 start = 0, end = 0;
        glGetQueryObjectui64v(m_start.id(), GL_QUERY_RESULT, &start);
        glGetQueryObjectui64v(m_end.id(), GL_QUERY_RESULT, &end);
        return end > start ? static_cast<double>(end - start) * 1e-6 : 0.0;
    }

    // The stamps, for a late read on the GPU (gpu_figures.h); false before the first end().
    bool stamped() const { return m_stamped; }
    GLuint startQuery() const { return m_start.id(); }
    GLuint endQuery() const { return m_end.id(); }

private:
    Query m_start, m_end;
    bool m_stamped = false;
};

} // namespace shadowkit::gl
