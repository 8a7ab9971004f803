// Virtual shadow maps on the GPU (core/virtual_clipmap.h has the maths, core/virtual_page_cache.h
// the page cache's policy: generations, eviction, the page budget, invalidation): the physical
// page pool — one depth atlas of fixed slots, each a page with a guard band around it —, the
// page requests marked from the camera's depth pre-pass (a compute pass, its bits read back for
// the cache), the pages the cache schedules drawn into their slots, and the page table the
// lookup reads.
#pragma once

#include "fenced_read.h"
#include "gl_object.h"
#include "gpu_scene.h"
#include "page_table.h"
#include "render_targets.h"
#include "stopwatch.h"
#include "uniforms.h"

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/virtual_clipmap.h"
#include "shadowkit/core/virtual_page_cache.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace shadowkit::gl {

using PageContent = core::PageContent;
// What pages drawn for `clipmap` with a guard band of `guardTexels` hold under this bias and
// these levels of detail.
PageContent pageContentOf(const core::VirtualClipmap& clipmap, int guardTexels, const core::BiasSettings& bias,
                          const RenderSettings& settings);

class VirtualPages {
public:
    static core::Result<std::unique_ptr<VirtualPages>> create();

    // Slots of (pageTexels + 2 guardTexels)² texels; `slots` 0: as many as fit in 2^24 texels
    // (64 MiB of 32-bit depth). A change of any of them reallocates the atlas, dropping every
    // page. Fails with an environment error naming virtual.pool_pages when the driver cannot.
    core::Status configure(int slots, int pageTexels, int guardTexels);

    // A frame's requests: marks the pages the pre-pass's receivers need in the windows the cache
    // asks for (compute pass), and hands them to the cache with the boxes of moved casters: it
    // lists the pages to render, at most `pageBudget` (0: every one). `setup` and `moved` in the
    // renderer's space.
    //
    // `late` false: the frame waits for its own marks (one read-back; two while a new sun's pages
    // are drawn under a budget). True: the marks go to a ring of mapped buffers behind fences, and
    // the frame reads the newest earlier frame's that arrived and still apply
    // (core::VirtualPageCache::marksApply) — no wait. When none arrived it requests again what the
    // last marks read asked for, unless those no longer apply (the first frame, a moved sun, a
    // level added): then it waits for its own. Pages needed first in this frame are then
    // served by coarser levels for the frame or two their marks take.
    void request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup,
                 const PageContent& content, std::span<const core::Aabb> moved, double reachTexels, int pageBudget,
                 bool late);
    // The set-up the lookup must read this frame (after request()): `setup` itself, or with the
    // levels still shown from the previous sun's pages placed around this frame's eye.
    const core::ShadowSetup& shown() const { return m_cache.shown(); }

    using PageToRender = core::VirtualPageCache::PageToRender;
    std::span<const PageToRender> pagesToRender() const { return m_cache.pagesToRender(); }
    // The slot's viewport in the atlas: x, y, side.
    glm::ivec3 slotViewport(int slot) const;
    // The atlas's width and height in texels (configure()).
    glm::ivec2 atlasTexels() const { return m_atlasTexels; }
    // Draws pagesToRender()[i] with the casters of view i into its slot, scissored so its clear
    // touches no other page: the clusters of large meshes culled to the page's volume, the faces
    // towards `wsTowardsLight` as the front ones (setLightFacingFront), `bias`'s constant term in
    // `depthUniforms` (depth.vert). Other GL state (polygon offset's slope term, clamp, culling)
    // is the caller's. Where the GL lets vertex stages read the draw's index and pick the
    // viewport, every page is drawn with page programs of this room's (`programs`' flags; each
    // page's matrix from a buffer), and the leading pages whose casters were culled on the GPU
    // (consecutive passes) together: up to a viewport each at once, every batch's level for all of
    // them in one multi-draw (drawPagesTogether) — the same depths, a few draws a frame instead of
    // a few a page. Elsewhere, with `programs`, the page's matrix into `depthUniforms`.
    DrawStats drawPages(const GpuScene& scene, const PassPrograms& programs, const core::BiasSettings& bias,
                        const core::Vec3& wsTowardsLight, const CasterLists& casters, const Buffer& depthUniforms);
    const Framebuffer& framebuffer() const { return m_framebuffer; }
    // After the pages were drawn: they are valid, and the page table for shown()'s windows is
    // brought up to date on the GPU (page_table.h: its changed entries, or the whole when new).
    void rendered();
    // The atlas at kShadowMapUnit, the page table at kPageTableUnit, the VirtualMaps block.
    void bind(const core::ShadowSetup& setup, float blendBand) const;
    // For frames without virtual maps: the VirtualMaps block with enabled 0.
    void bindDisabled() const;
    void setLinearFilter(bool linear) const;
    // The atlas as greys: every slot, black where empty (Renderer::readShadowMap).
    scene::Image readAtlas() const;
    // The page table of the last frame drawn, a pagesPerSide² tile per level (finest first, four
    // a row): a shown page in its level's tint (main.frag's --cascade-colors), a page requested
    // but not shown (pool full, over the budget, still drawing) white, the rest dark.
    scene::Image pageTableImage() const;

    // Every page dropped: what they hold is no longer known (casters moved in frames drawn
    // without virtual maps, a new atlas). The marks on their way go with them: the next frame
    // waits for its own.
    void forget();

    VirtualPageStats stats() const;
    const CpuTimes& glTimes() const { return m_gl; }

private:
    VirtualPages() = default;
    // How many of this frame's pages lead with casters the GPU culled into consecutive passes
    // (their commands one stride apart): 0, or 2 and more.
    size_t pagesCulledOnGpu(const CasterLists& casters) const;
    // Whether pages [first, first + count) can be drawn together: one light-facing winding, one
    // batch order, and unless they are of the pages culled on the GPU, none with GPU-culled casters.
    bool drawnAlike(const CasterLists& casters, const core::Vec3& wsTowardsLight, size_t first, size_t count,
                    bool culledOnGpu) const;
    // Pages [first, first + count), at most one a viewport, drawn together with the page programs
    // (`programs`), their blocks bound: what the GPU culled for them (`culledOnGpu`), then their lists.
    DrawStats drawPagesTogether(const GpuScene& scene, const PassPrograms& programs, const core::Vec3& wsTowardsLight,
                                const CasterLists& casters, size_t first, size_t count, bool culledOnGpu);
    // Marks the pages the pre-pass's receivers request in the windows of `views` (one per level
    // of `setup`) into `bits` (grown as needed); returns the words marked.
    size_t mark(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup,
                std::span<const core::ShadowView> views, double reachTexels, Buffer& bits, size_t& capacity);
    // Late requests: this frame's marks (`words` and `backWords` of them) into the ring; the marks
    // of an earlier frame that arrived and apply, the last ones read again, or this frame's after
    // a wait, in m_readBack and m_backReadBack. Returns the frame they were marked in.
    int64_t readMarksLate(size_t words, size_t backWords);

    // A frame's marks on their way back (request()'s `late`).
    struct MarkSlot {
        FencedReadBuffer read;
        int64_t frame = 0; // the cache's frame they were marked in
        size_t words = 0, backWords = 0;
    };
    static constexpr int kMarkSlots = 3;

    core::VirtualPageCache m_cache;
    Program m_mark;
    Buffer m_markUniforms, m_mapsUniforms, m_disabledUniforms, m_requestBits, m_backRequestBits;
    size_t m_requestCapacity = 0, m_backRequestCapacity = 0; // uints
    std::vector<uint32_t> m_readBack, m_backReadBack;        // the marks the cache read this frame
    std::array<MarkSlot, kMarkSlots> m_marks;
    int64_t m_nextMark = 0;
    int64_t m_lastMarksRead = 0; // the frame the marks in m_readBack were made in
    Texture m_atlas;
    std::unique_ptr<PageTable> m_pageTable;
    Framebuffer m_framebuffer;
    // The page programs (depth.vert's SK_PAGES), which draw every page where the GL can, and
    // each page's block (its matrix and dither origin).
    ProgramPair m_pagePrograms; // empty where the GL cannot
    GLint m_viewports = 1;      // GL_MAX_VIEWPORTS: pages drawn at once
    Buffer m_pageBlocks;
    size_t m_pageBlockCapacity = 0;
    std::vector<std::vector<visibility::HalfSpace>> m_volumes; // drawPagesTogether's group's pages' clip volumes
    int m_slotsPerRow = 0, m_slotTexels = 0, m_pageTexels = 0, m_guardTexels = 0;
    glm::ivec2 m_atlasTexels{0};
    CpuTimes m_gl;
};

} // namespace shadowkit::gl
