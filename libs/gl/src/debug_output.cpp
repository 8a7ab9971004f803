#include "debug_output.h"

#include <epoxy/gl.h>

#include <cstdio>

namespace shadowkit::gl {
namespace {

void GLAPIENTRY onMessage(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                          const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    // A broken state repeats the same message every draw; print each id a few times only
    // so a bug shows up as a line, not a wall.
    static int printed = 0;
    static GLuint lastId = 0;
    if (id == lastId && ++printed > 3) return;
    if (id != lastId) printed = 0;
    lastId = id;
    std::fprintf(stderr, "shadowkit: GL %s: %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "warning", message);
}

} // namespace

void installDebugOutput() {
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onMessage, nullptr);
}

} // namespace shadowkit::gl
