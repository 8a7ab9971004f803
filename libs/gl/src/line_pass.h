// Coloured world-space segments drawn over a finished frame (Renderer::drawLines): the
// viewer's wireframes of the view frustum, the focus body B and the shadow maps' volumes.
#pragma once

#include "gl_object.h"
#include "program.h"

#include "shadowkit/core/result.h"
#include "shadowkit/gl/render_settings.h"

#include <memory>
#include <span>

namespace shadowkit::gl {

class LinePass {
public:
    static core::Result<std::unique_ptr<LinePass>> create();
    // Into the bound framebuffer, over what it holds (no depth test).
    void draw(const core::Mat4& clipFromWorld, std::span<const LineSegment> lines);

private:
    LinePass() = default;
    Program m_program;
    VertexArray m_vertexArray;
    Buffer m_vertices;
    size_t m_capacity = 0; // segments
};

} // namespace shadowkit::gl
