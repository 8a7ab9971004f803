// The culling planner: which instances, at which level of detail, every pass of a frame
// draws. It owns the culling state that lives across frames — the instance hierarchy
// (visibility.h), CHC++'s history (occlusion_culling.h), the GPU-driven culling's buffers
// (gpu_culling.h), the receiver masks (receiver_masks.h), the camera's depth pre-pass and its
// reduction to a depth range (depth_range.h) — and produces one PassList per pass: the camera
// pass, each sun map or each virtual page to draw, each local light's map.
//
// The camera pass is planned first: with occlusion culling, receiver masks or virtual maps the
// shadow passes' lists depend on what it sees (its depth pre-pass).
#pragma once

#include "depth_range.h"
#include "gpu_culling.h"
#include "gpu_figures.h"
#include "gpu_scene.h"
#include "occlusion_culling.h"
#include "receiver_masks.h"
#include "render_targets.h"
#include "stopwatch.h"
#include "virtual_pages.h"
#include "visibility.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"

#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace shadowkit::gl {

// What a frame's lists are for.
enum class PassPurpose {
    Frame,      // every pass: camera, sun maps or virtual pages, local lights
    DepthRange, // Renderer::visibleDepth: the camera's pre-pass and list only
    Surfaces,   // Renderer::renderSurfaceBuffers: the camera's list only, no shadow pass
};

// One frame to plan, in the renderer's (scene) space.
struct PassPlanInputs {
    const core::PerspectiveCamera& camera;
    const core::ShadowSetup& setup;
    core::Vec3 wsTowardsLight; // the sun's (unit), in the scene's coordinates
    const RenderSettings& settings;
    const core::BiasSettings& bias;           // the frame's (biasFor): the receiver masks' reach
    const core::LocalLighting& localLights;   // in the scene's coordinates
    LocalPass localPass = LocalPass::Layered; // as LocalShadowMaps::resolve chose it
    PassPurpose purpose = PassPurpose::Frame;
};

// What building the lists cost (FrameStats' culling figures).
struct CullingCosts {
    CpuTimes total; // building this frame's lists
    CpuTimes inGl;  // of which inside GL doing or awaiting GPU work
    CpuTimes lists; // of which choosing levels and building lists
    visibility::CoherentCullingStats occlusion;
    double occlusionMilliseconds = 0.0; // the camera's culling (CHC++ or the GPU's)
    double receiverMaskMilliseconds = 0.0;

    // Into a frame's figures: wall and GL times, the list building's and culling's own CPU time.
    void fill(FrameStats& stats) const;
};

class PassLists {
public:
    // `gpuScene` must outlive the planner (the culling passes draw its meshes).
    static core::Result<std::unique_ptr<PassLists>>
    create(const scene::Scene& scene, std::span<const scene::MeshLods> lods, const GpuScene& gpuScene);

    // Whether plan() draws the camera's depth pre-pass: it reads the camera's Frame block, which
    // must be bound before plan() is called.
    static bool needsPrepass(const core::ShadowSetup& setup, const RenderSettings& settings, PassPurpose purpose);
    // GPU-driven culling's programs (built on first use; an error when the driver cannot).
    core::Status prepareGpuCulling() { return m_gpuCulling->buildPrograms(); }

    // Every list of the frame, uploaded together; for PassPurpose::Frame alone the shadow passes'
    // (and with virtual maps and a sun, the pages the visible receivers request, through `pages`).
    void plan(const PassPlanInputs& in, VirtualPages& pages);

    // The camera passes' casters: its list, the CPU's — or, GPU-driven, what the GPU culled and
    // beside it the CPU's list of the large clustered meshes in view (drawn by clusters).
    CasterLists cameraCasters() const {
        return m_cameraLeavesClustered ? CasterLists{{&m_cameraClustered, 1}, {&m_camera, 1}}
                                       : CasterLists{{&m_camera, 1}, {}};
    }
    // Each fixed map's casters (none with virtual maps): its list, the CPU's — or, GPU-driven, what
    // the GPU culled and beside it the CPU's list of the large clustered meshes meeting the map.
    CasterLists sunCasters() const {
        return m_sunClustered.empty() ? CasterLists{m_sun, {}} : CasterLists{m_sunClustered, m_sun};
    }
    std::span<const PassList> pageLists() const { return m_pages; } // one per VirtualPages::pagesToRender()
    // Culling::Gpu: what the GPU culled of each page (indirect < 0: the page is wholly the CPU's,
    // in pageLists()); the page's clustered meshes are in pageLists() (drawn together: CasterLists).
    std::span<const PassList> pageCulledLists() const { return m_pageCulled; }
    // Each local map's casters, LocalShadowMaps::listCount of them: its list, the CPU's — or,
    // GPU-driven, what the GPU culled and beside it the CPU's list of the clustered meshes.
    CasterLists localCasters() const {
        return m_localClustered.empty() ? CasterLists{m_local, {}} : CasterLists{m_localClustered, m_local};
    }
    // Each local list's volume (a spot's or cube face's clip volume without its near plane, a
    // layered cube's range box): a large mesh draws its clusters meeting it.
    std::span<const std::vector<visibility::HalfSpace>> localVolumes() const { return m_localVolumes; }
    const CullingCosts& costs() const { return m_costs; }
    // Camera depth pre-passes drawn since the planner was made (a CHC++ settle loop counts once).
    int prepassesDrawn() const { return m_prepassesDrawn; }
    // The camera's depth pre-pass of the frame last planned, when it has one: the depth of the
    // surfaces the camera list draws — the same instances at the same levels (GPU culling's may
    // add instances found hidden behind them), the same vertex shader and alpha test — which the
    // camera passes draw over (CameraPasses). nullptr: none.
    const CameraDepthTarget* cameraPrepass() const { return m_prepassThisFrame ? &*m_cameraDepth : nullptr; }

    // The levels the last frame's camera list and sun lists (maps or pages) drew each instance at.
    // GPU-culled lists are read back (a wait: for reports, not for frames).
    LevelsDrawn levelsDrawn() const;
    // What the same lists drew at each level (Renderer::workByLevel), read back the same way.
    WorkByLevel workByLevel(const GpuScene& gpuScene) const;
    // Culling::Gpu: what the sun maps' lists, or the pages' GPU-culled ones, drew, read back (waits for the GPU).
    // With `foliageOpacity`, counted as the layers draw the alpha-tested casters: twice, not in the depth pass.
    DrawStats gpuSunDrawn(bool foliageOpacity) const;
    // Culling::Gpu: the same lists for a late read (gpu_figures.h): the command buffer the GPU
    // wrote and where each list's draws lie in it.
    // With `foliageOpacity`, each sun list's alpha-tested casters once more (gpuSunDrawn).
    void describeGpuLists(FrameFigureSources& sources, bool foliageOpacity) const;

    // The view-depth range of the last pre-pass (Renderer::lastVisibleDepth). The reduction is
    // queued after every pre-pass once a range has been asked for; until then, the first ask
    // reduces the last pre-pass's depths itself (it is kept until the next one).
    std::optional<core::Vec2> lastVisibleDepth();
    // The range of the pre-pass plan() just drew, reduced now (Renderer::visibleDepth).
    std::optional<core::Vec2> visibleDepthNow();

    // An instance moved: its new world box into the hierarchy and the GPU culling; its old and
    // new boxes kept for the next frame's virtual pages to redraw what lies under them.
    void move(uint32_t globalInstance, const core::Aabb& wsBox);
    // After a frame's moves: the hierarchy rebuilt when they degraded it.
    void afterMoves();
    const visibility::InstanceHierarchy& hierarchy() const { return m_visibility->hierarchy(); }
    const core::Aabb& bounds() const { return m_visibility->bounds(); } // in the scene's coordinates

private:
    PassLists() = default;
    // A list as drawn: a GPU-culled one read back (a wait), any other as it is.
    PassList drawn(const PassList& list) const { return list.indirect >= 0 ? m_gpuCulling->read(list) : list; }
    // The ranges the sun's GPU-culled lists (its maps', or its pages' culled casters) drew, as
    // GpuCulling::drawnBy reads them (indirect and count only): each list, and with
    // `foliageOpacity` its alpha-tested batches' ranges once more.
    std::vector<PassList> sunCulledRanges(bool foliageOpacity) const;
    // The camera's list, and its depth pre-pass when the frame needs one.
    void planCamera(const PassPlanInputs& in, bool prepass);
    // The receiver masks of the frame's fixed maps, from the pre-pass.
    void planMasks(const PassPlanInputs& in);
    // Batches nearest the sun first, by the height of their boxes' centres (along the light
    // when the sun is on the horizon): the trees before the terrain under them, so the
    // terrain's covered texels are rejected rather than written and overwritten (the samples
    // a pass writes per texel, PassStats). One order for every map and virtual page of the sun.
    std::vector<uint32_t> nearestFirst(const core::Vec3& wsTowardsLight) const;
    // The sun's fixed maps' lists (receiver-masked when asked).
    void planSunMaps(const PassPlanInputs& in, std::vector<PassList*>& lists);
    // GPU-driven: `out`, the CPU's list of the large clustered meshes meeting `volume` (a map's
    // or a page's), whose clusters meeting it the pass draws; the GPU culls the rest.
    void collectClustered(std::span<const visibility::HalfSpace> volume, const LodChoice* lod, PassList& out);
    // m_cameraClustered into its own buffer: the GPU's camera pre-pass draws it before plan()
    // uploads the frame's lists.
    void uploadCameraClustered();
    // Virtual maps: the pages the receivers request, each with the casters in its own volume.
    void planPages(const PassPlanInputs& in, VirtualPages& pages, std::vector<PassList*>& lists);
    // Every local light's map: full meshes, culled to each pass's volume.
    void planLocal(const PassPlanInputs& in);
    // GPU culling's pass of the first local list: after the camera's and the sun maps'.
    static size_t firstLocalPass(const core::ShadowSetup& setup);
    // GPU culling's pass of the first virtual page's list: after the local lights'.
    static size_t firstPagePass(const PassPlanInputs& in);

    std::optional<Visibility> m_visibility;
    std::unique_ptr<OcclusionCuller> m_occlusion;
    std::unique_ptr<GpuCulling> m_gpuCulling;
    std::unique_ptr<ReceiverMasks> m_receiverMasks;
    const std::vector<visibility::ReceiverMask>* m_masks = nullptr; // this frame's, CPU-side
    std::unique_ptr<DepthRangeReduction> m_depthRange;
    std::optional<CameraDepthTarget> m_cameraDepth; // the pre-pass's target
    bool m_prepassUnreduced = false;                // m_cameraDepth holds a pre-pass not yet reduced
    bool m_prepassThisFrame = false;                // m_cameraDepth holds the last planned frame's pre-pass
    bool m_depthRangeWanted = false;                // lastVisibleDepth() has been asked
    std::vector<uint32_t> m_prepassDrawn;
    std::vector<core::Aabb> m_movedBoxes;  // old and new boxes of instances moved since the last frame
    std::vector<core::Aabb> m_batchBounds; // each batch's instances, as loaded: the sun maps' draw order
    int m_prepassesDrawn = 0;
    // What the camera's list and pre-pass depend on. A DepthRange plan keeps its camera part for
    // the frame that follows it with the same key (the frame driver measures the visible depth,
    // then draws that frame): one pre-pass, not two. Not with GPU culling, whose per-frame
    // buffers the next frame resets.
    struct CameraKey {
        core::Mat4 clipFromWorld{1.0};
        int width = 0, height = 0;
        Culling culling = Culling::Off;
        bool lod = false;
        float lodPixelError = 0.0f;
        float lodFoliageScale = 0.0f;
        float lodFade = 0.0f;
        bool operator==(const CameraKey&) const = default;
    };
    std::optional<CameraKey> m_keptCamera;
    CullingCosts m_keptCameraCosts;

    PassList m_camera;
    PassList m_cameraClustered;           // Culling::Gpu: the clustered meshes in view (the CPU's)
    bool m_cameraLeavesClustered = false; // this frame's camera list leaves them to m_cameraClustered
    Buffer m_cameraClusteredBuffer;       // m_cameraClustered's entries (uploaded before the frame's lists)
    size_t m_cameraClusteredCapacity = 0;
    std::vector<PassList> m_sun, m_pages, m_local;
    std::vector<PassList> m_sunClustered;       // Culling::Gpu: each fixed map's clustered meshes (the CPU's)
    std::vector<PassList> m_localClustered;     // Culling::Gpu: each local list's clustered meshes (the CPU's)
    std::vector<PassList> m_pageCulled;         // Culling::Gpu: each page's GPU-culled casters
    size_t m_pageRoom = 0;                      // pages a GPU-driven frame culls on the GPU
    std::vector<uint32_t> m_clusteredInstances; // of the meshes that draw by clusters (the CPU's per map and page)
    std::vector<uint32_t> m_clusteredMeeting;   // collectClustered's, kept to allocate nothing
    std::vector<bool> m_alphaTested;            // per scene batch: GpuScene::alphaTested
    std::vector<uint32_t> m_localFaces;         // per local list: the faces a geometry shader draws each instance into
    std::vector<std::vector<visibility::HalfSpace>> m_localVolumes; // per local list
    CullingCosts m_costs;
};

} // namespace shadowkit::gl
