// The sun's shadow pass: depth into the set-up's maps — one layer of a 2D array per fixed map
// (single maps and cascades), or the virtual pages a frame must draw into the page atlas
// (virtual_pages.h) — with the bias as polygon offset and caster culling (Scherzer 2005 §4.2),
// with --filter msm the maps' moments (moment_maps.h), and with --foliage-opacity the maps' or
// the pages' opacity layers (opacity_layers.h). It owns the maps and what draws
// them; the culling planner (pass_lists.h) hands it the lists.
#pragma once

#include "gpu_scene.h"
#include "moment_maps.h"
#include "opacity_layers.h"
#include "pass_samples.h"
#include "pass_timer.h"
#include "render_targets.h"
#include "virtual_pages.h"
#include "visibility.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace shadowkit::gl {

class SunPass {
public:
    static core::Result<std::unique_ptr<SunPass>> create();

    // The maps `setup` draws into, allocated (or kept) before the frame's lists are planned:
    // fixed layers of setup.mapSize², or the page pool sized for the set-up's pages and the
    // filter's guard band; with --foliage-opacity their opacity layers. Fails when the driver
    // cannot (out of memory, too large).
    core::Status prepare(const core::ShadowSetup& setup, const RenderSettings& settings,
                         const core::BiasSettings& bias);
    // Draws the maps: `maps` each fixed map's casters, or `pages` each page to render's. No
    // sun (settings.sun false): nothing is drawn. Timed (timer()). `wsTowardsLight`
    // says which faces bias.cull's front and back are (core/caster_facing.h).
    core::Result<PassStats> draw(const GpuScene& scene, const core::ShadowSetup& setup, const RenderSettings& settings,
                                 const core::BiasSettings& bias, const core::Vec3& wsTowardsLight,
                                 const CasterLists& maps, const CasterLists& pages);
    // The last draw()'s GPU time and the samples its depth test passed, as queries the frame's
    // figures read (gpu_figures.h), and the texels drawn: the fixed maps', or the virtual pages'
    // drawn, guard bands and all (0 without a sun or a page drawn, when no sample is counted).
    const PassTimer& timer() const { return m_timer; }
    const PassSamples& samples() const { return m_samples; }
    uint64_t mapTexels() const { return m_countedTexels; }
    // With --foliage-opacity, the last draw()'s opacity layers' two draws over the same texels
    // (OpacityLayers::firstLeafSamples and leafSamples; not counted in a frame that drew none);
    // null while the layers were never asked for.
    const OpacityLayers* opacity() const { return m_opacity.get(); }

    // The set-up the frame's lookups read: with virtual maps under a page budget, levels may
    // still be shown from an earlier sun's pages (VirtualPages::shown).
    const core::ShadowSetup& lookupSetup(const core::ShadowSetup& setup, const RenderSettings& settings) const {
        return setup.clipmap && settings.sun ? m_pages->shown() : setup;
    }
    // The maps for the camera passes' lookups: the fixed maps or the page atlas and its table
    // (kShadowMapUnit, kShadowDepthUnit, kPageTableUnit), the VirtualMaps block, the moments.
    void bind(const core::ShadowSetup& setup, const RenderSettings& settings) const;

    VirtualPages& pages() { return *m_pages; }
    // Technique virtual: the pages of the last frame drawn; nullopt when it had no virtual maps.
    const std::optional<VirtualPageStats>& lastVirtual() const { return m_lastVirtual; }
    // The last maps as greys (the page atlas with virtual maps), and the virtual page table.
    scene::Image readMaps() const;
    scene::Image readPageTable() const { return m_shadow ? scene::Image{} : m_pages->pageTableImage(); }

    // The depth programs of a layout: only the linear one writes gl_FragDepth (depth.frag).
    PassPrograms programsFor(core::DepthLayout layout) const {
        return m_programs[layout == core::DepthLayout::Linear].passPrograms();
    }

    // The programs that draw the fixed maps together (hyperbolic layout), zero where the GL cannot.
    PassPrograms mapsTogetherPrograms() const { return m_mapPrograms.passPrograms(); }

private:
    SunPass() = default;
    // The GL state both kinds of map draw with: depth only, the bias as polygon offset (and
    // caster culling), depth clamp when asked, the depth program and its uniforms bound.
    void beginDepthPass(const core::BiasSettings& bias, bool depthClamp, core::DepthLayout layout) const;
    static void endDepthPass();
    // The depth programs of a layout, told which levels bias.cull may cull.
    PassPrograms casterPrograms(core::DepthLayout layout, const core::BiasSettings& bias) const {
        PassPrograms programs = programsFor(layout);
        programs.cullClosedOnly = bias.cull == core::CasterCull::BackOfClosed;
        return programs;
    }
    // The opacity layers' textures (OpacityLayers::prepare), built on the first frame that asks.
    core::Status prepareOpacity(int width, int height, int layers, int mipLevels, const std::string& field);
    // The opacity layers of the pages to render: each into its slot of the layers' atlases.
    std::vector<OpacityView> pageOpacityViews() const;
    // `batches`: all, or the opaque ones when the alpha-tested cast through opacity layers.
    // `byClusters`: a large mesh in a CPU list draws its clusters meeting each map (culling on).
    DrawStats drawFixedMaps(const GpuScene& scene, const core::ShadowSetup& setup, const core::BiasSettings& bias,
                            const core::Vec3& wsTowardsLight, const CasterLists& casters, PassPrograms::Batches batches,
                            bool byClusters);
    // Whether the maps can be drawn together, each in its layer (drawMapsTogether): two or more, the
    // map programs built, the hyperbolic layout (the programs leave depth to the rasteriser), one
    // light-facing winding, one batch order, the GPU-culled lists (if any) in consecutive passes
    // (their commands one stride apart) and the CPU's all in one buffer.
    bool mapsDrawnTogether(const core::ShadowSetup& setup, const core::Vec3& wsTowardsLight,
                           const CasterLists& casters) const;
    // Every map at once with the map programs (`programs` says which batches and culling): each
    // map's block, one clear of every layer, then each batch's level for all maps in one multi-draw
    // (the GPU-culled lists', then the CPU's).
    DrawStats drawMapsTogether(const GpuScene& scene, const core::ShadowSetup& setup, const core::BiasSettings& bias,
                               const core::Vec3& wsTowardsLight, const CasterLists& casters, PassPrograms programs);

    ProgramPair m_programs[2]; // depth only, [hyperbolic, linear]; alpha-tested materials discard
    ProgramPair m_mapPrograms; // the fixed maps drawn together (depth_views.h); empty where the GL cannot
    Buffer m_mapBlocks;        // their blocks
    size_t m_mapBlockCapacity = 0;
    std::vector<std::vector<visibility::HalfSpace>> m_mapVolumes; // each map's clip volume, CPU lists
    Buffer m_uniforms;                                            // the DepthPass block
    Sampler m_rawDepth;                                           // the maps' stored depths, for the moments
    std::optional<ShadowTarget> m_shadow;
    std::unique_ptr<VirtualPages> m_pages;
    std::unique_ptr<MomentMaps> m_moments;
    std::unique_ptr<OpacityLayers> m_opacity; // built on the first frame that asks for it
    std::optional<VirtualPageStats> m_lastVirtual;
    PassTimer m_timer;
    PassSamples m_samples;
    uint64_t m_countedTexels = 0;
};

} // namespace shadowkit::gl
