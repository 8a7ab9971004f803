// The Renderer facade: it validates a frame's inputs against the driver and sequences the pass
// rooms — the culling planner (pass_lists.h), the sun's pass (sun_pass.h), the local lights'
// maps (local_shadows.h) and the camera passes (camera_passes.h) — in GPU order:
//
//   plan lists (camera pre-pass when culling, masks or pages need it) → sun maps → local maps
//   → [eval pass → blur] → main pass (or the eval pass, for renderEvalBuffers; or both in one
//   pass, for renderWithEvalBuffers without the blur)
//
// Each room owns its GL objects and takes the frame's inputs as arguments.
#include "shadowkit/gl/renderer.h"

#include "camera_passes.h"
#include "frame_check.h"
#include "gpu_figures.h"
#include "gpu_scene.h"
#include "line_pass.h"
#include "local_shadows.h"
#include "pass_lists.h"
#include "pass_timer.h"
#include "scene_frame.h"
#include "sun_pass.h"

#include <string>

namespace shadowkit::gl {

struct Renderer::Impl {
    std::optional<GpuScene> scene;
    std::unique_ptr<PassLists> lists;       // what every pass draws
    std::unique_ptr<SunPass> sun;           // the sun's maps
    std::unique_ptr<LocalShadowMaps> local; // the spot and point lights' maps
    std::unique_ptr<CameraPasses> camera;   // main, eval, blur
    std::unique_ptr<LinePass> lines;
    PassTimer localTimer;
    core::LocalLighting localLights;          // Renderer::setLocalLights, in the scene's coordinates
    core::LocalLighting wsLocalLights;        // the same as given: Renderer::localLights()
    core::Vec3 wsOrigin{0.0};                 // Scene::wsOrigin: where the GPU's coordinates start
    PassStats lastShadow;                     // the last sun shadow pass (its GPU time not read)
    DrawStats sunDrawnOnCpu;                  // of which drawn from lists culled on the CPU (FrameFigureSources)
    DrawStats localDrawnOnCpu;                // the local maps' likewise
    int64_t frames = 0;                       // render() calls
    GpuFigureRing figures;                    // every frame's GPU times, samples, GPU-culled counts
    bool lateFigures = false;                 // Renderer::readGpuFiguresLate
    Culling autoCulling = Culling::Occlusion; // what Culling::Auto is on this driver (read at create)

    // The settings a frame is drawn with: Culling::Auto resolved for this driver, and the camera
    // choosing levels in the scene's coordinates, as inScene puts the frame's. Every public entry
    // takes its settings through here, so no pass sees Auto or a world-space level camera.
    RenderSettings resolved(const RenderSettings& asked) const {
        RenderSettings settings = asked;
        if (asked.culling == Culling::Auto) settings.culling = autoCulling;
        if (settings.lodCamera) settings.lodCamera->wsEye -= wsOrigin;
        return settings;
    }

    // Checks the frame against the driver and the settings' ranges, allocates the maps and plans
    // every pass's lists; returns the frame's bias.
    core::Result<core::BiasSettings> prepare(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                             const core::ShadowSetup& setup, const RenderSettings& settings,
                                             PassPurpose purpose);
    // The sun's maps, then the local lights' (shadow terms every camera pass reads).
    core::Result<PassStats> shadowPasses(const core::DirectionalLight& light, const core::ShadowSetup& setup,
                                         const RenderSettings& settings, const core::BiasSettings& bias);
    // Culling::Gpu: what the sun's lists drew, read back into lastShadow (waits for the GPU).
    void readGpuShadowDraws(const RenderSettings& settings) {
        // No sun: nothing was drawn, nothing to read back.
        if (settings.culling != Culling::Gpu || lastShadow.drawCalls == 0) return;
        DrawStats drawn = sunDrawnOnCpu;
        drawn += lists->gpuSunDrawn(settings.foliageOpacity);
        keepGpuShadowDraws(drawn);
    }
    // What the sun's lists drew, GPU-culled and not, into lastShadow (no sun: nothing was drawn).
    void keepGpuShadowDraws(const DrawStats& drawn) {
        if (lastShadow.drawCalls > 0) lastShadow.instances = drawn.instances, lastShadow.triangles = drawn.triangles;
    }
    // The frame's GPU figures into `stats`: waited for now, or handed to the ring (and those
    // of earlier frames that came back taken from it).
    void gpuFigures(FrameStats& stats, const RenderSettings& settings, const DrawStats& mainDraws);
    // A frame: the shadow passes, then the main pass; with `evalBuffers`, the eval pass's buffers
    // of the same frame are read into it first (renderWithEvalBuffers).
    core::Result<FrameStats> frame(const SceneFrame& frame, const core::DirectionalLight& light,
                                   const RenderSettings& settings, core::RasterBuffers* evalBuffers);
    // The eval pass's buffers after the shadow passes (PassPurpose::Frame) or none (Surfaces).
    core::Result<core::RasterBuffers> evalBuffers(const SceneFrame& frame, const core::DirectionalLight& light,
                                                  const RenderSettings& settings, int localLight, PassPurpose purpose);
    // The Frame block and every map the camera passes look up; `evalLight` ≥ 0: the eval pass
    // reads that local light's map as its shadow term.
    void bindFrame(const CameraView& view, bool readBlurredMask, int evalLight) const {
        camera->bindFrame(view, readBlurredMask);
        sun->bind(view.setup, view.settings);
        local->bind(localLights, view.settings.localBias, evalLight, view.settings.sun);
    }
};

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

core::Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Scene& scene) {
    // Draw lists keep 24 bits of an entry for the instance's index in its batch (visibility.h).
    for (size_t b = 0; b < scene.batches.size(); ++b)
        if (scene.batches[b].worldFromObject.size() > size_t{kListIndexMask} + 1)
            return core::makeError("renderer: batch " + std::to_string(b) + " has " +
                                   std::to_string(scene.batches[b].worldFromObject.size()) +
                                   " instances; at most 16,777,216 fit one batch's draw lists");
    auto renderer = std::unique_ptr<Renderer>(new Renderer);
    Impl& r = *renderer->m_impl;
    r.wsOrigin = scene.wsOrigin;
    const auto* glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    r.autoCulling = resolveCulling(Culling::Auto, glRenderer ? glRenderer : "");
    auto sun = SunPass::create();
    if (!sun) return sun.errorInfo();
    r.sun = std::move(sun).value();
    auto camera = CameraPasses::create();
    if (!camera) return camera.errorInfo();
    r.camera = std::move(camera).value();
    auto lines = LinePass::create();
    if (!lines) return lines.errorInfo();
    r.lines = std::move(lines).value();
    auto local = LocalShadowMaps::create();
    if (!local) return local.errorInfo();
    r.local = std::move(local).value();
    // Levels of detail of every mesh, for the camera and for shadow maps (meshoptimizer).
    std::vector<scene::MeshLods> lods;
    for (const scene::Mesh& mesh : scene.meshes) lods.push_back(scene::buildLods(mesh, lodOptionsOf(scene, mesh)));
    r.scene.emplace(scene, lods);
    auto lists = PassLists::create(scene, lods, *r.scene);
    if (!lists) return lists.errorInfo();
    r.lists = std::move(lists).value();
    // Conventions (core/conventions.h): clip depth [0,1].
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    return renderer;
}

core::Result<core::BiasSettings> Renderer::Impl::prepare(const core::PerspectiveCamera& cam,
                                                         const core::DirectionalLight& light,
                                                         const core::ShadowSetup& setup, const RenderSettings& settings,
                                                         PassPurpose purpose) {
    const core::BiasSettings bias = biasFor(setup, settings);
    if (auto s = checkFrame(setup, settings, bias); !s) return s.errorInfo();
    if (auto s = camera->prepare(setup.clipmap.has_value()); !s) return s.errorInfo();
    if (settings.culling == Culling::Gpu)
        if (auto s = lists->prepareGpuCulling(); !s)
            return core::environmentError("culling: gpu is not available on this GL driver: " + s.errorInfo().message,
                                          "culling");
    if (auto s = sun->prepare(setup, settings, bias); !s) return s.errorInfo();
    // The pre-pass reads the camera's Frame block.
    if (PassLists::needsPrepass(setup, settings, purpose)) bindFrame({cam, light, setup, settings, bias}, false, -1);
    lists->plan(
        {cam, setup, light.wsTowardsLight(), settings, bias, localLights, local->resolve(settings.localPass), purpose},
        sun->pages());
    return bias;
}

core::Result<PassStats> Renderer::Impl::shadowPasses(const core::DirectionalLight& light,
                                                     const core::ShadowSetup& setup, const RenderSettings& settings,
                                                     const core::BiasSettings& bias) {
    auto sunStats = sun->draw(*scene, setup, settings, bias, light.wsTowardsLight(), lists->sunCasters(),
                              {lists->pageLists(), lists->pageCulledLists()});
    if (!sunStats) return sunStats.errorInfo();
    lastShadow = *sunStats;
    // A GPU-culled list's draws count no instance or triangle here (the GPU alone knows them).
    sunDrawnOnCpu = {sunStats->instances, sunStats->triangles, 0};
    localTimer.begin();
    auto localStats = local->draw(*scene, localLights, lists->localCasters(), lists->localVolumes(), settings.localPass,
                                  settings.filter.kind == core::ShadowFilter::Pcf2);
    localTimer.end();
    if (localStats) localDrawnOnCpu = {localStats->instances, localStats->triangles, 0};
    return localStats;
}

core::Result<FrameStats> Renderer::render(const core::PerspectiveCamera& wsCamera, const core::DirectionalLight& light,
                                          const core::ShadowSetup& wsSetup, const RenderSettings& asked) {
    return m_impl->frame(inScene(m_impl->wsOrigin, wsCamera, wsSetup), light, m_impl->resolved(asked), nullptr);
}

core::Result<std::pair<FrameStats, core::RasterBuffers>>
Renderer::renderWithEvalBuffers(const core::PerspectiveCamera& wsCamera, const core::DirectionalLight& light,
                                const core::ShadowSetup& wsSetup, const RenderSettings& asked) {
    core::RasterBuffers buffers;
    auto stats = m_impl->frame(inScene(m_impl->wsOrigin, wsCamera, wsSetup), light, m_impl->resolved(asked), &buffers);
    if (!stats) return stats.errorInfo();
    return std::pair{*stats, std::move(buffers)};
}

core::Result<FrameStats> Renderer::Impl::frame(const SceneFrame& sceneFrame, const core::DirectionalLight& light,
                                               const RenderSettings& settings, core::RasterBuffers* evalBuffers) {
    const core::PerspectiveCamera& cam = sceneFrame.camera;
    const core::ShadowSetup& setup = sceneFrame.setup();
    const auto bias = prepare(cam, light, setup, settings, PassPurpose::Frame);
    if (!bias) return bias.errorInfo();
    FrameStats stats;
    auto localStats = shadowPasses(light, setup, settings, *bias);
    if (!localStats) return localStats.errorInfo();
    stats.local = *localStats;
    for (const core::ShadowSetup& s : localLights.pointSetups)
        stats.localMaps += static_cast<int>(s.views.size()), stats.skippedFaces += s.skippedFaces;
    for (const core::ShadowSetup& s : localLights.spotSetups) stats.localMaps += static_cast<int>(s.views.size());

    const CameraView view{cam, light, sun->lookupSetup(setup, settings), settings, *bias};
    const bool blurred = settings.blur.iterations > 0;
    core::Result<DrawStats> mainDraws = DrawStats{};
    int maskIndex = -1;
    if (evalBuffers && !blurred) {
        // The evaluation's buffers and the picture from one draw of the camera's view.
        bindFrame(view, false, -1);
        mainDraws = camera->evalAndMainPass(*scene, lists->cameraCasters(), view, lists->cameraPrepass());
    } else {
        // With the eye-space blur, the shadow term comes from the blurred screen-space mask,
        // which the eval pass draws first.
        if (blurred) {
            bindFrame(view, false, -1);
            if (auto s = camera->evalPass(*scene, lists->cameraCasters(), view, lists->cameraPrepass()); !s)
                return s.errorInfo();
            maskIndex = camera->blurPass(settings.blur);
        }
        bindFrame(view, blurred, -1);
        mainDraws = camera->mainPass(*scene, lists->cameraCasters(), view, maskIndex, lists->cameraPrepass());
    }
    if (!mainDraws) return mainDraws.errorInfo();
    if (evalBuffers) { // the eval pass's buffers (neither the blur nor the main pass writes them)
        *evalBuffers = camera->readEval();
        evalBuffers->mapSize = setup.mapSize;
        if (blurred) evalBuffers->shadowTerm = camera->readBlurred(maskIndex);
    }
    stats.frame = ++frames;
    gpuFigures(stats, settings, *mainDraws);
    lists->costs().fill(stats);
    stats.virtualPages = sun->lastVirtual();
    return stats;
}

void Renderer::Impl::gpuFigures(FrameStats& stats, const RenderSettings& settings, const DrawStats& mainDraws) {
    stats.shadow = lastShadow;
    stats.shadow.mapTexels = sun->mapTexels();
    stats.main = {0.0, mainDraws.instances, mainDraws.triangles, mainDraws.drawCalls};
    FrameFigureSources sources{sun->timer(),   localTimer,        camera->timer(),
                               sun->samples(), camera->samples(), sun->mapTexels()};
    if (const OpacityLayers* opacity = sun->opacity()) {
        sources.firstLeafSamples = &opacity->firstLeafSamples();
        sources.leafSamples = &opacity->leafSamples();
    }
    if (settings.culling == Culling::Gpu) lists->describeGpuLists(sources, settings.foliageOpacity);
    sources.sunDrawnOnCpu = sunDrawnOnCpu;
    sources.localDrawnOnCpu = localDrawnOnCpu;
    sources.mainDrawnOnCpu = mainDraws;
    figures.take(stats, sources, lateFigures);
    if (!lateFigures && sources.commands) keepGpuShadowDraws({stats.shadow.instances, stats.shadow.triangles, 0});
}

void Renderer::readGpuFiguresLate(bool late) { m_impl->lateFigures = late; }

std::vector<GpuFigures> Renderer::finishGpuFigures() { return m_impl->figures.finish(); }

core::Result<core::RasterBuffers> Renderer::renderEvalBuffers(const core::PerspectiveCamera& wsCamera,
                                                              const core::DirectionalLight& light,
                                                              const core::ShadowSetup& wsSetup,
                                                              const RenderSettings& settings, int localLight) {
    if (localLight < -1 || localLight >= static_cast<int>(m_impl->localLights.size()))
        return core::makeError("renderer: local light " + std::to_string(localLight) + " does not exist (" +
                               std::to_string(m_impl->localLights.size()) + " set)");
    return m_impl->evalBuffers(inScene(m_impl->wsOrigin, wsCamera, wsSetup), light, m_impl->resolved(settings),
                               localLight, PassPurpose::Frame);
}

core::Result<core::RasterBuffers> Renderer::renderSurfaceBuffers(const core::PerspectiveCamera& wsCamera,
                                                                 const core::DirectionalLight& light,
                                                                 const core::ShadowSetup& wsSetup,
                                                                 const RenderSettings& settings) {
    return m_impl->evalBuffers(inScene(m_impl->wsOrigin, wsCamera, wsSetup), light, m_impl->resolved(settings), -1,
                               PassPurpose::Surfaces);
}

core::Result<core::RasterBuffers> Renderer::Impl::evalBuffers(const SceneFrame& frame,
                                                              const core::DirectionalLight& light,
                                                              const RenderSettings& settings, int localLight,
                                                              PassPurpose purpose) {
    const core::ShadowSetup& setup = frame.setup();
    const auto bias = prepare(frame.camera, light, setup, settings, purpose);
    if (!bias) return bias.errorInfo();
    const bool shadows = purpose == PassPurpose::Frame;
    lastShadow = {};
    sunDrawnOnCpu = localDrawnOnCpu = {};
    if (shadows)
        if (auto s = shadowPasses(light, setup, settings, *bias); !s) return s.errorInfo();
    readGpuShadowDraws(settings);
    const CameraView view{frame.camera, light, sun->lookupSetup(setup, settings), settings, *bias};
    bindFrame(view, false, localLight);
    if (auto s = camera->evalPass(*scene, lists->cameraCasters(), view, lists->cameraPrepass()); !s)
        return s.errorInfo();
    core::RasterBuffers buffers = camera->readEval();
    if (!shadows) std::ranges::fill(buffers.shadowTerm, 1.0f); // no map was drawn: lit
    if (localLight >= 0) {                                     // the eye-space blur is the sun's
        buffers.mapSize = localLights.mapSize;
        return buffers;
    }
    if (shadows && settings.blur.iterations > 0)
        buffers.shadowTerm = camera->readBlurred(camera->blurPass(settings.blur));
    buffers.mapSize = setup.mapSize;
    return buffers;
}

core::Result<std::optional<core::Vec2>> Renderer::visibleDepth(const core::PerspectiveCamera& wsCamera,
                                                               const core::DirectionalLight& light,
                                                               const core::ShadowSetup& wsSetup,
                                                               const RenderSettings& settings) {
    Impl& r = *m_impl;
    const SceneFrame frame = inScene(r.wsOrigin, wsCamera, wsSetup);
    // The culling's own pre-pass, or one made for the purpose; no shadow pass.
    if (auto s = r.prepare(frame.camera, light, frame.setup(), r.resolved(settings), PassPurpose::DepthRange); !s)
        return s.errorInfo();
    return r.lists->visibleDepthNow();
}

std::optional<core::Vec2> Renderer::lastVisibleDepth() { return m_impl->lists->lastVisibleDepth(); }

Culling Renderer::culling(Culling requested) const {
    return requested == Culling::Auto ? m_impl->autoCulling : requested;
}

int Renderer::cameraPrePassesDrawn() const { return m_impl->lists->prepassesDrawn(); }

int Renderer::cameraViewsDrawn() const { return m_impl->camera->viewsDrawn(); }

std::optional<VirtualPageStats> Renderer::lastVirtualPages() const { return m_impl->sun->lastVirtual(); }

PassStats Renderer::lastShadowPass() const { return m_impl->lastShadow; }

LevelsDrawn Renderer::levelsDrawn() const { return m_impl->lists->levelsDrawn(); }

WorkByLevel Renderer::workByLevel() const { return m_impl->lists->workByLevel(*m_impl->scene); }

core::Status Renderer::moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved) {
    Impl& r = *m_impl;
    if (scene.instanceCount() != r.lists->hierarchy().size())
        return core::makeError("renderer: moveInstances() needs the scene it was created with (" +
                               std::to_string(r.lists->hierarchy().size()) + " instances, got " +
                               std::to_string(scene.instanceCount()) + ")");
    // Every index checked before anything moves.
    std::vector<bool> batchMoved(scene.batches.size(), false);
    for (const uint32_t global : moved) {
        const auto ref = scene.locate(global);
        if (!ref) return core::makeError("renderer: moved instance " + std::to_string(global) + " is out of range");
        if (!scene.batches[ref->batch].dynamic)
            return core::makeError("renderer: moved instance " + std::to_string(global) + " belongs to a static batch");
        batchMoved[ref->batch] = true;
    }
    for (const uint32_t global : moved) {
        const scene::InstanceRef ref = *scene.locate(global);
        const scene::MeshBatch& b = scene.batches[ref.batch];
        r.lists->move(
            global, core::transformBounds(core::Mat4(b.worldFromObject[ref.instance]), scene.meshes[b.mesh].osBounds));
    }
    r.lists->afterMoves();
    for (size_t batch = 0; batch < scene.batches.size(); ++batch)
        if (batchMoved[batch]) r.scene->updateBatch(scene, batch);
    // A deformed mesh changed its shape as well as its box (scene::animate posed it).
    for (const scene::MeshDeformation& deformation : scene.deformations)
        if (deformation.batch < batchMoved.size() && batchMoved[deformation.batch])
            r.scene->reshapeMesh(scene, scene.batches[deformation.batch].mesh);
    return core::Ok{};
}

core::Status Renderer::setLocalLights(core::LocalLighting lights) {
    if (auto s = checkLocalLights(lights); !s) return s;
    m_impl->localLights = m_impl->wsOrigin == core::Vec3(0.0) ? lights : core::rebased(lights, m_impl->wsOrigin);
    m_impl->wsLocalLights = std::move(lights);
    return core::Ok{};
}

const core::LocalLighting& Renderer::localLights() const { return m_impl->wsLocalLights; }

scene::Image Renderer::readLocalShadowMaps() const { return m_impl->local->readAsGreys(m_impl->localLights); }

core::Aabb Renderer::wsSceneBounds() const {
    const core::Aabb& local = m_impl->lists->bounds();
    return local.isEmpty() ? local : core::Aabb::fromMinMax(local.min + m_impl->wsOrigin, local.max + m_impl->wsOrigin);
}

void Renderer::drawLines(const core::PerspectiveCamera& camera, std::span<const LineSegment> lines) {
    const ColorTarget* color = m_impl->camera->color();
    if (!color) return;
    glBindFramebuffer(GL_FRAMEBUFFER, color->framebuffer.id());
    glViewport(0, 0, color->width, color->height);
    core::PerspectiveCamera local = camera; // in the scene's coordinates, as inScene (scene_frame.h)
    local.wsEye -= m_impl->wsOrigin;
    std::vector<LineSegment> segments(lines.begin(), lines.end());
    for (LineSegment& line : segments) line.wsFrom -= m_impl->wsOrigin, line.wsTo -= m_impl->wsOrigin;
    m_impl->lines->draw(local.clipFromWorld(), segments);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::present(int width, int height) const {
    const ColorTarget* color = m_impl->camera->color();
    if (!color) return;
    glBlitNamedFramebuffer(color->framebuffer.id(), 0, 0, 0, color->width, color->height, 0, 0, width, height,
                           GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

scene::Image Renderer::readColor() const {
    const ColorTarget* color = m_impl->camera->color();
    return color ? color->read() : scene::Image{};
}

scene::Image Renderer::readVirtualPageTable() const { return m_impl->sun->readPageTable(); }

scene::Image Renderer::readShadowMap() const { return m_impl->sun->readMaps(); }

} // namespace shadowkit::gl
