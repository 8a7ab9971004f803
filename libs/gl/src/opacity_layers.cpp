#include "opacity_layers.h"

#include "gl_shaders.h"
#include "program.h"
#include "uniforms.h"

#include <algorithm>
#include <string>

namespace shadowkit::gl {
core::Result<std::unique_ptr<OpacityLayers>> OpacityLayers::create() {
    auto layers = std::unique_ptr<OpacityLayers>(new OpacityLayers);
    using namespace shaders;
    for (const bool first : {true, false}) {
        const std::string name = first ? "opacity layers, first leaf" : "opacity layers, transmittance";
        auto program =
            buildProgram(name, {kMaterialVariant[1], kDepthPassGlsl, kVisibleGlsl, kImpostorGlsl, kDepthVert},
                         {kMaterialVariant[1], first ? "#define SK_OPACITY_FIRST 1\n" : "", kDepthPassGlsl,
                          kMaterialGlsl, kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kOpacityFrag});
        if (!program) return program.errorInfo();
        (first ? layers->m_first : layers->m_transmittance) = std::move(program).value();
    }
    auto prefilter = buildProgram("opacity layers, prefiltered", {kFullscreenVert},
                                  {kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kOpacityPrefilterFrag});
    if (!prefilter) return prefilter.errorInfo();
    layers->m_prefilter = std::move(prefilter).value();
    auto downsample = buildProgram("opacity layers, downsampled", {kFullscreenVert}, {kOpacityDownsampleFrag});
    if (!downsample) return downsample.errorInfo();
    layers->m_downsample = std::move(downsample).value();
    layers->m_framebuffer = createFramebuffer();
    layers->m_firstFramebuffer = createFramebuffer();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao); // attribute-less: the prefilter's triangle comes from gl_VertexID
    layers->m_emptyVertexArray = VertexArray(vao);
    return layers;
}

std::vector<OpacityView> opacityViewsOf(const core::ShadowSetup& setup, int size) {
    std::vector<OpacityView> views;
    for (size_t i = 0; i < setup.views.size(); ++i)
        views.push_back({.layer = static_cast<int>(i),
                         .viewport = {0, 0, size},
                         .clipFromWorld = setup.views[i].clipFromWorld,
                         .linearDepthFromWorld = setup.views[i].linearDepthFromWorld});
    return views;
}

bool OpacityLayers::holds(int width, int height, int layers, int mipLevels) const {
    return m_width == width && m_height == height && m_count == layers &&
           m_mipLevels == std::clamp(mipLevels, 1, fullMipLevels(width, height));
}

core::Status OpacityLayers::prepare(int width, int height, int layers, int mipLevels, const std::string& field) {
    if (holds(width, height, layers, mipLevels)) return core::Ok{};
    m_levelViews.clear(), m_firstDepth.reset(), m_layers.reset(), m_prefiltered.reset(), m_nearestLeaf.reset();
    while (glGetError() != GL_NO_ERROR) {
    }
    m_firstDepth = createMapLayers(GL_R32F, width, height, layers, GL_NEAREST, 1);
    m_layers =
        createMapLayers(GL_RGBA16F, width, height, layers, GL_NEAREST, 1); // read texel by texel, as the first depth
    m_prefiltered = createMapLayers(GL_RG16F, width, height, layers, GL_LINEAR, mipLevels);
    m_nearestLeaf = createTexture2D(GL_DEPTH_COMPONENT32F, width, height);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        m_firstDepth.reset(), m_layers.reset(), m_prefiltered.reset(), m_nearestLeaf.reset();
        m_width = m_height = m_count = m_mipLevels = 0;
        return core::environmentError(field + ": the GL driver is out of memory for opacity layers of " +
                                          std::to_string(layers) + " × " + std::to_string(width) + " × " +
                                          std::to_string(height) + " texels (17 bytes a texel, 4 more in one layer)",
                                      field);
    }
    glNamedFramebufferTexture(m_firstFramebuffer.id(), GL_DEPTH_ATTACHMENT, m_nearestLeaf.id(), 0);
    m_width = width, m_height = height, m_count = layers;
    m_mipLevels = std::clamp(mipLevels, 1, fullMipLevels(width, height));
    for (int level = 0; level + 1 < m_mipLevels; ++level)
        m_levelViews.push_back(createLevelView(m_prefiltered, GL_TEXTURE_2D_ARRAY, GL_RG16F, level, layers));
    return core::Ok{};
}

DrawStats OpacityLayers::draw(const GpuScene& scene, const core::BiasSettings& bias, const core::Vec3& wsTowardsSun,
                              std::span<const OpacityView> views, const CasterLists& casters, const Buffer& depthPass,
                              bool depthClamp) {
    // Both sides of every leaf, and no depth test but the first draw's: in the layers each fragment
    // of each leaf counts once.
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    // The depth pass's slope-scaled offset would push a steep leaf behind a flat one at nearly its
    // depth, and the first draw's depth test must order the leaves as their linear depths do.
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (depthClamp) glEnable(GL_DEPTH_CLAMP); // casters before the near plane, as the depth pass
    glEnable(GL_BLEND);
    glEnable(GL_SCISSOR_TEST);
    glBindBufferBase(GL_UNIFORM_BUFFER, kDepthPassBinding, depthPass.id());
    const PassPrograms first{.material = m_first.id(), .batches = PassPrograms::Batches::AlphaTested};
    const PassPrograms transmittance{.material = m_transmittance.id(), .batches = PassPrograms::Batches::AlphaTested};
    const size_t count = std::min(views.size(), casters.lists.size());
    // View i's uniforms, viewport and scissor (its clears and draws stay inside it: a page's slot).
    const auto placeAt = [&](size_t i) {
        const OpacityView& view = views[i];
        DepthPassUniforms uniforms = depthPassUniformsFor(view.clipFromWorld, bias, wsTowardsSun);
        uniforms.linearDepthFromWorld = glm::vec4(view.linearDepthFromWorld);
        uploadToBuffer(depthPass.id(), 0, sizeof uniforms, &uniforms);
        glViewport(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.z);
        glScissor(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.z);
    };
    // View i's alpha-tested casters with `programs`.
    const auto drawLeaves = [&](size_t i, const PassPrograms& programs) {
        const OpacityView& view = views[i];
        if (!view.clustersInView) return casters.draw(scene, i, programs, nullptr);
        const std::vector<visibility::HalfSpace> volume = visibility::clipVolume(view.clipFromWorld, false);
        return casters.draw(scene, i, programs, &volume);
    };
    DrawStats draws;

    // Every view's first leaf, then every view's transmittance: each draw counted over all views
    // by one query (one may be active per target). The first leaf: depth-tested, so that a leaf
    // behind one already drawn — the cards come nearest the sun first — is rejected before it is
    // shaded; GL_MIN settles ties (casters clamped to the near plane all at depth 0 pass
    // GL_LEQUAL). The depth buffer, one layer, is cleared for each view: the second loop needs it
    // no more.
    glBindFramebuffer(GL_FRAMEBUFFER, m_firstFramebuffer.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glBlendEquation(GL_MIN);
    m_firstSamples.begin();
    for (size_t i = 0; i < count; ++i) {
        placeAt(i);
        glNamedFramebufferTextureLayer(m_firstFramebuffer.id(), GL_COLOR_ATTACHMENT0, m_firstDepth.id(), 0,
                                       views[i].layer);
        const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f}; // no leaf: the far end of the map's depth
        glClearNamedFramebufferfv(m_firstFramebuffer.id(), GL_COLOR, 0, far);
        glDepthMask(GL_TRUE); // before the clear, which it masks
        const float farthest = 1.0f;
        glClearNamedFramebufferfv(m_firstFramebuffer.id(), GL_DEPTH, 0, &farthest);
        draws += drawLeaves(i, first);
    }
    m_firstSamples.end();
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);

    // The transmittance: no depth test, every fragment of every leaf multiplied into its layer.
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR); // destination × source: the layer's leaves multiply
    glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
    m_leafSamples.begin();
    for (size_t i = 0; i < count; ++i) {
        placeAt(i);
        glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_layers.id(), 0, views[i].layer);
        const float clear[4] = {1.0f, 1.0f, 1.0f, 1.0f}; // no leaf lets all the light through
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_COLOR, 0, clear);
        glProgramUniform1i(m_transmittance.id(), kOpacityLayerLocation, views[i].layer);
        draws += drawLeaves(i, transmittance);
    }
    m_leafSamples.end();
    glBindTextureUnit(kOpacityFirstUnit, 0); // the next frame's first draw writes it
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_DEPTH_CLAMP);
    if (!views.empty()) prefilter(views); // still with no depth test: one triangle over each view
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    return draws;
}

void OpacityLayers::prefilter(std::span<const OpacityView> views) const {
    glUseProgram(m_prefilter.id());
    glBindVertexArray(m_emptyVertexArray.id());
    glBindTextureUnit(kOpacityUnit, m_layers.id());
    glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
    int attached = -1; // attached once a layer, not once a view (a virtual atlas's pages share one)
    for (const OpacityView& view : views) {
        if (view.layer != attached) {
            attached = view.layer;
            glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_prefiltered.id(), 0, attached);
        }
        glViewport(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.z);
        glScissor(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.z);
        glProgramUniform1i(m_prefilter.id(), kOpacityLayerLocation, view.layer);
        // The linear depth row's gradient is 1 / the map's depth range in metres.
        glProgramUniform1f(m_prefilter.id(), kOpacityDepthPerMetreLocation,
                           static_cast<float>(glm::length(core::Vec3(view.linearDepthFromWorld))));
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    if (m_mipLevels > 1) {
        const bool wholeLayers = m_width == m_height && std::ranges::all_of(views, [&](const OpacityView& v) {
                                     return v.viewport == glm::ivec3(0, 0, m_width);
                                 });
        if (wholeLayers)
            glGenerateTextureMipmap(m_prefiltered.id());
        else
            downsample(views);
    }
    glBindVertexArray(0);
}

void OpacityLayers::downsample(std::span<const OpacityView> views) const {
    glUseProgram(m_downsample.id());
    for (int level = 1; level < m_mipLevels; ++level) {
        glBindTextureUnit(kOpacityPrefilteredUnit, m_levelViews[size_t(level - 1)].id());
        const glm::ivec2 size(std::max(m_width >> level, 1), std::max(m_height >> level, 1));
        int attached = -1; // attached once a layer, not once a view (a virtual atlas's pages share one)
        for (const OpacityView& view : views) {
            if (view.layer != attached) {
                attached = view.layer;
                glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_COLOR_ATTACHMENT0, m_prefiltered.id(), level,
                                               attached);
            }
            // The level's texels that hold any of the view's: its corner rounded down, its far
            // edge up (those straddle a neighbour, as the driver's chain's do).
            const glm::ivec2 from = glm::ivec2(view.viewport) >> level;
            const glm::ivec2 to =
                glm::min((glm::ivec2(view.viewport) + view.viewport.z + (1 << level) - 1) >> level, size);
            glViewport(from.x, from.y, to.x - from.x, to.y - from.y);
            glScissor(from.x, from.y, to.x - from.x, to.y - from.y);
            glProgramUniform1i(m_downsample.id(), kOpacityLayerLocation, view.layer);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
}

int64_t OpacityLayers::bytes() const {
    // R32F and RGBA16F: 4 + 8 bytes a texel; RG16F, 4, and each mip level a quarter of the one
    // before; and the first draw's depth test, 4 bytes a texel of one layer.
    int64_t prefiltered = 0;
    for (int level = 0; level < m_mipLevels; ++level)
        prefiltered += int64_t(std::max(m_width >> level, 1)) * std::max(m_height >> level, 1) * 4;
    return (int64_t(m_width) * m_height * 12 + prefiltered) * m_count + int64_t(m_width) * m_height * 4;
}

void OpacityLayers::bind() const {
    glBindTextureUnit(kOpacityUnit, m_layers.id());
    glBindTextureUnit(kOpacityFirstUnit, m_firstDepth.id());
    glBindTextureUnit(kOpacityPrefilteredUnit, m_prefiltered.id());
}

} // namespace shadowkit::gl
