#include "sun_pass.h"

#include "depth_views.h"
#include "gl_shaders.h"
#include "lookup_reach.h"
#include "program.h"
#include "shadowkit/core/caster_facing.h"
#include "uniforms.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <string>
#include <vector>

namespace shadowkit::gl {

core::Result<std::unique_ptr<SunPass>> SunPass::create() {
    auto pass = std::unique_ptr<SunPass>(new SunPass);
    using namespace shaders;
    for (const bool linear : {false, true})
        for (const bool material : {false, true}) {
            const std::string_view withMaterial = kMaterialVariant[material];
            const std::string_view layout = linear ? "#define SK_LINEAR_DEPTH 1\n" : "";
            const std::string name =
                std::string(linear ? "linear " : "") + (material ? "depth pass, materials" : "depth pass");
            auto depth =
                buildProgram(name, {withMaterial, layout, kDepthPassGlsl, kVisibleGlsl, kImpostorGlsl, kDepthVert},
                             {withMaterial, layout, kDepthPassGlsl, kMaterialGlsl, kDepthFrag});
            if (!depth) return depth.errorInfo();
            if (auto s = checkUniformBlock(*depth, name, "DepthPass", sizeof(DepthPassUniforms), depthPassFields()); !s)
                return s.errorInfo();
            ProgramPair& pair = pass->m_programs[linear];
            (material ? pair.material : pair.plain) = std::move(depth).value();
        }
    auto mapPrograms = buildDepthViewPrograms(ViewTarget::Layer);
    if (!mapPrograms) return mapPrograms.errorInfo();
    pass->m_mapPrograms = std::move(mapPrograms).value();
    pass->m_uniforms = createBuffer(nullptr, sizeof(DepthPassUniforms));
    pass->m_rawDepth = createRawDepthSampler();
    auto moments = MomentMaps::create();
    if (!moments) return moments.errorInfo();
    pass->m_moments = std::move(moments).value();
    auto pages = VirtualPages::create();
    if (!pages) return pages.errorInfo();
    pass->m_pages = std::move(pages).value();
    return pass;
}

core::Status SunPass::prepare(const core::ShadowSetup& setup, const RenderSettings& settings,
                              const core::BiasSettings& bias) {
    const bool linearFilter = settings.filter.kind == core::ShadowFilter::Pcf2;
    if (setup.clipmap) {
        const int guard = guardTexelsFor(lookupFilterFor(setup, settings.filter), bias);
        if (auto s = m_pages->configure(settings.virtualPoolPages, setup.clipmap->pageTexels, guard); !s) return s;
        m_pages->setLinearFilter(linearFilter);
        m_shadow.reset(); // no fixed maps: their memory is the pool's
        if (settings.foliageOpacity) {
            // Laid out as the atlas. The lookup's search reads the prefiltered layers over a
            // square no wider than PCSS's kernel, which the guard band holds: mip levels up to
            // the guard's width, whose blocks stay near their own page.
            const glm::ivec2 atlas = m_pages->atlasTexels();
            const int mipLevels = std::bit_width(static_cast<unsigned>(std::max(guard, 1)));
            const bool kept = m_opacity && m_opacity->holds(atlas.x, atlas.y, 1, mipLevels);
            if (auto s = prepareOpacity(atlas.x, atlas.y, 1, mipLevels, "virtual.pool_pages"); !s) return s;
            if (!kept) m_pages->forget(); // the cached pages' layers are gone with the old textures
        }
        return core::Ok{};
    }
    const int maps = static_cast<int>(setup.views.size());
    if (settings.foliageOpacity) {
        if (auto s = prepareOpacity(setup.mapSize, setup.mapSize, maps, std::numeric_limits<int>::max(), "map_size");
            !s)
            return s;
    }
    if (!m_shadow || m_shadow->size != setup.mapSize || m_shadow->layers != maps) {
        m_shadow.reset(); // the old maps go before the new ones are allocated
        auto target = ShadowTarget::create(setup.mapSize, maps);
        if (!target) return target.errorInfo();
        m_shadow.emplace(std::move(target).value());
    }
    // Hardware 2x2 PCF is the sampler's linear filter; every other filter takes its own taps.
    const GLint filter = linearFilter ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(m_shadow->depth.id(), GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(m_shadow->depth.id(), GL_TEXTURE_MAG_FILTER, filter);
    return core::Ok{};
}

core::Status SunPass::prepareOpacity(int width, int height, int layers, int mipLevels, const std::string& field) {
    if (!m_opacity) {
        auto opacity = OpacityLayers::create();
        if (!opacity) return opacity.errorInfo();
        m_opacity = std::move(opacity).value();
    }
    return m_opacity->prepare(width, height, layers, mipLevels, field);
}

core::Result<PassStats> SunPass::draw(const GpuScene& scene, const core::ShadowSetup& setup,
                                      const RenderSettings& settings, const core::BiasSettings& bias,
                                      const core::Vec3& wsTowardsLight, const CasterLists& mapCasters,
                                      const CasterLists& pageCasters) {
    m_lastVirtual.reset();
    m_samples.reset();
    if (m_opacity) m_opacity->resetCounts();
    m_countedTexels = 0;
    // Night: no sun, no sun maps (the camera passes do not read them).
    if (!settings.sun) {
        m_timer.begin();
        m_timer.end();
        return PassStats{};
    }
    DrawStats draws;
    if (setup.clipmap) {
        // As the fixed maps' pass, one viewport per page (VirtualPages::drawPages).
        glBindFramebuffer(GL_FRAMEBUFFER, m_pages->framebuffer().id());
        beginDepthPass(bias, true, core::DepthLayout::Hyperbolic); // pages store clip depth
        // Samples over the texels of the pages drawn, guard bands and all (their slots): each of
        // those texels is cleared and drawn into, as a fixed map's are.
        const auto pages = m_pages->pagesToRender();
        m_timer.begin();
        if (!pages.empty()) m_samples.begin();
        PassPrograms programs = casterPrograms(core::DepthLayout::Hyperbolic, bias);
        if (settings.foliageOpacity) programs.batches = PassPrograms::Batches::Opaque;
        draws = m_pages->drawPages(scene, programs, bias, wsTowardsLight, pageCasters, m_uniforms);
        if (!pages.empty()) m_samples.end();
        // Opacity layers: each page's into its slot of the layers' atlases, as the fixed maps'.
        if (settings.foliageOpacity && !pages.empty())
            draws += m_opacity->draw(scene, bias, wsTowardsLight, pageOpacityViews(), pageCasters, m_uniforms,
                                     /*depthClamp=*/true);
        m_timer.end();
        if (!pages.empty()) {
            const auto side = uint64_t(m_pages->slotViewport(pages.front().slot).z);
            m_countedTexels = uint64_t(pages.size()) * side * side;
        }
        endDepthPass();
        m_pages->rendered();
        m_lastVirtual = m_pages->stats();
        m_lastVirtual->triangles = draws.triangles;
        m_lastVirtual->pagesCulledOnGpu = static_cast<int>(
            std::ranges::count_if(pageCasters.culled, [](const PassList& list) { return list.indirect >= 0; }));
        if (settings.foliageOpacity) m_lastVirtual->opacityBytes = m_opacity->bytes();
        return PassStats{.instances = draws.instances, .triangles = draws.triangles, .drawCalls = draws.drawCalls};
    }
    glBindFramebuffer(GL_FRAMEBUFFER, m_shadow->framebuffer.id());
    glViewport(0, 0, m_shadow->size, m_shadow->size);
    beginDepthPass(bias, setup.depthClamp, setup.depthLayout);
    m_timer.begin();
    m_samples.begin();
    using enum PassPrograms::Batches;
    draws = drawFixedMaps(scene, setup, bias, wsTowardsLight, mapCasters, settings.foliageOpacity ? Opaque : All,
                          settings.culling != Culling::Off);
    m_samples.end();
    // Opacity layers: the alpha-tested casters, inside the pass's time as the moments are.
    if (settings.foliageOpacity)
        draws += m_opacity->draw(scene, bias, wsTowardsLight, opacityViewsOf(setup, m_shadow->size), mapCasters,
                                 m_uniforms, setup.depthClamp);
    m_countedTexels = uint64_t(m_shadow->size) * uint64_t(m_shadow->size) * setup.views.size();
    // MSM: the maps' moments, blurred, inside the pass's time (a real frame pays them with it).
    core::Status moments = core::Ok{};
    if (settings.filter.kind == core::ShadowFilter::Msm)
        moments =
            m_moments->update(m_shadow->depth, m_rawDepth.id(), m_shadow->size, m_shadow->layers, settings.filter.taps);
    m_timer.end();
    endDepthPass();
    if (!moments) return moments.errorInfo();
    // Time read after the frame, not to stall here.
    return PassStats{.instances = draws.instances, .triangles = draws.triangles, .drawCalls = draws.drawCalls};
}

std::vector<OpacityView> SunPass::pageOpacityViews() const {
    std::vector<OpacityView> views;
    for (const VirtualPages::PageToRender& page : m_pages->pagesToRender()) {
        // A page's map is orthographic: its clip depth z (w = 1) is the linear depth.
        const core::Mat4& m = page.clipFromWorld;
        views.push_back({.viewport = m_pages->slotViewport(page.slot),
                         .clipFromWorld = m,
                         .linearDepthFromWorld = core::Vec4(m[0][2], m[1][2], m[2][2], m[3][2]),
                         .clustersInView = true});
    }
    return views;
}

DrawStats SunPass::drawFixedMaps(const GpuScene& scene, const core::ShadowSetup& setup, const core::BiasSettings& bias,
                                 const core::Vec3& wsTowardsLight, const CasterLists& casters,
                                 PassPrograms::Batches batches, bool byClusters) {
    PassPrograms programs = casterPrograms(setup.depthLayout, bias);
    programs.batches = batches;
    // Each map's volume, for the CPU's lists: a large mesh (a kilometre of terrain) draws in a map
    // only its clusters meeting it — without its near plane, as the lists were culled: where the
    // pass clamps depth, casters between the light and that plane are drawn at depth 0. Culling
    // off: no volume, every cluster.
    m_mapVolumes.resize(setup.views.size());
    for (size_t i = 0; i < setup.views.size(); ++i)
        m_mapVolumes[i] = byClusters ? visibility::clipVolume(setup.views[i].clipFromWorld, false)
                                     : std::vector<visibility::HalfSpace>{};
    if (mapsDrawnTogether(setup, wsTowardsLight, casters))
        return drawMapsTogether(scene, setup, bias, wsTowardsLight, casters, programs);
    DrawStats draws;
    for (size_t layer = 0; layer < setup.views.size(); ++layer) { // one array layer per shadow view
        const core::ShadowView& view = setup.views[layer];
        const DepthPassUniforms uniforms = depthPassUniformsFor(view, bias, wsTowardsLight);
        uploadToBuffer(m_uniforms.id(), 0, sizeof uniforms, &uniforms);
        m_shadow->attachLayer(static_cast<int>(layer));
        const float clearDepth = 1.0f;
        glClearNamedFramebufferfv(m_shadow->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
        setLightFacingFront(view.clipFromWorld, wsTowardsLight);
        draws += casters.draw(scene, layer, programs, &m_mapVolumes[layer]);
    }
    return draws;
}

bool SunPass::mapsDrawnTogether(const core::ShadowSetup& setup, const core::Vec3& wsTowardsLight,
                                const CasterLists& casters) const {
    const size_t maps = setup.views.size();
    if (!m_mapPrograms.plain || maps < 2 || setup.depthLayout != core::DepthLayout::Hyperbolic) return false;
    const auto winding = core::lightFacingWinding(setup.views.front().clipFromWorld, wsTowardsLight);
    for (size_t i = 0; i < maps; ++i)
        if (core::lightFacingWinding(setup.views[i].clipFromWorld, wsTowardsLight) != winding) return false;
    // Lists one a map, in one batch order and buffer: all the CPU's, or all culled on the GPU into
    // consecutive passes (their commands one stride apart).
    const auto alike = [&](std::span<const PassList> lists, bool culled) {
        if (lists.size() != maps) return false;
        const PassList& first = lists.front();
        const int64_t stride = lists[1].indirect - first.indirect;
        for (size_t i = 0; i < maps; ++i) {
            const PassList& list = lists[i];
            if (list.batchOrder != first.batchOrder || list.buffer != first.buffer) return false;
            const bool placed = culled ? first.indirect >= 0 && stride > 0 && list.commands == first.commands &&
                                             list.indirect == first.indirect + int64_t(i) * stride
                                       : list.indirect < 0;
            if (!placed) return false;
        }
        return true;
    };
    return alike(casters.lists, false) && (casters.culled.empty() || alike(casters.culled, true));
}

DrawStats SunPass::drawMapsTogether(const GpuScene& scene, const core::ShadowSetup& setup,
                                    const core::BiasSettings& bias, const core::Vec3& wsTowardsLight,
                                    const CasterLists& casters, PassPrograms programs) {
    programs.plain = m_mapPrograms.plain.id();
    programs.material = programs.material ? m_mapPrograms.material.id() : 0;
    // Each map's matrix in its block (a fixed map's dither origin is its texel grid's, 0); the
    // bias, which all share, in the pass's block.
    std::vector<PageBlock> blocks(setup.views.size());
    for (size_t i = 0; i < blocks.size(); ++i) blocks[i].clipFromWorld = glm::mat4(setup.views[i].clipFromWorld);
    uploadViewBlocks(blocks, m_mapBlocks, m_mapBlockCapacity);
    const DepthPassUniforms shared = depthPassUniformsFor(core::Mat4(1.0), bias, wsTowardsLight);
    uploadToBuffer(m_uniforms.id(), 0, sizeof shared, &shared);
    // Every layer attached, so the vertex stage's gl_Layer picks the map, and one clear clears them all.
    m_shadow->attachAllLayers();
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(m_shadow->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
    setLightFacingFront(setup.views.front().clipFromWorld, wsTowardsLight);
    DrawStats draws;
    if (!casters.culled.empty()) { // culled on the GPU: the draw's index names its map
        setViewBases(programs, 0, 0, ViewOfDraw::DrawIndex);
        draws += scene.drawTogether(casters.culled, programs);
    }
    // The CPU's lists: a table names each draw's map; a large mesh draws, in each map, the
    // clusters meeting its volume (drawFixedMaps).
    setViewBases(programs, 0, 0, ViewOfDraw::Table);
    draws += scene.drawTogether(casters.lists, programs, m_mapVolumes);
    return draws;
}

void SunPass::beginDepthPass(const core::BiasSettings& bias, bool depthClamp, core::DepthLayout layout) const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Caster culling: front-face culling stores the casters' back sides (Scherzer 2005 §4.2);
    // back-face culling of closed casters stores the same depths without bias for fewer samples
    // (not with slope-scaled offset: core/bias.h). Each
    // map sets which winding faces the light (setLightFacingFront); GpuScene keeps open levels,
    // double-sided materials and mirrored instances two-sided where asked.
    if (bias.cull == core::CasterCull::None) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(bias.cull == core::CasterCull::Front ? GL_FRONT : GL_BACK);
    }
    if (depthClamp) glEnable(GL_DEPTH_CLAMP);
    // The slope term only: the constant one is added in depth.vert (why there). Not for the
    // linear layout, whose fragment stage writes its depth and both terms (depth.frag): polygon
    // offset acts on the rasterised depth alone, which would then break the written depth's
    // promise to be no less (depth_pass.glsl's skConservativeClipZ).
    if (layout == core::DepthLayout::Linear) {
        glDisable(GL_POLYGON_OFFSET_FILL);
    } else {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(static_cast<float>(bias.slope), 0.0f);
    }
    glUseProgram(programsFor(layout).plain);
    glBindBufferBase(GL_UNIFORM_BUFFER, kDepthPassBinding, m_uniforms.id());
}

void SunPass::endDepthPass() {
    glFrontFace(GL_CCW); // the camera passes' winding
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);
}

void SunPass::bind(const core::ShadowSetup& setup, const RenderSettings& settings) const {
    if (setup.clipmap) {
        m_pages->bind(setup, settings.virtualBlendBand);
    } else {
        m_pages->bindDisabled();
        if (m_shadow) {
            glBindTextureUnit(kShadowMapUnit, m_shadow->depth.id());
            glBindTextureUnit(kShadowDepthUnit, m_shadow->depth.id());
        }
    }
    if (settings.filter.kind == core::ShadowFilter::Msm) m_moments->bind();
    if (settings.foliageOpacity && m_opacity) m_opacity->bind();
}

scene::Image SunPass::readMaps() const {
    if (m_shadow) return m_shadow->readAsGreys();
    return m_pages->readAtlas(); // virtual maps: the page pool
}

} // namespace shadowkit::gl
