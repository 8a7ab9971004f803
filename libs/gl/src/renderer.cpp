#include "shadowkit/gl/renderer.h"

#include "camera_programs.h"
#include "depth_range.h"
#include "gl_object.h"
#include "gl_shaders.h"
#include "gpu_culling.h"
#include "gpu_scene.h"
#include "line_pass.h"
#include "local_shadows.h"
#include "lookup_reach.h"
#include "moment_maps.h"
#include "occlusion_culling.h"
#include "program.h"
#include "receiver_masks.h"
#include "render_targets.h"
#include "scene_frame.h"
#include "stopwatch.h"
#include "uniforms.h"
#include "virtual_pages.h"
#include "visibility.h"

#include "shadowkit/core/light_size.h"
#include "shadowkit/core/output_conventions.h"

#include <algorithm>
#include <optional>
#include <string>

namespace shadowkit::gl {
namespace {

glm::mat4 toFloat(const core::Mat4& m) { return glm::mat4(m); }

// Measures the GPU time of the commands between begin() and end() with two timestamp
// queries. (A GL_TIME_ELAPSED query around the layered shadow pass came back as an absolute
// time on Mesa llvmpipe, ~4e6 ms; timestamps do not depend on how the driver splits the work.)
class PassTimer {
public:
    PassTimer() {
        GLuint ids[2] = {0, 0};
        glCreateQueries(GL_TIMESTAMP, 2, ids);
        m_start = Query(ids[0]);
        m_end = Query(ids[1]);
    }
    void begin() const { glQueryCounter(m_start.id(), GL_TIMESTAMP); }
    void end() const { glQueryCounter(m_end.id(), GL_TIMESTAMP); }
    double milliseconds() const {
        GLuint64 start = 0, end = 0;
        glGetQueryObjectui64v(m_start.id(), GL_QUERY_RESULT, &start);
        glGetQueryObjectui64v(m_end.id(), GL_QUERY_RESULT, &end);
        return end > start ? static_cast<double>(end - start) * 1e-6 : 0.0;
    }

private:
    Query m_start, m_end;
};

constexpr glm::vec3 kSky(0.62f, 0.72f, 0.85f);
constexpr glm::vec3 kNightSky(0.015f, 0.02f, 0.04f);

// Daylight, 1 to 0: full with the sun at 20° or higher, fading to night's at the horizon
// (dusk in the `village` view); 0 with the sun off. A look only: the shadow terms the
// evaluation compares do not depend on it.
float daylight(const core::DirectionalLight& light, const RenderSettings& settings) {
    return settings.sun ? glm::smoothstep(0.0f, 0.342f, static_cast<float>(light.wsTowardsLight().y)) : 0.0f; // sin 20°
}

// The instances a point light's cube may draw: those meeting the cube around its range.
std::vector<visibility::HalfSpace> rangeBox(const core::Vec3& wsLight, double range) {
    std::vector<visibility::HalfSpace> box;
    for (int axis = 0; axis < 3; ++axis)
        for (const double side : {1.0, -1.0}) {
            core::Vec4 h(0.0);
            h[axis] = side; // side · x + (range − side · light) >= 0
            h.w = range - side * wsLight[axis];
            box.push_back(h);
        }
    return box;
}

} // namespace

struct Renderer::Impl {
    std::optional<GpuScene> scene;
    std::optional<Visibility> visibility;
    std::vector<PassList> shadowLists; // one per shadow map of the frame
    PassList cameraList;
    CpuTimes cullTimes;   // building this frame's lists
    CpuTimes cullGlTimes; // of which inside GL doing or awaiting GPU work (FrameStats)
    CpuTimes listTimes;   // of which choosing levels and building lists (FrameStats)
    std::unique_ptr<OcclusionCuller> occlusion;
    std::unique_ptr<GpuCulling> gpuCulling;
    std::optional<CameraDepthTarget> cameraDepth; // the occlusion pre-pass's target
    std::vector<uint32_t> occlusionDrawn;
    visibility::CoherentCullingStats occlusionStats;
    double occlusionMilliseconds = 0.0;
    std::unique_ptr<ReceiverMasks> receiverMasks;
    double receiverMaskMilliseconds = 0.0;
    std::unique_ptr<DepthRangeReduction> depthRange; // of every pre-pass: Renderer::lastVisibleDepth
    bool prepassForDepthRange = false;               // Renderer::visibleDepth: a pre-pass even if culling needs none
    ProgramPair depthPrograms;                       // the shadow maps' depth pass
    Program blurProgram;
    PassPrograms depthPass() const { return depthPrograms.passPrograms(); }
    CameraPrograms cameraPrograms; // the main and eval passes, with and without virtual maps
    Buffer depthUniforms, frameUniforms, blurUniforms;
    VertexArray emptyVertexArray;            // for the full-screen triangle
    Sampler rawDepthSampler;                 // kShadowDepthUnit: the sun's maps' stored depths (PCSS's blocker search)
    std::unique_ptr<MomentMaps> moments;     // --filter msm: the sun's maps as prefiltered moments
    core::Status momentsStatus = core::Ok{}; // of the last shadow pass's moments (out of memory)
    std::optional<ShadowTarget> shadow;
    std::optional<ColorTarget> color;
    std::optional<EvalTarget> eval;
    std::optional<MaskPingPong> mask;
    PassTimer shadowTimer, mainTimer, localTimer;
    std::unique_ptr<LocalShadowMaps> localMaps;
    std::unique_ptr<LinePass> lines;
    core::LocalLighting localLights;   // Renderer::setLocalLights, in the scene's coordinates
    core::LocalLighting wsLocalLights; // the same as given: Renderer::localLights()
    core::Vec3 wsOrigin{0.0};          // Scene::wsOrigin: where the GPU's coordinates start

    std::unique_ptr<VirtualPages> virtualPages;  // technique virtual: the page pool
    std::vector<PassList> pageLists;             // this frame's pages to render, one list each
    std::vector<core::Aabb> movedBoxes;          // old and new boxes of instances moved since the last frame
    std::optional<VirtualPageStats> lastVirtual; // of the last frame's page pass
    PassStats lastShadow;                        // the last sun shadow pass (its GPU time not read)

    std::vector<PassList> localLists; // LocalShadowMaps::listCount of them
    int evalLight = -1;               // the eval pass's light (renderEvalBuffers)

    core::BiasSettings bias; // of the frame being drawn (biasFor), set by prepare()

    core::Status prepare(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                         const core::ShadowSetup& setup, const RenderSettings& settings);
    // The instances each pass of the frame draws (visibility.h), uploaded together; with
    // occlusion culling, after the camera's depth pre-pass.
    void collectVisible(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                        const core::ShadowSetup& setup, const RenderSettings& settings);
    PassStats shadowPass(const core::ShadowSetup& setup, const RenderSettings& settings);
    // Culling::Gpu: the sun's pass stats with what its lists drew, read back (waits for the GPU).
    PassStats gpuShadowDraws(PassStats pass) const {
        if (pass.drawCalls == 0) return pass; // no sun: nothing drawn
        const DrawStats drawn = gpuCulling->submitted(shadowLists);
        pass.instances = drawn.instances, pass.triangles = drawn.triangles;
        return pass;
    }
    // Technique virtual: the pages this frame must draw, each into its slot of the atlas.
    PassStats pagePass();
    // The set-up the frame's lookups read: with virtual maps under a page budget, levels may
    // still be shown from an earlier sun's pages (VirtualPages::shown).
    const core::ShadowSetup& lookupSetup(const core::ShadowSetup& setup, const RenderSettings& settings) const {
        return setup.clipmap && settings.sun ? virtualPages->shown() : setup;
    }
    // The GL state both sun passes draw with: depth only, the bias as polygon offset (and
    // caster culling), depth clamp when asked, the depth program and its uniforms bound.
    void beginDepthPass(bool depthClamp) const;
    static void endDepthPass();
    // Every local light's maps, timed.
    core::Result<PassStats> localPass(const RenderSettings& settings);
    void uploadFrame(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                     const core::ShadowSetup& setup, const RenderSettings& settings, bool useMask);
    // The eval pass into `eval` (shadow term, depth, ...), for the evaluation and as the
    // mask the blur starts from.
    core::Status evalPass(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                          const core::ShadowSetup& setup, const RenderSettings& settings);
    // Blurs eval's shadow term; returns the ping-pong index holding the result.
    int blurPass(const RenderSettings& settings);
};

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

core::Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Scene& scene) {
    auto renderer = std::unique_ptr<Renderer>(new Renderer);
    Impl& r = *renderer->m_impl;
    r.wsOrigin = scene.wsOrigin;
    using namespace shaders;
    for (const bool material : {false, true}) {
        const std::string_view withMaterial = kMaterialVariant[material];
        const std::string name = material ? "depth pass, materials" : "depth pass";
        auto depth = buildProgram(name, {withMaterial, kDepthPassGlsl, kDepthVert},
                                  {withMaterial, kDepthPassGlsl, kMaterialGlsl, kDepthFrag});
        if (!depth) return depth.errorInfo();
        if (auto s = checkUniformBlock(*depth, name, "DepthPass", sizeof(DepthPassUniforms), depthPassFields()); !s)
            return s.errorInfo();
        (material ? r.depthPrograms.material : r.depthPrograms.plain) = std::move(depth).value();
    }
    auto blur = buildProgram("blur pass", {kFullscreenVert}, {kBlurFrag});
    if (!blur) return blur.errorInfo();
    if (auto s = checkUniformBlock(*blur, "blur pass", "Blur", sizeof(BlurUniforms), blurFields()); !s)
        return s.errorInfo();
    auto camera = CameraPrograms::create();
    if (!camera) return camera.errorInfo();
    r.cameraPrograms = std::move(camera).value();
    auto lines = LinePass::create();
    if (!lines) return lines.errorInfo();
    r.lines = std::move(lines).value();
    auto localMaps = LocalShadowMaps::create();
    if (!localMaps) return localMaps.errorInfo();
    r.localMaps = std::move(localMaps).value();
    r.blurProgram = std::move(blur).value();
    r.depthUniforms = createBuffer(nullptr, sizeof(DepthPassUniforms));
    r.frameUniforms = createBuffer(nullptr, sizeof(FrameUniforms));
    r.blurUniforms = createBuffer(nullptr, sizeof(BlurUniforms));
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    r.emptyVertexArray = VertexArray(vao);
    r.rawDepthSampler = createRawDepthSampler();
    auto moments = MomentMaps::create();
    if (!moments) return moments.errorInfo();
    r.moments = std::move(moments).value();
    // Levels of detail of every mesh, for the camera and for shadow maps (meshoptimizer). An
    // alpha-tested mesh keeps its one level unless it brings its own (leaf cards: fewer, larger
    // cards): a simplifier moves positions under fixed uvs (and the shadow chain's vertex
    // clustering joins vertices of different cards), so a simplified card would no longer show
    // the leaf.
    std::vector<scene::MeshLods> lods;
    for (const scene::Mesh& mesh : scene.meshes) {
        const scene::Material* material = scene.materialOf(mesh);
        const bool keepWhole = material && material->alphaTested() && mesh.authoredLods.empty();
        lods.push_back(scene::buildLods(mesh, {.maxLevels = keepWhole ? 1 : 4}));
    }
    r.scene.emplace(scene, lods);
    r.visibility.emplace(scene, lods);
    auto occlusion = OcclusionCuller::create(*r.visibility, *r.scene);
    if (!occlusion) return occlusion.errorInfo();
    r.occlusion = std::move(occlusion).value();
    r.gpuCulling = GpuCulling::create(scene, lods, *r.scene);
    auto masks = ReceiverMasks::create();
    if (!masks) return masks.errorInfo();
    r.receiverMasks = std::move(masks).value();
    auto virtualPages = VirtualPages::create();
    if (!virtualPages) return virtualPages.errorInfo();
    r.virtualPages = std::move(virtualPages).value();
    auto depthRange = DepthRangeReduction::create();
    if (!depthRange) return depthRange.errorInfo();
    r.depthRange = std::move(depthRange).value();
    // Conventions (core/conventions.h): clip depth [0,1].
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    return renderer;
}

void Renderer::Impl::collectVisible(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                    const core::ShadowSetup& setup, const RenderSettings& settings) {
    const Stopwatch total;
    visibility->takeListTimes();
    const bool cull = settings.culling != Culling::Off;
    const bool gpu = settings.culling == Culling::Gpu;
    const bool virtualMaps = setup.clipmap.has_value();
    // Virtual maps cull per page, finer than any receiver mask; their pages come from the pre-pass.
    // With GPU culling the masks stay on the GPU, for its passes to test against.
    const bool masked = cull && settings.receiverMask && !virtualMaps;
    const bool prepass = settings.culling == Culling::Occlusion || gpu || masked || prepassForDepthRange || virtualMaps;
    // Camera pass first: with occlusion culling or receiver masks the shadow passes' lists
    // depend on what it sees. Levels by pixels. A simplified receiver lies up to its error
    // off the true surface and would self-shadow against the map (measured without
    // compensation: +0.05 to +0.12 points of false shadow on an aerial view), so its lookup
    // moves that far towards the light (receiverLookup in shadow_lookup.glsl).
    const LodProjection cameraProjection{camera.clipFromWorld(), 0.5 * std::max(settings.width, settings.height),
                                         settings.lodPixelError};
    const LodChoice cameraLod{cameraProjection, std::nullopt, false};
    const LodChoice* cameraLodOrNone = settings.lod ? &cameraLod : nullptr;
    const std::vector<visibility::HalfSpace> cameraVolume = visibility::clipVolume(camera.clipFromWorld());
    occlusionStats = {};
    occlusionMilliseconds = receiverMaskMilliseconds = 0.0;
    cullGlTimes = {};
    if (prepass) {
        if (!cameraDepth || cameraDepth->width != settings.width || cameraDepth->height != settings.height)
            cameraDepth.emplace(settings.width, settings.height);
        uploadFrame(camera, light, setup, settings, false); // the pre-pass reads the camera's Frame
    }
    if (gpu) {
        gpuCulling->beginFrame(GpuCulling::kCameraPasses + (virtualMaps ? 0 : setup.views.size()));
        const Stopwatch cameraTime;
        gpuCulling->camera(camera, cameraLodOrNone, *cameraDepth, cameraList);
        occlusionMilliseconds = cameraTime.elapsed().wallMilliseconds;
        cullGlTimes += gpuCulling->takeGlTimes();
    } else if (settings.culling == Culling::Occlusion) {
        const Stopwatch occlusionTime;
        occlusionStats = occlusion->frame(camera, cameraLodOrNone, *cameraDepth, occlusionDrawn);
        visibility->fromItems(occlusionDrawn, cameraLodOrNone, cameraList);
        occlusionMilliseconds = occlusionTime.elapsed().wallMilliseconds;
        cullGlTimes += occlusion->glTimes();
    } else if (prepass) {
        // The frustum's instances, asked once, for the depth pre-pass and the camera pass.
        occlusionDrawn.clear();
        visibility->hierarchy().query(cameraVolume, occlusionDrawn);
        if (cull)
            visibility->fromItems(occlusionDrawn, cameraLodOrNone, cameraList);
        else
            visibility->collect(cameraVolume, false, cameraLodOrNone, cameraList);
        occlusion->prepass(cameraLodOrNone, *cameraDepth, occlusionDrawn);
        cullGlTimes += occlusion->glTimes();
    } else {
        visibility->collect(cameraVolume, cull, cameraLodOrNone, cameraList);
    }
    if (prepass) {
        // Read when asked (Renderer::lastVisibleDepth). On llvmpipe the dispatch runs at
        // once, after the pre-pass's rasterisation it reads: GL time, not culling's own.
        const Stopwatch reduceTime;
        depthRange->reduce(*cameraDepth);
        cullGlTimes += reduceTime.elapsed();
    } else {
        depthRange->forget();
    }
    const std::vector<visibility::ReceiverMask>* masks = nullptr;
    if (masked && gpu) {
        const Stopwatch maskTime;
        receiverMasks->markOnGpu(*cameraDepth, camera, setup, lookupReachTexels(settings.filter, bias));
        receiverMaskMilliseconds = maskTime.elapsed().wallMilliseconds;
        cullGlTimes += receiverMasks->glTimes();
    } else if (masked) {
        const Stopwatch maskTime;
        masks = &receiverMasks->build(*cameraDepth, camera, setup, lookupReachTexels(settings.filter, bias));
        receiverMaskMilliseconds = maskTime.elapsed().wallMilliseconds;
        cullGlTimes += receiverMasks->glTimes();
    }
    std::vector<PassList*> lists;
    shadowLists.resize(virtualMaps ? 0 : setup.views.size());
    pageLists.clear();
    if (virtualMaps && settings.sun && !prepassForDepthRange) {
        // The pages the visible receivers request (not for visibleDepth(), which draws none); each draws the casters in
        // its own volume (extended towards the light), at levels of detail for its own texels.
        const core::FilterSettings filter = lookupFilterFor(setup, settings.filter);
        const int guard = guardTexelsFor(filter, bias);
        virtualPages->request(*cameraDepth, camera, setup, pageContentOf(*setup.clipmap, guard, bias, settings),
                              movedBoxes, lookupReachTexels(filter, bias), settings.virtualPageBudget);
        movedBoxes.clear();
        cullGlTimes += virtualPages->glTimes();
        const auto pages = virtualPages->pagesToRender();
        pageLists.resize(pages.size());
        const double slotTexels = setup.clipmap->pageTexels + 2.0 * guard;
        for (size_t i = 0; i < pages.size(); ++i) {
            // Levels by the page's own texels only, not by the camera: a page must hold the same
            // depths whenever it is drawn, or a page redrawn after a mover would differ from its
            // cached neighbours (and its texels already match the pixels it serves).
            const LodChoice lod{{pages[i].clipFromWorld, 0.5 * slotTexels, settings.lodTexelError}, std::nullopt, true};
            visibility->collect(visibility::clipVolume(pages[i].clipFromWorld, false), cull,
                                settings.lod ? &lod : nullptr, pageLists[i]);
            lists.push_back(&pageLists[i]);
        }
    }
    if (!virtualMaps && !movedBoxes.empty()) {
        virtualPages->forget(); // the pages under those movers were not redrawn
        movedBoxes.clear();
    }
    for (size_t i = 0; i < shadowLists.size(); ++i) {
        // No near plane: the pass clamps depth, so casters between the light and the near
        // plane are drawn at depth 0 and must not be culled. Levels by texels of this map.
        const core::Mat4& clipFromWorld = setup.views[i].clipFromWorld;
        const LodChoice lod{{clipFromWorld, 0.5 * setup.mapSize, settings.lodTexelError}, cameraProjection, true};
        if (gpu) {
            const GpuReceiverMask mask = GpuReceiverMask::of(*receiverMasks, setup, i);
            gpuCulling->cull(GpuCulling::kCameraPasses + i, visibility::clipVolume(clipFromWorld, false),
                             settings.lod ? &lod : nullptr, GpuCulling::Phase::All, shadowLists[i],
                             masked ? &mask : nullptr);
            continue;
        }
        visibility->collect(visibility::clipVolume(clipFromWorld, false), cull, settings.lod ? &lod : nullptr,
                            shadowLists[i], masks ? &(*masks)[i] : nullptr);
        lists.push_back(&shadowLists[i]);
    }
    if (gpu) cullGlTimes += gpuCulling->takeGlTimes();
    // Local lights: full meshes (levels are chosen for the sun's maps and the camera), culled
    // to each pass's volume; a point light's layered pass to the cube around its range.
    const LocalPass localPass = localMaps->resolve(settings.localPass);
    localLists.resize(LocalShadowMaps::listCount(localLights, localPass));
    size_t next = 0;
    for (size_t p = 0; p < localLights.points.size(); ++p) {
        const core::ShadowSetup& cube = localLights.pointSetups[p];
        if (localPass == LocalPass::PerFace) {
            for (const core::ShadowView& view : cube.views)
                visibility->collect(visibility::clipVolume(view.clipFromWorld, false), cull, nullptr,
                                    localLists[next++]);
        } else {
            PassList& list = localLists[next++];
            if (cube.views.empty())
                list = {};
            else
                visibility->collect(rangeBox(localLights.points[p].wsPosition, localLights.points[p].range), cull,
                                    nullptr, list);
        }
    }
    for (const core::ShadowSetup& spot : localLights.spotSetups) {
        PassList& list = localLists[next++];
        if (spot.views.empty())
            list = {};
        else
            visibility->collect(visibility::clipVolume(spot.views[0].clipFromWorld, false), cull, nullptr, list);
    }
    for (PassList& list : localLists) lists.push_back(&list);
    if (!gpu) lists.push_back(&cameraList);
    visibility->upload(lists);
    cullTimes = total.elapsed();
    listTimes = visibility->takeListTimes();
}

core::Status Renderer::Impl::prepare(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                     const core::ShadowSetup& setup, const RenderSettings& settings) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    // The set-up's map size is valid for core ([kMinMapSize, kMaxMapSize]); here it must
    // also fit this driver.
    // Within core's range but beyond this driver's: the machine's limit, not a wrong value.
    const bool virtualMaps = setup.clipmap.has_value();
    if (!virtualMaps && (setup.mapSize < core::kMinMapSize || setup.mapSize > maxSize))
        return core::environmentError(
            "map_size: must be in [" + std::to_string(core::kMinMapSize) + ", " + std::to_string(maxSize) +
                "] texels on this GL driver (GL_MAX_TEXTURE_SIZE), got " + std::to_string(setup.mapSize),
            "map_size");
    if (settings.width < 1 || settings.height < 1 || settings.width > maxSize || settings.height > maxSize)
        return core::environmentError("image_size: each side must be in [1, " + std::to_string(maxSize) +
                                          "] pixels on this GL driver (GL_MAX_TEXTURE_SIZE)",
                                      "image_size");
    if (auto s = cameraPrograms.prepare(virtualMaps); !s) return s;
    if (settings.culling == Culling::Gpu)
        if (auto s = gpuCulling->buildPrograms(); !s)
            return core::environmentError("culling: gpu is not available on this GL driver: " + s.errorInfo().message,
                                          "culling");
    bias = biasFor(setup, settings);
    if (auto s = core::validate(bias); !s) return s;
    if (auto s = core::validate(settings.filter); !s) return s;
    if (auto s = core::validateSunAngle(settings.sunAngleDegrees); !s) return s;
    if (auto s = validate(settings.blur); !s) return s;
    if (auto s = validate(settings.localBias); !s) return s;
    const int maps = static_cast<int>(setup.views.size());
    if (maps < 1 || maps > kMaxCascades)
        return core::makeError("renderer: set-ups need 1 to " + std::to_string(kMaxCascades) + " shadow maps, got " +
                               std::to_string(maps));
    const bool linearFilter = settings.filter.kind == core::ShadowFilter::Pcf2;
    if (virtualMaps && settings.filter.kind == core::ShadowFilter::Msm)
        return core::fieldError("filter", "msm needs fixed maps: virtual pages hold depth only (use pcss)");
    if (virtualMaps) {
        if (auto s = validateVirtualSettings(settings); !s) return s;
        if (auto s = virtualPages->configure(settings.virtualPoolPages, setup.clipmap->pageTexels,
                                             guardTexelsFor(lookupFilterFor(setup, settings.filter), bias));
            !s)
            return s;
        virtualPages->setLinearFilter(linearFilter);
        shadow.reset(); // no fixed maps: their memory is the pool's
    } else if (!shadow || shadow->size != setup.mapSize || shadow->layers != maps) {
        shadow.reset(); // the old maps go before the new ones are allocated
        auto target = ShadowTarget::create(setup.mapSize, maps);
        if (!target) return target.errorInfo();
        shadow.emplace(std::move(target).value());
    }
    if (shadow) {
        // Hardware 2x2 PCF is the sampler's linear filter; every other filter takes its own taps.
        const GLint filter = linearFilter ? GL_LINEAR : GL_NEAREST;
        glTextureParameteri(shadow->depth.id(), GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(shadow->depth.id(), GL_TEXTURE_MAG_FILTER, filter);
    }
    collectVisible(camera, light, setup, settings);
    return core::Ok{};
}

core::Result<PassStats> Renderer::Impl::localPass(const RenderSettings& settings) {
    localTimer.begin();
    auto stats = localMaps->draw(*scene, localLights, localLists, settings.localPass,
                                 settings.filter.kind == core::ShadowFilter::Pcf2);
    localTimer.end();
    return stats;
}

PassStats Renderer::Impl::shadowPass(const core::ShadowSetup& setup, const RenderSettings& settings) {
    lastVirtual.reset();
    momentsStatus = core::Ok{};
    // Night: no sun, no sun maps (the camera passes do not read them).
    if (!settings.sun) {
        shadowTimer.begin();
        shadowTimer.end();
        return {};
    }
    if (setup.clipmap) {
        const PassStats stats = pagePass();
        lastVirtual = virtualPages->stats();
        lastVirtual->triangles = stats.triangles;
        return stats;
    }
    // One array layer per shadow view.
    glBindFramebuffer(GL_FRAMEBUFFER, shadow->framebuffer.id());
    glViewport(0, 0, shadow->size, shadow->size);
    beginDepthPass(setup.depthClamp);
    const auto slope = static_cast<float>(bias.slope), constant = static_cast<float>(bias.constant);
    const bool linear = setup.depthLayout == core::DepthLayout::Linear;
    DrawStats draws;
    shadowTimer.begin();
    for (size_t layer = 0; layer < setup.views.size(); ++layer) {
        const core::ShadowView& view = setup.views[layer];
        // Linear layout: the same slope / constant bias, applied in depth.frag. One constant
        // unit is 2^-24 of the depth range, the resolvable step of a 24-bit buffer.
        const DepthPassUniforms uniforms{.clipFromWorld = toFloat(view.clipFromWorld),
                                         .linearDepthFromWorld = glm::vec4(view.linearDepthFromWorld),
                                         .linearLayout = linear ? 1 : 0,
                                         .slopeBias = slope,
                                         .constantBias = constant * 0x1p-24f};
        glNamedBufferSubData(depthUniforms.id(), 0, sizeof uniforms, &uniforms);
        shadow->attachLayer(static_cast<int>(layer));
        const float clearDepth = 1.0f;
        glClearNamedFramebufferfv(shadow->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
        draws += scene->draw(shadowLists[layer], depthPass());
    }
    // MSM: the maps' moments, blurred, inside the pass's time (a real frame pays them with it).
    if (settings.filter.kind == core::ShadowFilter::Msm)
        momentsStatus =
            moments->update(shadow->depth, rawDepthSampler.id(), shadow->size, shadow->layers, settings.filter.taps);
    shadowTimer.end();
    endDepthPass();
    // Time read after the frame, not to stall here.
    return {.instances = draws.instances, .triangles = draws.triangles, .drawCalls = draws.drawCalls};
}

PassStats Renderer::Impl::pagePass() {
    // As the fixed maps' pass, one viewport per page (VirtualPages::drawPages).
    glBindFramebuffer(GL_FRAMEBUFFER, virtualPages->framebuffer().id());
    beginDepthPass(true);
    shadowTimer.begin();
    const DrawStats draws = virtualPages->drawPages(*scene, depthPass(), pageLists, depthUniforms);
    shadowTimer.end();
    endDepthPass();
    virtualPages->rendered();
    return {.instances = draws.instances, .triangles = draws.triangles, .drawCalls = draws.drawCalls};
}

void Renderer::Impl::beginDepthPass(bool depthClamp) const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Caster culling: front-face culling stores the casters' back sides (Scherzer 2005 §4.2).
    if (bias.cull == core::CasterCull::None) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(bias.cull == core::CasterCull::Back ? GL_BACK : GL_FRONT);
    }
    if (depthClamp) glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(static_cast<float>(bias.slope), static_cast<float>(bias.constant));
    glUseProgram(depthPrograms.plain.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kDepthPassBinding, depthUniforms.id());
}

void Renderer::Impl::endDepthPass() {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);
}

void Renderer::Impl::uploadFrame(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                 const core::ShadowSetup& setup, const RenderSettings& settings, bool useMask) {
    FrameUniforms frame{};
    frame.clipFromWorld = toFloat(camera.clipFromWorld());
    frame.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    frame.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    frame.wsTowardsLight = glm::vec4(glm::vec3(light.wsTowardsLight()), 0.0f);
    const float day = daylight(light, settings);
    frame.sunRadiance = day * glm::vec4(1.05f, 1.0f, 0.9f, 0.0f);
    frame.ambientRadiance = glm::mix(glm::vec4(0.02f, 0.025f, 0.04f, 0.0f), glm::vec4(0.28f, 0.32f, 0.40f, 0.0f), day);
    frame.fogColorDensity = glm::vec4(glm::pow(glm::mix(kNightSky, kSky, day), glm::vec3(2.2f)), settings.fogDensity);
    frame.mapTexels = static_cast<float>(setup.mapSize);
    frame.mapCount = static_cast<int32_t>(setup.views.size());
    frame.linearLayout = setup.depthLayout == core::DepthLayout::Linear ? 1 : 0;
    frame.cascadeColors = settings.cascadeColors ? 1 : 0;
    const core::FilterSettings f = lookupFilterFor(setup, settings.filter);
    frame.filterKind = static_cast<int32_t>(f.kind); // SK_FILTER_* in the shaders
    frame.filterTaps = f.taps;
    frame.poissonRadiusTexels = f.radiusTexels;
    frame.lightTanHalfAngle = static_cast<float>(core::tanAngularRadius(settings.sunAngleDegrees));
    frame.receiverPlane = bias.receiverPlane ? 1 : 0;
    frame.normalOffsetTexels = static_cast<float>(bias.normalOffset);
    frame.readBlurredMask = useMask ? 1 : 0;
    frame.aliasingOverlay = settings.aliasingOverlay ? 1 : 0;
    for (size_t i = 0; i < setup.views.size(); ++i) {
        const core::ShadowView& view = setup.views[i];
        frame.shadowTextureFromWorld[i] = toFloat(core::toEngineView(view, setup, {}).textureFromWorld);
        frame.shadowLinearDepthFromWorld[i] = glm::vec4(view.linearDepthFromWorld);
        const core::Vec2 range = view.split.value_or(core::Vec2(camera.zNear, camera.zFar));
        frame.cascadeRange[i] = glm::vec4(static_cast<float>(range.x), static_cast<float>(range.y), 0.0f, 0.0f);
    }
    glNamedBufferSubData(frameUniforms.id(), 0, sizeof frame, &frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, frameUniforms.id());
    if (setup.clipmap)
        virtualPages->bind(setup, settings.virtualBlendBand);
    else {
        virtualPages->bindDisabled();
        if (shadow) {
            glBindTextureUnit(kShadowMapUnit, shadow->depth.id());
            glBindTextureUnit(kShadowDepthUnit, shadow->depth.id());
        }
    }
    for (const unsigned unit : {kShadowDepthUnit, kSpotDepthUnit, kPointDepthUnit})
        glBindSampler(unit, rawDepthSampler.id()); // the maps once more, their stored depths
    if (settings.filter.kind == core::ShadowFilter::Msm) moments->bind();
    localMaps->bind(localLights, settings.localBias, evalLight, settings.sun);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
}

core::Status Renderer::Impl::evalPass(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                      const core::ShadowSetup& setup, const RenderSettings& settings) {
    if (!eval || eval->width != settings.width || eval->height != settings.height) {
        eval.emplace(settings.width, settings.height);
        if (auto s = checkComplete(eval->framebuffer, "eval pass"); !s) return s;
    }
    uploadFrame(camera, light, setup, settings, false);
    glBindFramebuffer(GL_FRAMEBUFFER, eval->framebuffer.id());
    glViewport(0, 0, eval->width, eval->height);
    eval->clear();
    scene->draw(cameraList, cameraPrograms.eval(setup.clipmap.has_value()), true);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return core::Ok{};
}

int Renderer::Impl::blurPass(const RenderSettings& settings) {
    if (!mask || mask->width != settings.width || mask->height != settings.height)
        mask.emplace(settings.width, settings.height);
    const BlurUniforms uniforms{.radiusPixels = settings.blur.radiusPixels,
                                .depthFalloff = settings.blur.depthFalloff,
                                .depthThreshold = settings.blur.depthThreshold};
    glNamedBufferSubData(blurUniforms.id(), 0, sizeof uniforms, &uniforms);
    glBindBufferBase(GL_UNIFORM_BUFFER, kBlurBinding, blurUniforms.id());
    glUseProgram(blurProgram.id());
    glBindVertexArray(emptyVertexArray.id());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, mask->width, mask->height);
    glBindTextureUnit(kBlurDepthUnit, eval->viewDepth.id());
    int target = 0;
    for (int i = 0; i < settings.blur.iterations; ++i) {
        glBindTextureUnit(kBlurMaskUnit, i == 0 ? eval->shadowTerm.id() : mask->images[1 - target].id());
        glBindFramebuffer(GL_FRAMEBUFFER, mask->framebuffers[target].id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        target = 1 - target;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    return 1 - target; // the last one written
}

core::Result<FrameStats> Renderer::render(const core::PerspectiveCamera& wsCamera, const core::DirectionalLight& light,
                                          const core::ShadowSetup& wsSetup, const RenderSettings& settings) {
    Impl& r = *m_impl;
    const SceneFrame frame = inScene(r.wsOrigin, wsCamera, wsSetup);
    const core::PerspectiveCamera& camera = frame.camera;
    const core::ShadowSetup& setup = frame.setup();
    if (auto s = r.prepare(camera, light, setup, settings); !s) return s.errorInfo();
    if (!r.color || r.color->width != settings.width || r.color->height != settings.height) {
        r.color.emplace(settings.width, settings.height);
        if (auto s = checkComplete(r.color->framebuffer, "main pass"); !s) return s.errorInfo();
    }
    FrameStats stats;
    stats.shadow = r.lastShadow = r.shadowPass(setup, settings);
    if (!r.momentsStatus) return r.momentsStatus.errorInfo();
    auto local = r.localPass(settings);
    if (!local) return local.errorInfo();
    stats.local = *local;
    for (const core::ShadowSetup& s : r.localLights.pointSetups)
        stats.localMaps += static_cast<int>(s.views.size()), stats.skippedFaces += s.skippedFaces;
    for (const core::ShadowSetup& s : r.localLights.spotSetups) stats.localMaps += static_cast<int>(s.views.size());

    // With the eye-space blur, the shadow term comes from the blurred screen-space mask.
    const bool blurred = settings.blur.iterations > 0;
    int maskIndex = 0;
    const core::ShadowSetup& shown = r.lookupSetup(setup, settings);
    if (blurred) {
        if (auto s = r.evalPass(camera, light, shown, settings); !s) return s.errorInfo();
        maskIndex = r.blurPass(settings);
    }
    r.uploadFrame(camera, light, shown, settings, blurred);
    if (blurred) glBindTextureUnit(kShadowMaskUnit, r.mask->images[maskIndex].id());
    glBindFramebuffer(GL_FRAMEBUFFER, r.color->framebuffer.id());
    glViewport(0, 0, r.color->width, r.color->height);
    const float day = daylight(light, settings);
    const glm::vec3 sky = glm::mix(kNightSky, kSky, day);
    const float clearColor[4] = {sky.r, sky.g, sky.b, 1.0f};
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(r.color->framebuffer.id(), GL_COLOR, 0, clearColor);
    glClearNamedFramebufferfv(r.color->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
    r.mainTimer.begin();
    DrawStats mainDraws = r.scene->draw(r.cameraList, r.cameraPrograms.main(setup.clipmap.has_value()), true);
    r.mainTimer.end();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (settings.culling == Culling::Gpu) {
        // What the GPU's lists drew, read back now that the frame is submitted.
        mainDraws = r.gpuCulling->submitted(r.cameraList);
        stats.shadow = r.lastShadow = r.gpuShadowDraws(r.lastShadow);
    }

    stats.shadow.gpuMilliseconds = r.shadowTimer.milliseconds();
    stats.local.gpuMilliseconds = r.localTimer.milliseconds();
    stats.main = {r.mainTimer.milliseconds(), mainDraws.instances, mainDraws.triangles, mainDraws.drawCalls};
    stats.cullMilliseconds = r.cullTimes.wallMilliseconds;
    stats.cullGlMilliseconds = r.cullGlTimes.wallMilliseconds;
    stats.listCpuMilliseconds = r.listTimes.threadMilliseconds;
    stats.cullOwnCpuMilliseconds =
        r.cullTimes.threadMilliseconds - r.cullGlTimes.threadMilliseconds - stats.listCpuMilliseconds;
    stats.occlusion = r.occlusionStats;
    stats.occlusionMilliseconds = r.occlusionMilliseconds;
    stats.receiverMaskMilliseconds = r.receiverMaskMilliseconds;
    stats.virtualPages = r.lastVirtual;
    return stats;
}

core::Result<core::RasterBuffers> Renderer::renderEvalBuffers(const core::PerspectiveCamera& wsCamera,
                                                              const core::DirectionalLight& light,
                                                              const core::ShadowSetup& wsSetup,
                                                              const RenderSettings& settings, int localLight) {
    Impl& r = *m_impl;
    const SceneFrame frame = inScene(r.wsOrigin, wsCamera, wsSetup);
    const core::PerspectiveCamera& camera = frame.camera;
    const core::ShadowSetup& setup = frame.setup();
    if (localLight < -1 || localLight >= static_cast<int>(r.localLights.size()))
        return core::makeError("renderer: local light " + std::to_string(localLight) + " does not exist (" +
                               std::to_string(r.localLights.size()) + " set)");
    if (auto s = r.prepare(camera, light, setup, settings); !s) return s.errorInfo();
    r.lastShadow = r.shadowPass(setup, settings);
    if (!r.momentsStatus) return r.momentsStatus.errorInfo();
    if (settings.culling == Culling::Gpu) r.lastShadow = r.gpuShadowDraws(r.lastShadow);
    if (auto s = r.localPass(settings); !s) return s.errorInfo();
    r.evalLight = localLight;
    const core::Status evaluated = r.evalPass(camera, light, r.lookupSetup(setup, settings), settings);
    r.evalLight = -1;
    if (!evaluated) return evaluated.errorInfo();
    core::RasterBuffers buffers = r.eval->read();
    if (localLight >= 0) buffers.mapSize = r.localLights.mapSize;
    if (localLight >= 0) return buffers; // the eye-space blur is the sun's
    if (settings.blur.iterations > 0) buffers.shadowTerm = r.mask->read(r.blurPass(settings));
    buffers.mapSize = setup.mapSize;
    return buffers;
}

core::Result<std::optional<core::Vec2>> Renderer::visibleDepth(const core::PerspectiveCamera& wsCamera,
                                                               const core::DirectionalLight& light,
                                                               const core::ShadowSetup& wsSetup,
                                                               const RenderSettings& settings) {
    Impl& r = *m_impl;
    const SceneFrame frame = inScene(r.wsOrigin, wsCamera, wsSetup);
    const core::PerspectiveCamera& camera = frame.camera;
    const core::ShadowSetup& setup = frame.setup();
    // The culling's own pre-pass, or one made for the purpose; no shadow pass.
    r.prepassForDepthRange = true;
    const core::Status prepared = r.prepare(camera, light, setup, settings);
    r.prepassForDepthRange = false;
    if (!prepared) return prepared.errorInfo();
    return r.depthRange->read();
}

std::optional<core::Vec2> Renderer::lastVisibleDepth() { return m_impl->depthRange->read(); }

std::optional<VirtualPageStats> Renderer::lastVirtualPages() const { return m_impl->lastVirtual; }

PassStats Renderer::lastShadowPass() const { return m_impl->lastShadow; }

core::Status Renderer::moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved) {
    Impl& r = *m_impl;
    if (scene.instanceCount() != r.visibility->hierarchy().size())
        return core::makeError("renderer: moveInstances() needs the scene it was created with (" +
                               std::to_string(r.visibility->hierarchy().size()) + " instances, got " +
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
        const core::Aabb box =
            core::transformBounds(core::Mat4(b.worldFromObject[ref.instance]), scene.meshes[b.mesh].osBounds);
        // Virtual maps redraw the pages under where it was and where it is.
        r.movedBoxes.push_back(r.visibility->hierarchy().itemBounds(global));
        r.movedBoxes.push_back(box);
        r.visibility->move(global, box);
        if (r.gpuCulling) r.gpuCulling->move(global, box);
    }
    if (r.visibility->rebuildIfDegraded() && r.occlusion) r.occlusion->hierarchyRebuilt();
    for (size_t batch = 0; batch < scene.batches.size(); ++batch)
        if (batchMoved[batch]) r.scene->updateBatch(scene, batch);
    return core::Ok{};
}

core::Status Renderer::setLocalLights(core::LocalLighting lights) {
    if (lights.points.size() > static_cast<size_t>(kMaxLocalLights) ||
        lights.spots.size() > static_cast<size_t>(kMaxLocalLights))
        return core::makeError("renderer: at most " + std::to_string(kMaxLocalLights) + " point and " +
                               std::to_string(kMaxLocalLights) + " spot lights, got " +
                               std::to_string(lights.points.size()) + " and " + std::to_string(lights.spots.size()));
    if (lights.pointSetups.size() != lights.points.size() || lights.spotSetups.size() != lights.spots.size())
        return core::makeError("renderer: every local light needs its set-up (core::computeLocalLighting)");
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &maxSize);
    if (!lights.empty() && (lights.mapSize < core::kMinMapSize || lights.mapSize > maxSize))
        return core::environmentError(
            "local_map_size: must be in [" + std::to_string(core::kMinMapSize) + ", " + std::to_string(maxSize) +
                "] texels on this GL driver (GL_MAX_CUBE_MAP_TEXTURE_SIZE), got " + std::to_string(lights.mapSize),
            "local_map_size");
    m_impl->localLights = m_impl->wsOrigin == core::Vec3(0.0) ? lights : core::rebased(lights, m_impl->wsOrigin);
    m_impl->wsLocalLights = std::move(lights);
    return core::Ok{};
}

const core::LocalLighting& Renderer::localLights() const { return m_impl->wsLocalLights; }

scene::Image Renderer::readLocalShadowMaps() const { return m_impl->localMaps->readAsGreys(m_impl->localLights); }

core::Aabb Renderer::wsSceneBounds() const {
    const core::Aabb& local = m_impl->visibility->bounds();
    return local.isEmpty() ? local : core::Aabb::fromMinMax(local.min + m_impl->wsOrigin, local.max + m_impl->wsOrigin);
}

void Renderer::drawLines(const core::PerspectiveCamera& camera, std::span<const LineSegment> lines) {
    Impl& r = *m_impl;
    if (!r.color) return;
    glBindFramebuffer(GL_FRAMEBUFFER, r.color->framebuffer.id());
    glViewport(0, 0, r.color->width, r.color->height);
    core::PerspectiveCamera local = camera; // in the scene's coordinates, as inScene (scene_frame.h)
    local.wsEye -= r.wsOrigin;
    std::vector<LineSegment> segments(lines.begin(), lines.end());
    for (LineSegment& line : segments) line.wsFrom -= r.wsOrigin, line.wsTo -= r.wsOrigin;
    r.lines->draw(local.clipFromWorld(), segments);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::present(int width, int height) const {
    const auto& color = m_impl->color;
    if (!color) return;
    glBlitNamedFramebuffer(color->framebuffer.id(), 0, 0, 0, color->width, color->height, 0, 0, width, height,
                           GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

scene::Image Renderer::readColor() const { return m_impl->color ? m_impl->color->read() : scene::Image{}; }

scene::Image Renderer::readVirtualPageTable() const {
    return m_impl->shadow ? scene::Image{} : m_impl->virtualPages->pageTableImage();
}

scene::Image Renderer::readShadowMap() const {
    if (m_impl->shadow) return m_impl->shadow->readAsGreys();
    return m_impl->virtualPages->readAtlas(); // virtual maps: the page pool
}

} // namespace shadowkit::gl
