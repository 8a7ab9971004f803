// Virtual shadow maps on the GPU (core/virtual_clipmap.h has the maths): the physical page
// pool — one depth atlas of fixed slots, each a page with a guard band around it —, the page
// requests marked from the camera's depth pre-pass, allocation of new pages and eviction of the
// least recently requested, invalidation under moving casters, the pages a frame must render,
// and the page table the lookup reads. Pages keep their depth across frames for as long as
// what they were rendered with (the sun, the depth range, the bias, the levels of detail) stays
// the same: then only new and invalidated pages are drawn.
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

class VirtualPages {
public:
    static core::Result<std::unique_ptr<VirtualPages>> create();

    // Slots of (pageTexels + 2 guardTexels)² texels; `slots` 0: as many as fit in 2^24 texels
    // (64 MiB of 32-bit depth). A change of any of them reallocates the atlas, dropping every
    // page. Fails with an environment error naming virtual.pool_pages when the driver cannot.
    core::Status configure(int slots, int pageTexels, int guardTexels);

    // A frame's requests: marks the pages the pre-pass's receivers need (compute pass, bits read
    // back), drops what `content` no longer matches and what moved casters touched, allocates
    // (coarsest levels first, so the fallback of every receiver is served before its finer
    // page), and lists the pages to render. `setup` and `moved` in the renderer's scene space.
    void request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup,
                 const PageContent& content, std::span<const core::Aabb> moved, double reachTexels);

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
    DrawStats drawPages(const GpuScene& scene, std::span<const PassList> lists, const Buffer& depthUniforms) const;
    const Framebuffer& framebuffer() const { return m_framebuffer; }
    // After the pages were drawn: they are valid, and the page table for `setup`'s windows is
    // uploaded.
    void rendered(const core::ShadowSetup& setup);
    // The atlas at kShadowMapUnit, the page table at kPageTableUnit, the VirtualMaps block.
    void bind(const core::ShadowSetup& setup, float blendBand) const;
    // For frames without virtual maps: the VirtualMaps block with enabled 0.
    void bindDisabled() const;
    void setLinearFilter(bool linear) const;
    // The atlas as greys: every slot, black where empty (Renderer::readShadowMap).
    scene::Image readAtlas() const;

    // Every page dropped: what they hold is no longer known (casters moved in frames drawn
    // without virtual maps).
    void forget() { dropAll(); }

    VirtualPageStats stats() const { return m_stats; }
    const CpuTimes& glTimes() const { return m_gl; }

private:
    VirtualPages() = default;
    struct Slot {
        core::PageKey key;
        int64_t lastRequested = -1; // frame index
        bool used = false, valid = false;
    };
    struct KeyHash {
        size_t operator()(const core::PageKey& k) const {
            return std::hash<int64_t>()(k.x * 73856093 ^ k.y * 19349663 ^ int64_t(k.exponent) * 83492791);
        }
    };
    void dropAll();
    std::vector<core::PageKey> readRequests(const core::ShadowSetup& setup) const;

    Program m_mark;
    Buffer m_markUniforms, m_mapsUniforms, m_disabledUniforms, m_requestBits;
    size_t m_requestCapacity = 0; // uints
    mutable std::vector<uint32_t> m_readBack;
    Texture m_atlas, m_pageTable;
    Framebuffer m_framebuffer;
    int m_slotsPerRow = 0, m_slotTexels = 0, m_pageTexels = 0, m_guardTexels = 0;
    glm::ivec2 m_atlasTexels{0};
    int m_tablePagesPerSide = 0;
    std::vector<Slot> m_slots;
    std::unordered_map<core::PageKey, int, KeyHash> m_resident;
    std::vector<PageToRender> m_toRender;
    std::vector<uint32_t> m_table;
    PageContent m_content;
    int64_t m_frame = 0;
    VirtualPageStats m_stats;
    CpuTimes m_gl;
};

} // namespace shadowkit::gl
