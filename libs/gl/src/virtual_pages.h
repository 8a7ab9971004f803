// Virtual shadow maps on the GPU (core/virtual_clipmap.h has the maths): the physical page
// pool — one depth atlas of fixed slots, each a page with a guard band around it —, the page
// requests marked from the camera's depth pre-pass, allocation of new pages and eviction of the
// least recently requested, invalidation under moving casters, the pages a frame must render,
// and the page table the lookup reads. Pages keep their depth across frames for as long as
// what they were rendered with (the sun, the depth range, the bias, the levels of detail) stays
// the same: then only new and invalidated pages are drawn.
//
// A page budget (RenderSettings::virtualPageBudget) caps the pages drawn a frame, most needed
// first: the pages shown, coarsest level first. When what the pages depend on changes (a moving
// sun), the pages drawn for the old sun — the front generation — keep serving while the new
// sun's — the back generation — are drawn with what is left of the budget, finest level first;
// a level is shown from the back generation in the frame its last page is drawn, and when every
// level is, the back generation becomes the front one. With a budget that holds every page this
// is the frame an unlimited one draws. At most two generations live in the pool; each level is
// shown from one of them, so a lookup never mixes two suns' depths within a level.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "render_targets.h"
#include "stopwatch.h"
#include "uniforms.h"

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/virtual_clipmap.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace shadowkit::gl {

// What a page's depth depends on besides its key: a change drops every page.
struct PageContent {
    core::Mat4 lightFromWorldRotation{1.0};
    core::Vec3 wsGridOrigin{0.0};
    double zNear = 0.0, zFar = 0.0;
    int pageTexels = 0, guardTexels = 0;
    float slopeBias = 0.0f, constantBias = 0.0f;
    int cull = 0;
    bool lod = false;
    double lodTexelError = 0.0;
    bool operator==(const PageContent&) const = default;
};
// What pages drawn for `clipmap` with a guard band of `guardTexels` hold under this bias and
// these levels of detail.
PageContent pageContentOf(const core::VirtualClipmap& clipmap, int guardTexels, const core::BiasSettings& bias,
                          const RenderSettings& settings);

// RenderSettings' virtual-map fields in range; errors name virtual.pool_pages,
// virtual.blend_band, virtual.page_budget.
core::Status validateVirtualSettings(const RenderSettings& settings);

class VirtualPages {
public:
    static core::Result<std::unique_ptr<VirtualPages>> create();

    // Slots of (pageTexels + 2 guardTexels)² texels; `slots` 0: as many as fit in 2^24 texels
    // (64 MiB of 32-bit depth). A change of any of them reallocates the atlas, dropping every
    // page. Fails with an environment error naming virtual.pool_pages when the driver cannot.
    core::Status configure(int slots, int pageTexels, int guardTexels);

    // A frame's requests: marks the pages the pre-pass's receivers need (compute pass, bits read
    // back), drops what `content` no longer matches (at once without a budget, else by
    // generations) and what moved casters touched, and lists the pages to render, at most
    // `pageBudget` (0: every one), allocating their slots: coarsest levels first, so the fallback
    // of every receiver is served before its finer page. `setup` and `moved` in the renderer's
    // space.
    void request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup,
                 const PageContent& content, std::span<const core::Aabb> moved, double reachTexels, int pageBudget);
    // The set-up the lookup must read this frame (after request()): `setup` itself, or with the
    // levels still shown from the previous sun's pages placed around this frame's eye.
    const core::ShadowSetup& shown() const { return m_shown; }

    struct PageToRender {
        core::PageKey key;
        int slot = 0;
        core::Mat4 clipFromWorld{1.0}; // the page and its guard band (core::clipmapPageClipFromWorld)
    };
    std::span<const PageToRender> pagesToRender() const { return m_toRender; }
    // The slot's viewport in the atlas: x, y, side.
    glm::ivec3 slotViewport(int slot) const;
    // Draws pagesToRender()[i] with lists[i] into its slot, scissored so its clear touches no
    // other page, with the bound depth program: the page's matrix into `depthUniforms`, the
    // clusters of large meshes culled to the page's volume. GL state (bias, clamp) is the caller's.
    DrawStats drawPages(const GpuScene& scene, const PassPrograms& programs, std::span<const PassList> lists,
                        const Buffer& depthUniforms) const;
    const Framebuffer& framebuffer() const { return m_framebuffer; }
    // After the pages were drawn: they are valid, and the page table for shown()'s windows is
    // uploaded.
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
    // without virtual maps).
    void forget() { dropAll(); }

    VirtualPageStats stats() const { return m_stats; }
    const CpuTimes& glTimes() const { return m_gl; }

private:
    VirtualPages() = default;
    using ViewList = core::SmallVector<core::ShadowView, core::kMaxShadowViews>;
    // Pages drawn for one PageContent: a sun, a depth range, a bias.
    struct Generation {
        int64_t id = -1;
        PageContent content;
        int64_t lastCurrent = 0; // the last frame whose content this was
    };
    // A page of a generation: what a slot holds.
    struct SlotKey {
        core::PageKey page;
        int64_t generation = -1;
        bool operator==(const SlotKey&) const = default;
    };
    struct Slot {
        SlotKey key;
        int64_t lastRequested = -1; // frame index
        bool used = false, valid = false;
    };
    struct KeyHash {
        size_t operator()(const SlotKey& k) const {
            return std::hash<int64_t>()(k.page.x * 73856093 ^ k.page.y * 19349663 ^
                                        int64_t(k.page.exponent) * 83492791 ^ k.generation * 2654435761);
        }
    };
    void dropAll();
    // Front and back generations for this frame's `content`; slots of any other are freed.
    void advanceGenerations(const PageContent& content, int pageBudget);
    // `setup`'s clipmap with the sun, grid and depth range pages of `generation` were drawn in.
    static core::VirtualClipmap clipmapOf(const core::VirtualClipmap& current, const Generation& generation);
    // Level `level` of `setup` as `generation` draws it around this frame's eye: the set-up's
    // own view when the generation is the current `content`'s.
    static core::ShadowView levelView(const core::ShadowSetup& setup, int level, const PageContent& content,
                                      const Generation& generation, const core::Vec3& wsEye);
    // Marks the pages the pre-pass's receivers request in the windows of `views` (one per level
    // of `setup`) into `bits`, read back into `readBack`.
    void mark(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup,
              std::span<const core::ShadowView> views, double reachTexels, Buffer& bits, size_t& capacity,
              std::vector<uint32_t>& readBack);
    // Marks invalid every valid page a moved box (old or new place) touches, in any level.
    void invalidateUnder(std::span<const core::Aabb> moved, const core::VirtualClipmap& clipmap);
    // Appends the keys of the bits set in `readBack` for level `level`, whose window is `view`,
    // as pages of `generation`.
    static void appendKeys(int pagesPerSide, const core::ShadowView& view, int level,
                           const std::vector<uint32_t>& readBack, int64_t generation, std::vector<SlotKey>& keys);

    Program m_mark;
    Buffer m_markUniforms, m_mapsUniforms, m_disabledUniforms, m_requestBits, m_backRequestBits;
    size_t m_requestCapacity = 0, m_backRequestCapacity = 0; // uints
    std::vector<uint32_t> m_readBack, m_backReadBack;
    Texture m_atlas, m_pageTable;
    Framebuffer m_framebuffer;
    int m_slotsPerRow = 0, m_slotTexels = 0, m_pageTexels = 0, m_guardTexels = 0;
    glm::ivec2 m_atlasTexels{0};
    int m_tablePagesPerSide = 0;
    std::vector<Slot> m_slots;
    std::unordered_map<SlotKey, int, KeyHash> m_resident;
    std::vector<PageToRender> m_toRender;
    std::vector<uint32_t> m_table;
    Generation m_front;               // the pages on screen (every level not yet shown from m_back)
    std::optional<Generation> m_back; // page budget: a newer content's pages, being drawn
    std::vector<int> m_backExponents; // levels (by exponent) shown from m_back
    int64_t m_nextGeneration = 0;
    core::ShadowSetup m_shown;              // this frame's set-up as the lookup reads it
    std::vector<int64_t> m_shownGeneration; // per level of m_shown
    int64_t m_frame = 0;
    VirtualPageStats m_stats;
    CpuTimes m_gl;
};

} // namespace shadowkit::gl
