// One RGBA32F pixel that a full-screen triangle draws a program into, read back as four floats:
// how the tests run one function of the installed GLSL at one input (its uniforms) on the real
// rasteriser, as an engine's fragment shader calls it.
#pragma once

#include "gl_object.h"

#include <epoxy/gl.h>

#include <array>
#include <string_view>

namespace shadowkit::gl::testing {

// The vertex stage of such a program: one triangle over the pixel.
inline constexpr std::string_view kFullScreenTriangle = R"glsl(
void main() { gl_Position = vec4(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0, 0.0, 1.0); }
)glsl";

class OnePixelTarget {
public:
    OnePixelTarget() : m_colour(createTexture2D(GL_RGBA32F, 1, 1)), m_framebuffer(createFramebuffer()) {
        glNamedFramebufferTexture(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_colour.id(), 0);
        GLuint id = 0;
        glCreateVertexArrays(1, &id);
        m_vertexArray = VertexArray(id);
    }

    // What `program` (its uniforms set) writes to the pixel.
    std::array<float, 4> draw(GLuint program) const {
        glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
        glViewport(0, 0, 1, 1);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(program);
        glBindVertexArray(m_vertexArray.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::array<float, 4> out{};
        glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, out.data());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return out;
    }

private:
    Texture m_colour;
    Framebuffer m_framebuffer;
    VertexArray m_vertexArray;
};

} // namespace shadowkit::gl::testing
