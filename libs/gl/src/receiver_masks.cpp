#include "receiver_masks.h"

#include "gl_shaders.h"
#include "program.h"
#include "shadowkit/gl/read_backs.h"
#include "stopwatch.h"
#include "uniforms.h"

#include <cmath>
#include <cstring>

namespace shadowkit::gl {
namespace {

// Inverse of encodeDepth in receiver_mask.comp.
float decodeDepth(uint32_t u) {
    if (u == 0u) return -INFINITY;    // nothing marked
    if (u == 0xFFFFFFFFu) return NAN; // behind the centre: ReceiverMask::finish keeps everything
    const uint32_t bits = (u & 0x80000000u) != 0u ? u & 0x7FFFFFFFu : ~u;
    float d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
}

} // namespace

core::Result<std::unique_ptr<ReceiverMasks>> ReceiverMasks::create() {
    auto masks = std::unique_ptr<ReceiverMasks>(new ReceiverMasks);
    auto program = buildComputeProgram("receiver mask pass", {shaders::kReceiverMaskComp});
    if (!program) return program.errorInfo();
    if (auto s = checkUniformBlock(*program, "receiver mask pass", "ReceiverMask", sizeof(ReceiverMaskUniforms),
                                   receiverMaskFields());
        !s)
        return s.errorInfo();
    masks->m_program = std::move(program).value();
    auto dilate = buildComputeProgram("receiver mask dilation", {shaders::kReceiverDilateComp});
    if (!dilate) return dilate.errorInfo();
    masks->m_dilateProgram = std::move(dilate).value();
    masks->m_uniforms = createBuffer(nullptr, sizeof(ReceiverMaskUniforms));
    return masks;
}

void ReceiverMasks::mark(const CameraDepthTarget& target, const core::PerspectiveCamera& camera,
                         const core::ShadowSetup& setup) {
    const int maps = static_cast<int>(setup.views.size());
    const bool linear = setup.depthLayout == core::DepthLayout::Linear;
    ReceiverMaskUniforms u{};
    u.worldFromClip = glm::mat4(glm::inverse(camera.clipFromWorld()));
    u.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    u.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    for (int m = 0; m < maps; ++m) {
        u.mapClipFromWorld[m] = glm::mat4(setup.views[size_t(m)].clipFromWorld);
        u.mapLinearDepthFromWorld[m] = glm::vec4(setup.views[size_t(m)].linearDepthFromWorld);
    }
    u.mapCount = maps;
    u.linearLayout = linear ? 1 : 0;
    u.maskSize = kReceiverMaskSize;
    uploadToBuffer(m_uniforms.id(), 0, sizeof u, &u);

    const size_t texels = size_t(maps) * kReceiverMaskSize * kReceiverMaskSize;
    if (texels > m_texelCapacity) {
        m_texelCapacity = texels;
        m_texels = createBuffer(nullptr, texels * sizeof(uint32_t));
        // The dilated masks (and their scratch) hold a flag per map after the texels.
        m_scratch = createBuffer(nullptr, (texels + size_t(maps)) * sizeof(uint32_t));
        m_dilated = createBuffer(nullptr, (texels + size_t(maps)) * sizeof(uint32_t));
    }
    const uint32_t zero = 0;
    glClearNamedBufferSubData(m_texels.id(), GL_R32UI, 0, GLsizeiptr(texels * sizeof(uint32_t)), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glUseProgram(m_program.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kReceiverMaskBinding, m_uniforms.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaskBinding, m_texels.id());
    glBindTextureUnit(kReceiverDepthUnit, target.viewDepth.id());
    dispatchCompute(GLuint(target.width + 7) / 8, GLuint(target.height + 7) / 8, 1);
}

const std::vector<visibility::ReceiverMask>& ReceiverMasks::build(const CameraDepthTarget& target,
                                                                  const core::PerspectiveCamera& camera,
                                                                  const core::ShadowSetup& setup,
                                                                  double dilationTexels) {
    const Stopwatch inGl;
    mark(target, camera, setup);
    const int maps = static_cast<int>(setup.views.size());
    const bool linear = setup.depthLayout == core::DepthLayout::Linear;
    const size_t texels = size_t(maps) * kReceiverMaskSize * kReceiverMaskSize;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_readBack.resize(texels);
    detail::countReadBack();
    readBuffer(m_texels.id(), 0, GLsizeiptr(texels * sizeof(uint32_t)), m_readBack.data());
    m_gl = inGl.elapsed();

    const int dilation = dilationFor(setup, dilationTexels);
    m_masks.clear();
    for (int m = 0; m < maps; ++m) {
        const core::ShadowView& view = setup.views[size_t(m)];
        visibility::ReceiverMask& mask = m_masks.emplace_back(
            kReceiverMaskSize, view.clipFromWorld, linear ? std::optional(view.linearDepthFromWorld) : std::nullopt);
        std::span<float> out = mask.texels();
        const uint32_t* in = m_readBack.data() + size_t(m) * kReceiverMaskSize * kReceiverMaskSize;
        for (size_t t = 0; t < out.size(); ++t) out[t] = decodeDepth(in[t]);
        mask.finish(dilation);
    }
    return m_masks;
}

void ReceiverMasks::markOnGpu(const CameraDepthTarget& target, const core::PerspectiveCamera& camera,
                              const core::ShadowSetup& setup, double dilationTexels) {
    const Stopwatch inGl;
    mark(target, camera, setup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const int maps = static_cast<int>(setup.views.size());
    const GLuint p = m_dilateProgram.id();
    glUseProgram(p);
    glProgramUniform1i(p, glGetUniformLocation(p, "maskSize"), kReceiverMaskSize);
    glProgramUniform1i(p, glGetUniformLocation(p, "mapCount"), maps);
    glProgramUniform1i(p, glGetUniformLocation(p, "dilation"), dilationFor(setup, dilationTexels));
    for (int pass = 0; pass < 2; ++pass) {
        glProgramUniform2i(p, glGetUniformLocation(p, "axis"), pass == 0 ? 1 : 0, pass == 0 ? 0 : 1);
        glProgramUniform1i(p, glGetUniformLocation(p, "firstPass"), pass == 0 ? 1 : 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaskBinding, pass == 0 ? m_texels.id() : m_scratch.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDilatedMaskBinding, pass == 0 ? m_scratch.id() : m_dilated.id());
        dispatchCompute(GLuint(kReceiverMaskSize + 7) / 8, GLuint(kReceiverMaskSize + 7) / 8, GLuint(maps));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    m_gl = inGl.elapsed();
}

int ReceiverMasks::dilationFor(const core::ShadowSetup& setup, double dilationTexels) {
    return static_cast<int>(std::ceil(dilationTexels * kReceiverMaskSize / setup.mapSize)) + 1;
}

} // namespace shadowkit::gl
