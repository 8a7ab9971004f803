#include "opacity_layers.h"

#include "gl_shaders.h"
#include "program.h"
#include "uniforms.h"

#include <string>

namespace shadowkit::gl {
core::Result<std::unique_ptr<OpacityLayers>> OpacityLayers::create() {
    auto layers = std::unique_ptr<OpacityLayers>(new OpacityLayers);
    using namespace shaders;
    for (const bool first : {true, false}) {
        const std::string name = first ? "opacity layers, first leaf" : "opacity layers, transmittance";
        auto program = buildProgram(name, {kMaterialVariant[1], kDepthPassGlsl, kVisibleGlsl, kDepthVert},
                                    {kMaterialVariant[1], first ? "#define SK_OPACITY_FIRST 1\n" : "", kDepthPassGlsl,
                                     kMaterialGlsl, kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kOpacityFrag});
        if (!program) return program.errorInfo();
        (first ? layers->m_first : layers->m_transmittance) = std::move(program).value();
    }
    auto prefilter = buildProgram("opacity layers, prefiltered", {kFullscreenVert},
                                  {kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kOpacityPrefilterFrag});
    if (!prefilter) return prefilter.errorInfo();
    layers->m_prefilter = std::move(prefilter).value();
    layers->m_framebuffer = createFramebuffer();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao); // attribute-less: the prefilter's triangle comes from gl_VertexID
    layers->m_emptyVertexArray = VertexArray(vao);
    return layers;
}

core::Status OpacityLayers::prepare(int size, int layers) {
    if (m_size == size && m_count == layers) return core::Ok{};
    m_firstDepth.reset(), m_layers.reset(), m_prefiltered.reset(); // the old ones go first
    while (glGetError() != GL_NO_ERROR) {
    }
    m_firstDepth = createMapLayers(GL_R32F, size, layers, GL_NEAREST);
    m_layers = createMapLayers(GL_RGBA16F, size, layers, GL_NEAREST); // read texel by texel, as the first depth
    m_prefiltered = createMapLayers(GL_RG16F, size, layers, GL_LINEAR, /*mipmapped=*/true);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        m_firstDepth.reset(), m_layers.reset(), m_prefiltered.reset();
        m_size = m_count = 0;
        return core::environmentError("map_size: the GL driver is out of memory for opacity layers of " +
                                          std::to_string(layers) + " × " + std::to_string(size) +
                                          "² (17 bytes a texel)",
                                      "map_size");
    }
    m_size = size, m_count = layers;
    return core::Ok{};
}

DrawStats OpacityLayers::draw(const GpuScene& scene, const core::ShadowSetup& setup, const core::BiasSettings& bias,
                              std::span<const PassList> lists, const Buffer& depthPass) const {
    // No depth test and both sides of every leaf: each fragment of each leaf counts once.
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    if (setup.depthClamp) glEnable(GL_DEPTH_CLAMP); // casters before the near plane, as the depth pass
    glEnable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    glViewport(0, 0, m_size, m_size);
    glBindBufferBase(GL_UNIFORM_BUFFER, kDepthPassBinding, depthPass.id());
    const PassPrograms first{.material = m_first.id(), .batches = PassPrograms::Batches::AlphaTested};
    const PassPrograms transmittance{.material = m_transmittance.id(), .batches = PassPrograms::Batches::AlphaTested};
    DrawStats draws;
    for (size_t layer = 0; layer < setup.views.size() && layer < lists.size(); ++layer) {
        const DepthPassUniforms uniforms = depthPassUniformsFor(setup.views[layer], bias);
        glNamedBufferSubData(depthPass.id(), 0, sizeof uniforms, &uniforms);
        const auto l = static_cast<GLint>(layer);

        glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_firstDepth.id(), 0, l);
        const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f}; // no leaf: the far end of the map's depth
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_COLOR, 0, far);
        glBlendEquation(GL_MIN);
        draws += scene.draw(lists[layer], first);

        glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_layers.id(), 0, l);
        const float clear[4] = {1.0f, 1.0f, 1.0f, 1.0f}; // no leaf lets all the light through
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_COLOR, 0, clear);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ZERO, GL_SRC_COLOR); // destination × source: the layer's leaves multiply
        glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
        glProgramUniform1i(m_transmittance.id(), kOpacityLayerLocation, l);
        draws += scene.draw(lists[layer], transmittance);
        glBindTextureUnit(kOpacityFirstUnit, 0); // the next layer's first pass writes it
    }
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_DEPTH_CLAMP);
    prefilter(setup); // still with no depth test: one triangle over each whole layer
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    return draws;
}

void OpacityLayers::prefilter(const core::ShadowSetup& setup) const {
    glUseProgram(m_prefilter.id());
    glBindVertexArray(m_emptyVertexArray.id());
    glBindTextureUnit(kOpacityUnit, m_layers.id());
    glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
    for (size_t layer = 0; layer < setup.views.size() && layer < size_t(m_count); ++layer) {
        const auto l = static_cast<GLint>(layer);
        glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_prefiltered.id(), 0, l);
        glProgramUniform1i(m_prefilter.id(), kOpacityLayerLocation, l);
        // The linear depth row's gradient is 1 / the map's depth range in metres.
        glProgramUniform1f(m_prefilter.id(), kOpacityDepthPerMetreLocation,
                           static_cast<float>(glm::length(core::Vec3(setup.views[layer].linearDepthFromWorld))));
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindVertexArray(0);
    glGenerateTextureMipmap(m_prefiltered.id());
}

void OpacityLayers::bind() const {
    glBindTextureUnit(kOpacityUnit, m_layers.id());
    glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
    glBindTextureUnit(kOpacityPrefilteredUnit, m_prefiltered.id());
}

} // namespace shadowkit::gl
