#include "virtual_pages.h"

#include "depth_views.h"
#include "gl_shaders.h"
#include "program.h"
#include "shadowkit/core/caster_facing.h"
#include "shadowkit/gl/read_backs.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <variant>

namespace shadowkit::gl {
namespace {

constexpr int64_t kPoolTexelBudget = int64_t(1) << 24; // 64 MiB of 32-bit depth

} // namespace

PageContent pageContentOf(const core::VirtualClipmap& clipmap, int guardTexels, const core::BiasSettings& bias,
                          const RenderSettings& settings) {
    return {.lightFromWorldRotation = clipmap.lightFromWorldRotation,
            .wsGridOrigin = clipmap.wsGridOrigin,
            .zNear = clipmap.zNear,
            .zFar = clipmap.zFar,
            .pageTexels = clipmap.pageTexels,
            .guardTexels = guardTexels,
            .slopeBias = static_cast<float>(bias.slope),
            .constantBias = static_cast<float>(bias.constant),
            .cull = static_cast<int>(bias.cull),
            .lod = settings.lod,
            .lodTexelError = settings.lodTexelError,
            .lodFoliageScale = settings.lodFoliageScale,
            .lodFade = settings.lodFade,
            .foliageOpacity = settings.foliageOpacity};
}

core::Result<std::unique_ptr<VirtualPages>> VirtualPages::create() {
    auto pages = std::unique_ptr<VirtualPages>(new VirtualPages);
    auto program = buildComputeProgram("virtual page marking", {shaders::kVirtualMarkComp});
    if (!program) return program.errorInfo();
    if (auto s = checkUniformBlock(*program, "virtual page marking", "VirtualMark", sizeof(VirtualMarkUniforms),
                                   virtualMarkFields());
        !s)
        return s.errorInfo();
    pages->m_mark = std::move(program).value();
    auto table = PageTable::create();
    if (!table) return table.errorInfo();
    pages->m_pageTable = std::move(table).value();
    // The page programs (drawPages): where vertex stages read the draw's index and may pick the
    // viewport; else every page is drawn alone with the caller's.
    auto pagePrograms = buildDepthViewPrograms(ViewTarget::Viewport);
    if (!pagePrograms) return pagePrograms.errorInfo();
    pages->m_pagePrograms = std::move(pagePrograms).value();
    if (pages->m_pagePrograms.plain) glGetIntegerv(GL_MAX_VIEWPORTS, &pages->m_viewports); // 16 at least since GL 4.1
    pages->m_markUniforms = createBuffer(nullptr, sizeof(VirtualMarkUniforms));
    pages->m_mapsUniforms = createBuffer(nullptr, sizeof(VirtualMapsUniforms));
    const VirtualMapsUniforms disabled{};
    pages->m_disabledUniforms = createBuffer(&disabled, sizeof disabled);
    return pages;
}

core::Status VirtualPages::configure(int slots, int pageTexels, int guardTexels) {
    const int slotTexels = pageTexels + 2 * guardTexels;
    if (slots == 0) slots = static_cast<int>(kPoolTexelBudget / (int64_t(slotTexels) * slotTexels));
    if (slots == m_cache.slotCount() && pageTexels == m_pageTexels && guardTexels == m_guardTexels) return core::Ok{};
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int perRow = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(std::max(slots, 1)))));
    const int rows = (slots + perRow - 1) / perRow;
    if (slots < 1 || int64_t(perRow) * slotTexels > maxSize || int64_t(rows) * slotTexels > maxSize)
        return core::environmentError("virtual.pool_pages: " + std::to_string(slots) + " pages of " +
                                          std::to_string(slotTexels) + "² texels do not fit a " +
                                          std::to_string(maxSize) + "² texture on this GL driver",
                                      "virtual.pool_pages");
    m_atlas = {};
    m_framebuffer = {};
    glGetError();
    m_atlas = createTexture2DArray(GL_DEPTH_COMPONENT32F, perRow * slotTexels, rows * slotTexels, 1);
    if (glGetError() == GL_OUT_OF_MEMORY)
        return core::environmentError("virtual.pool_pages: out of GPU memory for " + std::to_string(slots) + " pages",
                                      "virtual.pool_pages");
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    m_framebuffer = createFramebuffer();
    glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_DEPTH_ATTACHMENT, m_atlas.id(), 0, 0);
    glNamedFramebufferDrawBuffer(m_framebuffer.id(), GL_NONE);
    glNamedFramebufferReadBuffer(m_framebuffer.id(), GL_NONE);
    if (auto s = checkComplete(m_framebuffer, "virtual page atlas"); !s) return s;
    m_slotsPerRow = perRow;
    m_slotTexels = slotTexels;
    m_pageTexels = pageTexels;
    m_guardTexels = guardTexels;
    m_atlasTexels = {perRow * slotTexels, rows * slotTexels};
    m_cache.configure(slots, guardTexels);
    forget(); // a new atlas holds no page
    return core::Ok{};
}

void VirtualPages::forget() {
    m_cache.dropAll();
    for (MarkSlot& slot : m_marks) slot.read.dropFence();
    m_lastMarksRead = 0;
}

glm::ivec3 VirtualPages::slotViewport(int slot) const {
    return {(slot % m_slotsPerRow) * m_slotTexels, (slot / m_slotsPerRow) * m_slotTexels, m_slotTexels};
}

size_t VirtualPages::mark(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera,
                          const core::ShadowSetup& setup, std::span<const core::ShadowView> views, double reachTexels,
                          Buffer& bits, size_t& capacity) {
    const core::VirtualClipmap& clipmap = *setup.clipmap;
    const int levels = static_cast<int>(views.size());
    const int pages = clipmap.pagesPerSide();
    VirtualMarkUniforms u{};
    u.worldFromClip = glm::mat4(glm::inverse(camera.clipFromWorld()));
    u.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    u.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    for (int l = 0; l < levels; ++l) u.levelClipFromWorld[l] = glm::mat4(views[size_t(l)].clipFromWorld);
    u.levels = levels;
    u.firstExponent = clipmap.firstExponent;
    u.footprintPerMetre = static_cast<float>(clipmap.footprintPerMetre);
    u.lodBias = static_cast<float>(clipmap.lodBias);
    u.pagesPerSide = pages;
    u.pageTexels = clipmap.pageTexels;
    u.reachTexels = static_cast<float>(reachTexels);
    uploadToBuffer(m_markUniforms.id(), 0, sizeof u, &u);
    const size_t words = (size_t(levels) * pages * pages + 31) / 32;
    if (words > capacity) {
        capacity = words;
        bits = createBuffer(nullptr, words * sizeof(uint32_t));
    }
    const uint32_t zero = 0;
    glClearNamedBufferSubData(bits.id(), GL_R32UI, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glUseProgram(m_mark.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualMarkBinding, m_markUniforms.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPageRequestBinding, bits.id());
    glBindTextureUnit(kReceiverDepthUnit, depth.viewDepth.id());
    dispatchCompute(GLuint(depth.width + 7) / 8, GLuint(depth.height + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // for a read or a copy of the bits
    return words;
}

void VirtualPages::request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera,
                           const core::ShadowSetup& setup, const PageContent& content,
                           std::span<const core::Aabb> moved, double reachTexels, int pageBudget, bool late) {
    const Stopwatch inGl;
    const core::VirtualPageCache::Windows& windows = m_cache.beginFrame(setup, content, pageBudget, camera.wsEye);
    // One bit per page of every level's standing window; and of the back generation's windows.
    const size_t words = mark(depth, camera, setup, windows.standing, reachTexels, m_requestBits, m_requestCapacity);
    const size_t backWords = windows.drawingBack ? mark(depth, camera, setup, windows.back, reachTexels,
                                                        m_backRequestBits, m_backRequestCapacity)
                                                 : 0;
    int64_t markedIn = m_cache.frame();
    if (late) {
        markedIn = readMarksLate(words, backWords);
    } else {
        m_readBack.resize(words);
        detail::countReadBack();
        readBuffer(m_requestBits.id(), 0, GLsizeiptr(words * sizeof(uint32_t)), m_readBack.data());
        m_backReadBack.resize(backWords);
        if (backWords > 0) {
            detail::countReadBack();
            readBuffer(m_backRequestBits.id(), 0, GLsizeiptr(backWords * sizeof(uint32_t)), m_backReadBack.data());
        }
        m_lastMarksRead = markedIn;
    }
    m_gl = inGl.elapsed();
    m_cache.request(m_readBack, m_backReadBack, moved, markedIn);
}

int64_t VirtualPages::readMarksLate(size_t words, size_t backWords) {
    // This frame's marks into the next slot, after its own: one buffer, the back marks after the
    // standing ones. A slot still pending there is a frame the GPU has not finished: dropped.
    MarkSlot& slot = m_marks[size_t(m_nextMark++ % kMarkSlots)];
    slot.read.reserve((words + backWords) * sizeof(uint32_t));
    copyToHost(m_requestBits.id(), slot.read.id(), 0, 0, GLsizeiptr(words * sizeof(uint32_t)));
    if (backWords > 0)
        copyToHost(m_backRequestBits.id(), slot.read.id(), 0, GLintptr(words * sizeof(uint32_t)),
                   GLsizeiptr(backWords * sizeof(uint32_t)));
    slot.read.fence();
    slot.frame = m_cache.frame();
    slot.words = words, slot.backWords = backWords;

    // The newest earlier frame's marks that arrived and apply; those and any older are done with.
    const auto take = [&](MarkSlot& from) {
        const auto* bits = static_cast<const uint32_t*>(from.read.data());
        m_readBack.assign(bits, bits + from.words);
        m_backReadBack.assign(bits + from.words, bits + from.words + from.backWords);
        return m_lastMarksRead = from.frame;
    };
    for (int64_t i = m_nextMark - 2; i >= 0 && i > m_nextMark - 1 - kMarkSlots; --i) { // newest first
        MarkSlot& earlier = m_marks[size_t(i % kMarkSlots)];
        if (!earlier.read.pending() || !m_cache.marksApply(earlier.frame) || !earlier.read.arrived()) continue;
        const int64_t frame = take(earlier);
        for (MarkSlot& s : m_marks)
            if (s.frame <= frame) s.read.dropFence();
        return frame;
    }
    // None arrived: the last marks read, again, if they still apply (the same sun and levels):
    // they keep the pages they name from eviction and redraw those a mover has invalidated since.
    // Else nothing names the pages this frame's receivers need — its own marks, after a wait.
    if (m_lastMarksRead > 0 && m_cache.marksApply(m_lastMarksRead)) return m_lastMarksRead;
    detail::countReadBack();
    const int64_t frame = slot.read.waited() ? take(slot) : -1; // −1: a lost context, nothing requested
    slot.read.dropFence();
    return frame;
}

VirtualPageStats VirtualPages::stats() const {
    VirtualPageStats stats;
    static_cast<core::PageCacheStats&>(stats) = m_cache.stats();
    stats.poolBytes = int64_t(m_atlasTexels.x) * m_atlasTexels.y * 4;
    stats.tableBytes = m_pageTable->bytesUploaded();
    return stats;
}

DrawStats VirtualPages::drawPages(const GpuScene& scene, const PassPrograms& programs, const core::BiasSettings& bias,
                                  const core::Vec3& wsTowardsLight, const CasterLists& casters,
                                  const Buffer& depthUniforms) {
    // A page's first texel in its level's grid less its slot's in the atlas, so that the levels'
    // cross-fade dither (material.glsl) is the same in any slot; modulo 8, the dither's period,
    // to stay exact in a float.
    auto ditherOf = [](int64_t levelTexel, int slotTexel) {
        return static_cast<float>(((levelTexel - slotTexel) % 8 + 8) % 8);
    };
    const auto toRender = m_cache.pagesToRender();
    if (toRender.empty()) return {}; // a still frame: nothing to draw, nothing to upload
    auto ditherOrigin = [&](size_t i) {
        const glm::ivec3 v = slotViewport(toRender[i].slot);
        return glm::vec2(ditherOf(toRender[i].key.x * m_pageTexels - m_guardTexels, v.x),
                         ditherOf(toRender[i].key.y * m_pageTexels - m_guardTexels, v.y));
    };
    // Where the GL can, every page is drawn by the page programs (each page's matrix from its
    // block), whether with others or alone: the same arithmetic for a page culled on the GPU and
    // one culled on the CPU, so the two paths store the same depths on any driver.
    const bool pageProgramsUsed = static_cast<bool>(m_pagePrograms.plain);
    PassPrograms drawWith = programs;
    if (pageProgramsUsed) {
        drawWith.plain = m_pagePrograms.plain.id();
        drawWith.material = programs.material ? m_pagePrograms.material.id() : 0;
        std::vector<PageBlock> blocks(toRender.size());
        for (size_t i = 0; i < toRender.size(); ++i)
            blocks[i] = {glm::mat4(toRender[i].clipFromWorld), glm::vec4(ditherOrigin(i), 0.0f, 0.0f)};
        uploadViewBlocks(blocks, m_pageBlocks, m_pageBlockCapacity);
        // What the pages share: the bias (the block's matrix and dither origin are the pages').
        const DepthPassUniforms shared = depthPassUniformsFor(core::Mat4(1.0), bias, wsTowardsLight);
        uploadToBuffer(depthUniforms.id(), 0, sizeof shared, &shared);
    }
    // A page alone: its slot as the viewport, its uniforms (or, for the page programs, its block),
    // then its casters.
    DrawStats draws;
    glEnable(GL_SCISSOR_TEST);
    auto drawAlone = [&](size_t i) {
        const glm::ivec3 v = slotViewport(toRender[i].slot);
        glViewport(v.x, v.y, v.z, v.z);
        glScissor(v.x, v.y, v.z, v.z);
        const float clearDepth = 1.0f;
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_DEPTH, 0, &clearDepth);
        if (pageProgramsUsed) {
            setViewBases(drawWith, i, 0, ViewOfDraw::Call);
        } else {
            DepthPassUniforms uniforms = depthPassUniformsFor(toRender[i].clipFromWorld, bias, wsTowardsLight);
            uniforms.ditherOrigin = ditherOrigin(i);
            uploadToBuffer(depthUniforms.id(), 0, sizeof uniforms, &uniforms);
        }
        setLightFacingFront(toRender[i].clipFromWorld, wsTowardsLight);
        const std::vector<visibility::HalfSpace> volume = visibility::clipVolume(toRender[i].clipFromWorld, false);
        draws += casters.draw(scene, i, drawWith, &volume);
    };
    if (!pageProgramsUsed) {
        for (size_t i = 0; i < toRender.size(); ++i) drawAlone(i);
        glDisable(GL_SCISSOR_TEST);
        return draws;
    }
    // With the page programs, as many pages at once as the GL has viewports: first the leading
    // pages culled on the GPU (their commands a stride apart), then the rest — culled on the CPU:
    // past the room the frame made for pages on the GPU, a view's first frame, or every page on
    // the other paths. A group of one, or of pages that disagree on the light-facing winding or
    // their batches' order, is drawn a page at a time.
    const size_t culledOnGpu = pagesCulledOnGpu(casters);
    const size_t group = static_cast<size_t>(std::max(m_viewports, 1));
    struct Range {
        size_t begin, end;
        bool culledOnGpu;
    };
    for (const Range range : {Range{0, culledOnGpu, true}, Range{culledOnGpu, toRender.size(), false}})
        for (size_t first = range.begin; first < range.end; first += group) {
            const size_t count = std::min(group, range.end - first);
            if (count > 1 && drawnAlike(casters, wsTowardsLight, first, count, range.culledOnGpu))
                draws += drawPagesTogether(scene, drawWith, wsTowardsLight, casters, first, count, range.culledOnGpu);
            else
                for (size_t i = first; i < first + count; ++i) drawAlone(i);
        }
    glDisable(GL_SCISSOR_TEST);
    return draws;
}

size_t VirtualPages::pagesCulledOnGpu(const CasterLists& casters) const {
    const auto toRender = m_cache.pagesToRender();
    if (toRender.size() < 2 || casters.culled.size() != toRender.size()) return 0;
    // The leading pages whose casters were culled on the GPU into consecutive passes: their
    // commands one stride apart.
    const int64_t stride = casters.culled[1].indirect - casters.culled[0].indirect;
    if (casters.culled[0].indirect < 0 || stride <= 0) return 0;
    size_t pages = 0;
    while (pages < toRender.size() &&
           casters.culled[pages].indirect == casters.culled[0].indirect + int64_t(pages) * stride)
        ++pages;
    return pages;
}

bool VirtualPages::drawnAlike(const CasterLists& casters, const core::Vec3& wsTowardsLight, size_t first, size_t count,
                              bool culledOnGpu) const {
    const auto pages = m_cache.pagesToRender().subspan(first, count);
    const std::span<const PassList> lists = casters.lists.subspan(first, count);
    const auto winding = core::lightFacingWinding(pages.front().clipFromWorld, wsTowardsLight);
    // One winding for all (orthographic maps of one sun: always, but it is a draw state), one
    // order, and past the pages culled on the GPU none that the GPU culled.
    return std::ranges::all_of(
               pages,
               [&](const auto& p) { return core::lightFacingWinding(p.clipFromWorld, wsTowardsLight) == winding; }) &&
           std::ranges::all_of(lists, [&](const PassList& l) { return l.batchOrder == lists.front().batchOrder; }) &&
           (culledOnGpu || casters.culled.size() < first + count ||
            std::ranges::all_of(casters.culled.subspan(first, count),
                                [](const PassList& l) { return l.indirect < 0; }));
}

DrawStats VirtualPages::drawPagesTogether(const GpuScene& scene, const PassPrograms& programs,
                                          const core::Vec3& wsTowardsLight, const CasterLists& casters, size_t first,
                                          size_t count, bool culledOnGpu) {
    const auto pages = m_cache.pagesToRender().subspan(first, count);
    setLightFacingFront(pages.front().clipFromWorld, wsTowardsLight);
    // Each page's slot a viewport: its clear scissored to it. Then, for pages culled on the GPU,
    // every batch's level for all of them in one multi-draw (GpuScene::drawTogether), the draw's
    // index naming the page; then their CPU lists (on the GPU path the clustered meshes the CPU
    // picked for each, its runs of clusters meeting the page; on the others every caster) a
    // batch's level for all of them in one multi-draw too, each draw's page from a table. A page
    // sees the same draws in the same order as when drawn alone.
    for (size_t k = 0; k < count; ++k) {
        const glm::ivec3 v = slotViewport(pages[k].slot);
        glScissorIndexed(0, v.x, v.y, v.z, v.z); // the clear's
        const float clearDepth = 1.0f;
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_DEPTH, 0, &clearDepth);
        glViewportIndexedf(GLuint(k), float(v.x), float(v.y), float(v.z), float(v.z));
    }
    for (size_t k = 0; k < count; ++k) {
        const glm::ivec3 v = slotViewport(pages[k].slot);
        glScissorIndexed(GLuint(k), v.x, v.y, v.z, v.z);
    }
    DrawStats draws;
    if (culledOnGpu) {
        setViewBases(programs, first, 0, ViewOfDraw::DrawIndex);
        draws += scene.drawTogether(casters.culled.subspan(first, count), programs);
    }
    m_volumes.resize(count);
    for (size_t k = 0; k < count; ++k) m_volumes[k] = visibility::clipVolume(pages[k].clipFromWorld, false);
    setViewBases(programs, first, 0, ViewOfDraw::Table);
    draws += scene.drawTogether(casters.lists.subspan(first, count), programs, m_volumes);
    return draws;
}

void VirtualPages::rendered() {
    m_cache.rendered();
    m_pageTable->update(m_cache.pageTable(), m_cache.shown().clipmap->pagesPerSide(), m_cache.tableRebuilt(),
                        m_cache.tableChanges());
}

void VirtualPages::bind(const core::ShadowSetup& setup, float blendBand) const {
    const core::VirtualClipmap& c = *setup.clipmap;
    VirtualMapsUniforms u{};
    u.enabled = 1;
    u.levels = static_cast<int32_t>(setup.views.size());
    u.firstExponent = c.firstExponent;
    u.footprintPerMetre = static_cast<float>(c.footprintPerMetre);
    u.lodBias = static_cast<float>(c.lodBias);
    u.pagesPerSide = c.pagesPerSide();
    u.pageTexels = c.pageTexels;
    u.guardTexels = m_guardTexels;
    u.slotsPerRow = m_slotsPerRow;
    u.virtualTexels = static_cast<float>(c.virtualTexels);
    u.atlasTexels = glm::vec2(m_atlasTexels);
    u.blendBand = blendBand;
    for (int l = 0; l < u.levels; ++l) {
        const auto& level = std::get<core::ClipmapLevel>(setup.views[size_t(l)].warp);
        const core::PageTableCell cell = core::pageTableCellOf(level.firstPageX, level.firstPageY, u.pagesPerSide);
        u.tableOrigin[l] = {cell.x, cell.y, 0, 0};
    }
    // The levels' origins that are in use, not the whole array.
    uploadToBuffer(m_mapsUniforms.id(), 0,
                   GLsizeiptr(offsetof(VirtualMapsUniforms, tableOrigin) + size_t(u.levels) * 16), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualBinding, m_mapsUniforms.id());
    glBindTextureUnit(kShadowMapUnit, m_atlas.id());
    glBindTextureUnit(kShadowDepthUnit, m_atlas.id()); // PCSS's blocker search: its stored depths
    glBindTextureUnit(kPageTableUnit, m_pageTable->texture().id());
}

scene::Image VirtualPages::readAtlas() const {
    return m_atlas ? readDepthAsGreys(m_atlas, m_atlasTexels.x, m_atlasTexels.y, 1) : scene::Image{};
}

scene::Image VirtualPages::pageTableImage() const {
    const int levels = static_cast<int>(m_cache.shown().views.size());
    const std::span<const uint32_t> table = m_cache.pageTable();
    const int pages = m_cache.shown().clipmap ? m_cache.shown().clipmap->pagesPerSide() : 0;
    if (levels == 0 || pages == 0 || table.size() != size_t(pages) * pages * levels) return {};
    // main.frag's kCascadeTint, which --cascade-colors multiplies the levels' albedo by.
    static constexpr uint8_t kTint[8][3] = {{255, 89, 89},   {89, 255, 89},  {102, 128, 255}, {255, 255, 77},
                                            {255, 102, 255}, {77, 255, 255}, {255, 179, 77},  {204, 204, 204}};
    const int columns = std::min(levels, 4), gap = 2;
    const int rows = (levels + columns - 1) / columns;
    std::vector<core::PageTableCell> origin;
    for (const core::ShadowView& view : m_cache.shown().views) {
        const auto& level = std::get<core::ClipmapLevel>(view.warp);
        origin.push_back(core::pageTableCellOf(level.firstPageX, level.firstPageY, pages));
    }
    scene::Image image(columns * (pages + gap) - gap, rows * (pages + gap) - gap);
    for (int l = 0; l < levels; ++l) {
        const int x0 = (l % columns) * (pages + gap), y0 = (l / columns) * (pages + gap);
        for (int y = 0; y < pages; ++y)
            for (int x = 0; x < pages; ++x) {
                // The requests are window-relative, the table toroidal (core::pageTableCellOf).
                const size_t i = size_t(l) * pages * pages + size_t(y) * pages + size_t(x);
                const size_t entry = size_t(l) * pages * pages + size_t((y + origin[size_t(l)].y) % pages) * pages +
                                     size_t((x + origin[size_t(l)].x) % pages);
                const bool requested = i / 32 < m_readBack.size() && (m_readBack[i / 32] >> (i % 32) & 1u) != 0;
                uint8_t* p = image.pixel(x0 + x, y0 + pages - 1 - y); // light-space +y up
                const uint8_t dark[3] = {24, 24, 28}, white[3] = {255, 255, 255};
                const uint8_t* c = table[entry] != 0 ? kTint[l % 8] : requested ? white : dark;
                p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
            }
    }
    return image;
}

void VirtualPages::bindDisabled() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualBinding, m_disabledUniforms.id());
}

void VirtualPages::setLinearFilter(bool linear) const {
    if (!m_atlas) return;
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_MIN_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
}

} // namespace shadowkit::gl
