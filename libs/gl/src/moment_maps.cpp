#include "moment_maps.h"

#include "gl_shaders.h"
#include "program.h"
#include "uniforms.h"

#include <string>

namespace shadowkit::gl {
namespace {

// moments.comp's uniforms (explicit locations).
constexpr GLint kModeLocation = 0, kStepLocation = 1, kRadiusLocation = 2;

Texture momentTexture(int size, int layers) { return createMapLayers(GL_RGBA32F, size, layers, GL_LINEAR); }

} // namespace

core::Result<std::unique_ptr<MomentMaps>> MomentMaps::create() {
    auto maps = std::unique_ptr<MomentMaps>(new MomentMaps);
    auto program = buildComputeProgram("moment maps", {shaders::kMomentsComp});
    if (!program) return program.errorInfo();
    maps->m_program = std::move(program).value();
    return maps;
}

core::Status MomentMaps::update(const Texture& depth, GLuint rawSampler, int size, int layers, int blurTexels) {
    if (m_size != size || m_layers != layers) {
        m_moments.reset(), m_scratch.reset(); // the old ones go before the new ones are allocated
        while (glGetError() != GL_NO_ERROR) {
        }
        m_moments = momentTexture(size, layers);
        m_scratch = momentTexture(size, layers);
        if (glGetError() == GL_OUT_OF_MEMORY) {
            m_moments.reset(), m_scratch.reset();
            m_size = m_layers = 0;
            return core::environmentError("map_size: the GL driver is out of memory for moment maps of " +
                                              std::to_string(layers) + " × " + std::to_string(size) +
                                              "² (16 bytes a texel, twice)",
                                          "map_size");
        }
        m_size = size, m_layers = layers;
    }
    glUseProgram(m_program.id());
    const auto groups = static_cast<GLuint>((size + 15) / 16);
    // Pass: read `from` (through `sampler`, 0 for its own state) and write `to`.
    auto pass = [&](const Texture& from, GLuint sampler, const Texture& to, int mode, int stepX, int stepY) {
        glBindTextureUnit(kMomentsSourceUnit, from.id());
        glBindSampler(kMomentsSourceUnit, sampler);
        glBindImageTexture(kMomentsImageUnit, to.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glProgramUniform1i(m_program.id(), kModeLocation, mode);
        glProgramUniform2i(m_program.id(), kStepLocation, stepX, stepY);
        glProgramUniform1i(m_program.id(), kRadiusLocation, blurTexels);
        dispatchCompute(groups, groups, static_cast<GLuint>(layers));
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    };
    if (blurTexels == 0) {
        pass(depth, rawSampler, m_moments, 0, 0, 0);
    } else {
        pass(depth, rawSampler, m_scratch, 0, 0, 0);
        pass(m_scratch, 0, m_moments, 1, 1, 0);
        pass(m_moments, 0, m_scratch, 1, 0, 1);
        std::swap(m_moments, m_scratch);
    }
    glBindSampler(kMomentsSourceUnit, 0);
    return core::Ok{};
}

void MomentMaps::bind() const {
    if (m_moments) glBindTextureUnit(kMomentsUnit, m_moments.id());
}

} // namespace shadowkit::gl
