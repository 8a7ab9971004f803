// The GPU time of one pass, read after the frame.
#pragma once

#include "gl_object.h"

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
    void end() const { glQueryCounter(m_end.id(), GL_TIMESTAMP); }
    // Waits for the end stamp: call it after the frame is submitted, not between its passes.
    double milliseconds() const {
        GLuint64 start = 0, end = 0;
        glGetQueryObjectui64v(m_start.id(), GL_QUERY_RESULT, &start);
        glGetQueryObjectui64v(m_end.id(), GL_QUERY_RESULT, &end);
        return end > start ? static_cast<double>(end - start) * 1e-6 : 0.0;
    }

private:
    Query m_start, m_end;
};

} // namespace shadowkit::gl
