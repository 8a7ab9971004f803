// Renders a scene with a shadow set-up: the shadow-map depth pass, then the shaded
// camera view, into off-screen targets that can be read back as images.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <memory>
#include <optional>
#include <span>
#include <utility>

namespace shadowkit::gl {

// Cameras, lights, set-ups and lines come in world coordinates; the renderer draws in the
// scene's (scene::Scene::wsOrigin at 0), rebasing every frame's set-up in double from its
// eye-relative matrices, so a scene 1,000 km from the origin is drawn as precisely as at it.
// Inside libs/gl every GPU-side position is in that scene space and keeps the world names
// (`ws`, `*FromWorld`), as core/conventions.h has code that holds one space do; `qs` is
// written only where world and scene meet (scene_frame.h).
class Renderer {
public:
    // Uploads the scene and builds the programs; needs a current Context.
    static core::Result<std::unique_ptr<Renderer>> create(const scene::Scene& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Validates the settings and the set-up's map size against the driver's limits, then draws.
    core::Result<FrameStats> render(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                    const core::ShadowSetup& setup, const RenderSettings& settings);

    // The shadow pass, then instead of shading, the per-pixel buffers the evaluation
    // compares with ray-traced truth (shadow term — filtered and blurred as the settings
    // say —, surface identity, depth, normal, shadow texel coordinates and their screen
    // derivatives).
    // With `localLight` ≥ 0 the shadow term, texel coordinates and their derivatives are those
    // of that local light's map (points first, then spots), without its range and cone.
    core::Result<core::RasterBuffers> renderEvalBuffers(const core::PerspectiveCamera& camera,
                                                        const core::DirectionalLight& light,
                                                        const core::ShadowSetup& setup, const RenderSettings& settings,
                                                        int localLight = -1);

    // render(), handing back too the eval pass's buffers of the same frame — drawn over its maps,
    // lists and pre-pass, in the same pass as the picture (with the eye-space blur, the pass
    // before it) — what renderEvalBuffers() gives for these inputs without drawing the shadow
    // passes, the culling and the camera's view a second time (an evaluation that wants the
    // shaded frame too).
    core::Result<std::pair<FrameStats, core::RasterBuffers>>
    renderWithEvalBuffers(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                          const core::ShadowSetup& setup, const RenderSettings& settings);

    // The eval pass's surfaces alone, with no shadow pass drawn: surface identity, view depth,
    // normals — the visible receivers a sampling model reads (readReceivers). The shadow term
    // reads lit everywhere and the texel fields are not meaningful; `setup` only chooses the
    // pass's variant (and is checked as render() checks it).
    core::Result<core::RasterBuffers> renderSurfaceBuffers(const core::PerspectiveCamera& camera,
                                                           const core::DirectionalLight& light,
                                                           const core::ShadowSetup& setup,
                                                           const RenderSettings& settings);

    // The spot and point lights of the frames to come, with their set-ups (core::computeLocalLighting
    // for the frame's camera), drawn beside the sun until set again. At most
    // kMaxLocalLightsPerKind of each kind.
    core::Status setLocalLights(core::LocalLighting lights);
    const core::LocalLighting& localLights() const;

    // The view-depth range of what this camera sees ([nearest, farthest] drawn; nullopt for
    // an empty frame), for ShadowSetupInputs::visibleDepth: a camera depth pre-pass (the
    // culling's own, CHC++ included) reduced to min / max on the GPU, 8 bytes read back.
    // For a single frame; it waits for the GPU.
    core::Result<std::optional<core::Vec2>> visibleDepth(const core::PerspectiveCamera& camera,
                                                         const core::DirectionalLight& light,
                                                         const core::ShadowSetup& setup,
                                                         const RenderSettings& settings);
    // The same range from the last frame render() drew, when it made a camera pre-pass
    // (Culling::Occlusion or receiverMask): what a running application feeds to its next
    // frame's set-up, by then long computed, so nothing waits (Scherzer 2005 took Δz "from
    // the visibility algorithm" the same way). nullopt without a pre-pass or visible pixels.
    std::optional<core::Vec2> lastVisibleDepth();
    // The culling a frame asking for `requested` is drawn with: Culling::Auto resolved for this
    // renderer's driver (resolveCulling: Gpu on a GPU, Occlusion on a software rasteriser),
    // anything else as asked. What front ends print.
    Culling culling(Culling requested) const;
    // How render() reads the GPU's figures (pass times, samples, GPU-culled counts). By default
    // each frame waits for its own (exact at once, a stall a frame on a GPU). Late: each frame
    // hands its figures to a ring the GPU fills and returns, without waiting, those of earlier
    // frames whose fence has passed (FrameStats::gpuFigures, two or three frames late): what an
    // application loop wants. finishGpuFigures() waits for the rest.
    void readGpuFiguresLate(bool late);
    // Every frame's figures not yet returned, after waiting for the GPU (one synchronisation,
    // outside any frame): what a benchmark collects at the end of its frames.
    std::vector<GpuFigures> finishGpuFigures();
    // Camera depth pre-passes drawn since the renderer was created (work, for tests and benches):
    // a render() right after visibleDepth() for the same camera and culling reuses that one.
    int cameraPrePassesDrawn() const;
    // Passes that drew the camera's view — main, eval, or both in one (renderWithEvalBuffers
    // without the eye-space blur) — since the renderer was created (work, for tests and benches).
    int cameraViewsDrawn() const;

    // Instances that moved since the last frame (scene::animate's list of global indices),
    // all of dynamic batches of the scene the renderer was created with: their transforms
    // go to the GPU, their boxes into the instance hierarchy (refitted to the root), and the
    // vertices of a mesh the scene deforms (Scene::deformations) with them. Fails, changing
    // nothing, for an index out of range or of a static batch.
    core::Status moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved);

    // Technique virtual: the pages of the last frame drawn (render or renderEvalBuffers); nullopt
    // when that frame had no virtual maps.
    std::optional<VirtualPageStats> lastVirtualPages() const;
    // What the last frame's sun shadow pass drew (render or renderEvalBuffers); its GPU time is
    // left 0 here (render's FrameStats has it).
    PassStats lastShadowPass() const;
    // The level of detail the last frame (render or renderEvalBuffers) drew each instance at, in
    // the camera pass and in the sun's maps or pages (the finest where several drew it): what a
    // report's level map shows. GPU-culled lists are read back, a wait: not for every frame.
    LevelsDrawn levelsDrawn() const;
    // What the last frame's camera pass and sun pass drew at each level of detail: where a
    // frame's triangles go. Reads GPU-culled lists back like levelsDrawn (a wait).
    WorkByLevel workByLevel() const;

    // World bounds of every instance, from the instance hierarchy: O(1).
    core::Aabb wsSceneBounds() const;

    // The last rendered frame (top row first).
    scene::Image readColor() const;
    // Draws segments over the last rendered frame as `camera` sees them (always on top: no
    // depth test); readColor() and present() then include them.
    void drawLines(const core::PerspectiveCamera& camera, std::span<const LineSegment> lines);
    // Copies the last rendered frame into the current context's default framebuffer (a
    // window's), scaled to width × height pixels; nothing before the first frame.
    void present(int width, int height) const;
    // The last shadow maps as greys, side by side: near the light is bright, empty texels black.
    scene::Image readShadowMap() const;
    // The local lights' last maps likewise: spot maps, then each cube unfolded as a cross.
    scene::Image readLocalShadowMaps() const;
    // Technique virtual: the last frame's page table, a tile per level, finest first: a page
    // shown in its level's --cascade-colors tint, one requested but served coarser (pool full,
    // over the page budget) white. Empty for every other technique.
    scene::Image readVirtualPageTable() const;

private:
    Renderer();
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace shadowkit::gl
