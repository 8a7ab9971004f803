#include "line_pass.h"

#include "gl_shaders.h"

#include <algorithm>
#include <vector>

namespace shadowkit::gl {

core::Result<std::unique_ptr<LinePass>> LinePass::create() {
    auto pass = std::unique_ptr<LinePass>(new LinePass);
    auto program = buildProgram("line pass", {shaders::kLinesVert}, {shaders::kLinesFrag});
    if (!program) return program.errorInfo();
    pass->m_program = std::move(program).value();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    pass->m_vertexArray = VertexArray(vao);
    for (GLuint attrib = 0; attrib < 2; ++attrib) {
        glEnableVertexArrayAttrib(vao, attrib);
        glVertexArrayAttribFormat(vao, attrib, 3, GL_FLOAT, GL_FALSE, attrib * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao, attrib, 0);
    }
    return pass;
}

void LinePass::draw(const core::Mat4& clipFromWorld, std::span<const LineSegment> lines) {
    if (lines.empty()) return;
    // Per vertex: position, colour (six floats); positions relative to nothing: the frame's
    // own world (float is enough for a viewer's overlay).
    std::vector<float> vertices;
    vertices.reserve(lines.size() * 12);
    for (const LineSegment& l : lines)
        for (const core::Vec3& p : {l.wsFrom, l.wsTo})
            vertices.insert(vertices.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z),
                                             l.color.r, l.color.g, l.color.b});
    if (lines.size() > m_capacity) {
        m_capacity = std::max(lines.size(), 2 * m_capacity);
        m_vertices = createBuffer(nullptr, m_capacity * 12 * sizeof(float));
        glVertexArrayVertexBuffer(m_vertexArray.id(), 0, m_vertices.id(), 0, 6 * sizeof(float));
    }
    uploadToBuffer(m_vertices.id(), 0, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data());
    glUseProgram(m_program.id());
    const glm::mat4 m(clipFromWorld);
    glUniformMatrix4fv(0, 1, GL_FALSE, &m[0][0]);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(m_vertexArray.id());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.size() * 2));
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
}

} // namespace shadowkit::gl
