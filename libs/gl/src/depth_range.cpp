#include "depth_range.h"

#include "gl_shaders.h"
#include "shadowkit/gl/read_backs.h"
#include "uniforms.h"

#include <bit>
#include <cstdint>
#include <limits>

namespace shadowkit::gl {

core::Result<std::unique_ptr<DepthRangeReduction>> DepthRangeReduction::create() {
    auto reduction = std::unique_ptr<DepthRangeReduction>(new DepthRangeReduction);
    auto program = buildComputeProgram("visible depth reduction", {shaders::kDepthRangeComp});
    if (!program) return program.errorInfo();
    reduction->m_program = std::move(program).value();
    reduction->m_range = createBuffer(nullptr, 2 * sizeof(uint32_t));
    return reduction;
}

void DepthRangeReduction::reduce(const CameraDepthTarget& target) {
    const uint32_t empty[2] = {0xFFFFFFFFu, 0u}; // near = +max, far = 0: "nothing drawn"
    uploadToBuffer(m_range.id(), 0, sizeof empty, empty);
    glUseProgram(m_program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRangeBinding, m_range.id());
    glBindTextureUnit(kRangeDepthUnit, target.viewDepth.id());
    dispatchCompute(GLuint(target.width + 15) / 16, GLuint(target.height + 15) / 16, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_pending = true;
}

std::optional<core::Vec2> DepthRangeReduction::read() {
    if (!m_pending) return m_last;
    m_pending = false;
    uint32_t bits[2] = {0, 0};
    detail::countReadBack();
    readBuffer(m_range.id(), 0, sizeof bits, bits);
    m_last.reset();
    if (bits[1] == 0u) return m_last;
    const float zNear = std::bit_cast<float>(bits[0]);
    float zFar = std::bit_cast<float>(bits[1]);
    // One depth only: a thin slab, so [near, far] stays a valid range (as core::visibleDepthRange).
    if (!(zFar > zNear)) zFar = std::nextafter(zNear, std::numeric_limits<float>::infinity());
    m_last = core::Vec2(zNear, zFar);
    return m_last;
}

} // namespace shadowkit::gl
