// The GPU time of one pass, as two timestamps the frame's figures read (gpu_figures.h).
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
    void end() {
        glQueryCounter(m_end.id(), GL_TIMESTAMP);
        m_stamped = true;
    }
    // The stamps, written into the frame's figures on the GPU; false before the first end().
    bool stamped() const { return m_stamped; }
    GLuint startQuery() const { return m_start.id(); }
    GLuint endQuery() const { return m_end.id(); }

private:
    Query m_start, m_end;
    bool m_stamped = false;
};

} // namespace shadowkit::gl
