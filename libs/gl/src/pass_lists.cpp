#include "pass_lists.h"

#include "local_shadows.h"
#include "lookup_reach.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shadowkit::gl {
namespace {

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

bool virtualMaps(const core::ShadowSetup& setup) { return setup.clipmap.has_value(); }

// Virtual maps cull per page, finer than any receiver mask; their pages come from the pre-pass.
bool masked(const core::ShadowSetup& setup, const RenderSettings& settings) {
    return settings.culling != Culling::Off && settings.receiverMask && !virtualMaps(setup);
}

// The camera's levels by pixels. A simplified receiver lies up to its error off the true surface
// and would self-shadow against the map (measured without compensation: +0.05 to +0.12 points of
// false shadow on an aerial view), so its lookup moves that far towards the light (receiverLookup
// in shadow_lookup.glsl).
// RenderSettings::lodCamera, where a measurement sets it, chooses in the frame camera's place.
LodProjection cameraProjectionOf(const core::PerspectiveCamera& camera, const RenderSettings& settings) {
    const core::PerspectiveCamera& chooser = settings.lodCamera ? *settings.lodCamera : camera;
    return {chooser.clipFromWorld(), 0.5 * std::max(settings.width, settings.height), settings.lodPixelError};
}

// A pass's choice of levels with RenderSettings' foliage scale and cross-fade. The crossing is
// centred on where the coarser level would be switched to: with x the allowed error over the
// coarser level's (the foliage scale's bound), its share is 0 at x = 1 − B/2, ½ at x = 1 and 1 at
// x = 1 + B/2 (B = lodFade), so that on the mean a tree is drawn as fine as when switching.
// LodChoice's band ends at its bound, where the level is taken outright: that bound is x = 1 + B/2,
// a foliage scale divided by 1 + B/2, and the band is B of the scale's bound, B / (1 + B/2) of its own.
LodChoice lodChoiceOf(const LodProjection& pass, std::optional<LodProjection> camera, bool shadow,
                      const RenderSettings& settings) {
    const double outwards = 1.0 + 0.5 * settings.lodFade;
    return {pass, camera, shadow, settings.lodFoliageScale / outwards, settings.lodFade / outwards};
}

} // namespace

void CullingCosts::fill(FrameStats& stats) const {
    stats.cullMilliseconds = total.wallMilliseconds;
    stats.cullGlMilliseconds = inGl.wallMilliseconds;
    stats.listCpuMilliseconds = lists.threadMilliseconds;
    stats.cullOwnCpuMilliseconds = total.threadMilliseconds - inGl.threadMilliseconds - lists.threadMilliseconds;
    stats.occlusion = occlusion;
    stats.occlusionMilliseconds = occlusionMilliseconds;
    stats.receiverMaskMilliseconds = receiverMaskMilliseconds;
}

core::Result<std::unique_ptr<PassLists>>
PassLists::create(const scene::Scene& scene, std::span<const scene::MeshLods> lods, const GpuScene& gpuScene) {
    auto lists = std::unique_ptr<PassLists>(new PassLists);
    lists->m_visibility.emplace(scene, lods);
    const std::vector<core::Aabb> instances = scene.instanceBounds(); // batch after batch
    size_t next = 0;
    for (const scene::MeshBatch& batch : scene.batches) {
        core::Aabb box;
        for (size_t k = 0; k < batch.worldFromObject.size(); ++k) box.extend(instances[next++]);
        lists->m_batchBounds.push_back(box);
    }
    for (size_t b = 0; b < scene.batches.size(); ++b) lists->m_alphaTested.push_back(gpuScene.alphaTested(b));
    // The large meshes a virtual page draws by clusters: the CPU's to cull per page on either path.
    const std::span<const uint32_t> batchFirst = lists->m_visibility->batchFirst();
    for (size_t b = 0; b < scene.batches.size(); ++b)
        if (gpuScene.drawsByClusters(b))
            for (uint32_t i = batchFirst[b]; i < batchFirst[b + 1]; ++i) lists->m_clusteredInstances.push_back(i);
    auto occlusion = OcclusionCuller::create(*lists->m_visibility, gpuScene);
    if (!occlusion) return occlusion.errorInfo();
    lists->m_occlusion = std::move(occlusion).value();
    lists->m_gpuCulling = GpuCulling::create(scene, lods, gpuScene);
    auto masks = ReceiverMasks::create();
    if (!masks) return masks.errorInfo();
    lists->m_receiverMasks = std::move(masks).value();
    auto depthRange = DepthRangeReduction::create();
    if (!depthRange) return depthRange.errorInfo();
    lists->m_depthRange = std::move(depthRange).value();
    return lists;
}

bool PassLists::needsPrepass(const core::ShadowSetup& setup, const RenderSettings& settings, PassPurpose purpose) {
    const bool cameraCulling = settings.culling == Culling::Occlusion || settings.culling == Culling::Gpu;
    switch (purpose) {
    case PassPurpose::Frame:
        return cameraCulling || masked(setup, settings) || virtualMaps(setup);
    case PassPurpose::DepthRange:
        return true;
    case PassPurpose::Surfaces:
        return cameraCulling;
    }
    return true;
}

void PassLists::plan(const PassPlanInputs& in, VirtualPages& pages) {
    const Stopwatch total;
    m_visibility->takeListTimes();
    m_costs = {};
    const bool prepass = needsPrepass(in.setup, in.settings, in.purpose);
    const CameraKey camera{in.camera.clipFromWorld(),   in.settings.width,  in.settings.height,
                           in.settings.culling,         in.settings.lod,    in.settings.lodPixelError,
                           in.settings.lodFoliageScale, in.settings.lodFade};
    if (prepass && in.purpose == PassPurpose::Frame && m_keptCamera == camera) {
        // The depth-range pre-pass just drawn for this very camera: its list, depth and costs.
        m_costs.occlusion = m_keptCameraCosts.occlusion;
        m_costs.occlusionMilliseconds = m_keptCameraCosts.occlusionMilliseconds;
    } else {
        planCamera(in, prepass);
        m_prepassesDrawn += prepass;
    }
    m_keptCamera.reset();
    if (in.purpose == PassPurpose::DepthRange && in.settings.culling != Culling::Gpu) {
        m_keptCamera = camera;
        m_keptCameraCosts = m_costs;
    }
    planMasks(in);
    // The pre-pass's depth range, for whoever reads it (lastVisibleDepth).
    m_prepassUnreduced = false;
    m_prepassThisFrame = prepass;
    if (!prepass) {
        m_depthRange->forget();
    } else if (m_depthRangeWanted) {
        // On llvmpipe the dispatch runs at once, after the pre-pass's rasterisation it reads: GL
        // time, not culling's own.
        const Stopwatch reduceTime;
        m_depthRange->reduce(*m_cameraDepth);
        m_costs.inGl += reduceTime.elapsed();
    } else {
        m_prepassUnreduced = true;
    }

    std::vector<PassList*> lists;
    m_pages.clear();
    m_sun.clear();
    m_sunClustered.clear();
    m_local.clear();
    m_localClustered.clear();
    const bool shadows = in.purpose == PassPurpose::Frame;
    if (shadows && virtualMaps(in.setup) && in.settings.sun) planPages(in, pages, lists);
    if (!virtualMaps(in.setup) && !m_movedBoxes.empty()) {
        pages.forget(); // the pages under those movers were not redrawn
        m_movedBoxes.clear();
    }
    if (shadows) {
        planSunMaps(in, lists);
        planLocal(in);
    }
    if (in.settings.culling != Culling::Gpu) {
        for (PassList& list : m_local) lists.push_back(&list);
        lists.push_back(&m_camera);
    }
    for (PassList& list : m_localClustered) lists.push_back(&list);
    m_visibility->upload(lists);
    m_costs.total = total.elapsed();
    m_costs.lists = m_visibility->takeListTimes();
}

void PassLists::planCamera(const PassPlanInputs& in, bool prepass) {
    const RenderSettings& settings = in.settings;
    const bool cull = settings.culling != Culling::Off;
    const LodChoice cameraLod = lodChoiceOf(cameraProjectionOf(in.camera, settings), std::nullopt, false, settings);
    const LodChoice* lod = settings.lod ? &cameraLod : nullptr;
    const std::vector<visibility::HalfSpace> cameraVolume = visibility::clipVolume(in.camera.clipFromWorld());
    m_cameraLeavesClustered = false;
    if (prepass &&
        (!m_cameraDepth || m_cameraDepth->width != settings.width || m_cameraDepth->height != settings.height))
        m_cameraDepth.emplace(settings.width, settings.height);
    if (settings.culling == Culling::Gpu) {
        const bool shadows = in.purpose == PassPurpose::Frame;
        // Virtual pages after the local lights: as many as the room kept for them (planPages).
        const bool pages = shadows && virtualMaps(in.setup) && settings.sun;
        m_gpuCulling->beginFrame(shadows ? firstPagePass(in) + (pages ? m_pageRoom : 0) : firstLocalPass(in.setup));
        const Stopwatch cameraTime;
        // The large clustered meshes (the terrain) left to the CPU, as the shadow passes leave
        // them: listed where they meet the frustum, in a buffer of their own (the pre-pass draws
        // them before the frame's lists are uploaded), drawn by their clusters in view.
        collectClustered(cameraVolume, lod, m_cameraClustered);
        uploadCameraClustered();
        m_cameraLeavesClustered = true;
        m_gpuCulling->camera(in.camera, lod, *m_cameraDepth, m_camera, &m_cameraClustered);
        m_costs.occlusionMilliseconds = cameraTime.elapsed().wallMilliseconds;
        m_costs.inGl += m_gpuCulling->takeGlTimes();
    } else if (settings.culling == Culling::Occlusion) {
        const Stopwatch occlusionTime;
        m_costs.occlusion = m_occlusion->frame(in.camera, lod, *m_cameraDepth, m_prepassDrawn);
        m_visibility->fromItems(m_prepassDrawn, lod, m_camera);
        m_costs.occlusionMilliseconds = occlusionTime.elapsed().wallMilliseconds;
        m_costs.inGl += m_occlusion->glTimes();
    } else if (prepass) {
        // The frustum's instances, asked once, for the depth pre-pass and the camera pass.
        m_prepassDrawn.clear();
        m_visibility->hierarchy().query(cameraVolume, m_prepassDrawn);
        if (cull)
            m_visibility->fromItems(m_prepassDrawn, lod, m_camera);
        else
            m_visibility->collect(cameraVolume, false, lod, m_camera);
        m_occlusion->prepass(cull ? cameraVolume : std::span<const visibility::HalfSpace>{}, lod, *m_cameraDepth,
                             m_prepassDrawn);
        m_costs.inGl += m_occlusion->glTimes();
    } else {
        m_visibility->collect(cameraVolume, cull, lod, m_camera);
    }
}

void PassLists::planMasks(const PassPlanInputs& in) {
    // On the CPU, or left on the GPU for its culling passes to test against.
    const RenderSettings& settings = in.settings;
    m_masks = nullptr;
    if (!masked(in.setup, settings) || in.purpose != PassPurpose::Frame) return;
    const Stopwatch maskTime;
    const double reach = lookupReachTexels(settings.filter, in.bias);
    if (settings.culling == Culling::Gpu)
        m_receiverMasks->markOnGpu(*m_cameraDepth, in.camera, in.setup, reach);
    else
        m_masks = &m_receiverMasks->build(*m_cameraDepth, in.camera, in.setup, reach);
    m_costs.receiverMaskMilliseconds = maskTime.elapsed().wallMilliseconds;
    m_costs.inGl += m_receiverMasks->glTimes();
}

void PassLists::planPages(const PassPlanInputs& in, VirtualPages& pages, std::vector<PassList*>& lists) {
    const RenderSettings& settings = in.settings;
    const core::ShadowSetup& setup = in.setup;
    const core::FilterSettings filter = lookupFilterFor(setup, settings.filter);
    const int guard = guardTexelsFor(filter, in.bias);
    pages.request(*m_cameraDepth, in.camera, setup, pageContentOf(*setup.clipmap, guard, in.bias, settings),
                  m_movedBoxes, lookupReachTexels(filter, in.bias), settings.virtualPageBudget,
                  settings.virtualRequestsLate);
    m_movedBoxes.clear();
    m_costs.inGl += pages.glTimes();
    const auto toRender = pages.pagesToRender();
    m_pages.resize(toRender.size());
    m_pageCulled.assign(toRender.size(), {});
    // GPU-driven: the first pages as many as the frame made room for (planCamera), culled on the
    // GPU but for their clustered meshes; the rest, and every page on the other paths, on the CPU.
    // The room grows to the most pages a frame has drawn, within the lists' memory budget.
    const bool gpu = settings.culling == Culling::Gpu;
    const size_t onGpu = gpu ? std::min(toRender.size(), m_pageRoom) : 0;
    if (gpu) {
        const size_t budget = m_gpuCulling->passesWithinBudget(), first = firstPagePass(in);
        m_pageRoom = std::max(m_pageRoom, std::min(toRender.size(), budget > first ? budget - first : 0));
    }
    const double slotTexels = setup.clipmap->pageTexels + 2.0 * guard;
    const std::vector<uint32_t> order = nearestFirst(in.wsTowardsLight);
    std::vector<GpuCulling::PassVolume> onGpuPasses;
    std::vector<LodChoice> onGpuLods;
    for (size_t i = 0; i < toRender.size(); ++i) {
        m_pages[i].batchOrder = order;
        // Levels by the page's own texels only, not by the camera: a page must hold the same
        // depths whenever it is drawn, or a page redrawn after a mover would differ from its
        // cached neighbours (and its texels already match the pixels it serves).
        const LodChoice lod = lodChoiceOf({toRender[i].clipFromWorld, 0.5 * slotTexels, settings.lodTexelError},
                                          std::nullopt, true, settings);
        std::vector<visibility::HalfSpace> volume = visibility::clipVolume(toRender[i].clipFromWorld, false);
        if (i < onGpu) {
            collectClustered(volume, settings.lod ? &lod : nullptr, m_pages[i]);
            m_pageCulled[i].batchOrder = order;
            onGpuPasses.push_back({std::move(volume), lod.pass});
            onGpuLods.push_back(lod);
        } else {
            m_visibility->collect(volume, settings.culling != Culling::Off, settings.lod ? &lod : nullptr, m_pages[i]);
        }
        lists.push_back(&m_pages[i]);
    }
    if (onGpu > 0) {
        // Every page's casters in one set of dispatches: the choice of levels but for each page's
        // own projection is the same for all (lodChoiceOf's shadow pass without a camera bound).
        const LodChoice shared = lodChoiceOf({}, std::nullopt, true, settings);
        m_gpuCulling->cullPasses(firstPagePass(in), onGpuPasses, settings.lod ? &shared : nullptr,
                                 /*leaveClustered=*/true, std::span(m_pageCulled).first(onGpu));
        // Of each page's ranges, those of the levels its instances can take: the others would be
        // draws of no instance (a page's levels follow the instances' scales alone).
        for (size_t i = 0; i < onGpu; ++i)
            m_visibility->emptyLevelsNoneTakes(m_pageCulled[i], settings.lod ? &onGpuLods[i] : nullptr);
        m_costs.inGl += m_gpuCulling->takeGlTimes();
    }
}

LevelsDrawn PassLists::levelsDrawn() const {
    const std::span<const uint32_t> batchFirst = m_visibility->batchFirst();
    LevelsDrawn out;
    out.camera.assign(batchFirst.back(), kLevelNotDrawn);
    out.sun.assign(batchFirst.back(), kLevelNotDrawn);
    auto mark = [&](const PassList& list, std::vector<uint8_t>& levels) {
        const PassList drawn = this->drawn(list);
        for (size_t slot = 0; slot < drawn.count.size(); ++slot) {
            const size_t batch = slot / kMaxLodLevels;
            const auto level = static_cast<uint8_t>(slot % kMaxLodLevels);
            for (uint32_t k = 0; k < drawn.count[slot]; ++k) {
                uint8_t& at = levels[batchFirst[batch] + instanceOfEntry(drawn.indices[drawn.first[slot] + k])];
                at = std::min(at, level);
            }
        }
    };
    mark(m_camera, out.camera);
    if (m_cameraLeavesClustered) mark(m_cameraClustered, out.camera);
    for (const PassList& list : m_sun) mark(list, out.sun);
    for (const PassList& list : m_sunClustered) mark(list, out.sun);
    for (const PassList& list : m_pages) mark(list, out.sun);
    for (const PassList& list : m_pageCulled)
        if (list.indirect >= 0) mark(list, out.sun);
    return out;
}

WorkByLevel PassLists::workByLevel(const GpuScene& gpuScene) const {
    WorkByLevel out;
    out.camera.assign(kMaxLodLevels, {});
    out.sun.assign(kMaxLodLevels, {});
    gpuScene.addLevelWork(drawn(m_camera), out.camera);
    if (m_cameraLeavesClustered) gpuScene.addLevelWork(drawn(m_cameraClustered), out.camera);
    for (const PassList& list : m_sun) gpuScene.addLevelWork(drawn(list), out.sun);
    for (const PassList& list : m_sunClustered) gpuScene.addLevelWork(drawn(list), out.sun);
    for (const PassList& list : m_pages) gpuScene.addLevelWork(drawn(list), out.sun);
    for (const PassList& list : m_pageCulled)
        if (list.indirect >= 0) gpuScene.addLevelWork(drawn(list), out.sun);
    return out;
}

std::vector<PassList> PassLists::sunCulledRanges(bool foliageOpacity) const {
    // With opacity layers the depth pass leaves a list's alpha-tested casters out and the layers
    // draw them twice (SunPass::draw, OpacityLayers::draw): once more than the list counts them.
    std::vector<PassList> ranges;
    const auto add = [&](const PassList& list) {
        ranges.push_back({.count = list.count, .indirect = list.indirect});
        if (!foliageOpacity) return;
        PassList leaves{.count = list.count, .indirect = list.indirect};
        for (size_t slot = 0; slot < leaves.count.size(); ++slot)
            if (!m_alphaTested[slot / kMaxLodLevels]) leaves.count[slot] = 0;
        ranges.push_back(std::move(leaves));
    };
    for (const PassList& list : m_sun) add(list);
    for (const PassList& list : m_pageCulled)
        if (list.indirect >= 0) add(list);
    return ranges;
}

DrawStats PassLists::gpuSunDrawn(bool foliageOpacity) const {
    const std::vector<PassList> ranges = sunCulledRanges(foliageOpacity);
    std::vector<const PassList*> asked;
    for (const PassList& list : ranges) asked.push_back(&list);
    DrawStats sum;
    for (const DrawStats& drawn : m_gpuCulling->submitted(asked)) sum += drawn;
    return sum;
}

void PassLists::describeGpuLists(FrameFigureSources& sources, bool foliageOpacity) const {
    sources.commands = m_gpuCulling->commandBuffer();
    sources.commandWords = m_gpuCulling->commandWords();
    sources.lists.push_back({m_camera.indirect, m_camera.count, CulledListShape::Pass::Camera});
    for (PassList& list : sunCulledRanges(foliageOpacity))
        sources.lists.push_back({list.indirect, std::move(list.count), CulledListShape::Pass::Sun});
    for (size_t i = 0; i < m_local.size(); ++i)
        if (m_local[i].indirect >= 0)
            sources.lists.push_back(
                {m_local[i].indirect, m_local[i].count, CulledListShape::Pass::Local, m_localFaces[i]});
    // The commands copied for the figures: up to the last list's, not the room made for pages.
    size_t used = 0;
    for (const CulledListShape& list : sources.lists) used = std::max(used, size_t(list.indirect) + list.count.size());
    sources.commandWords = std::min(sources.commandWords, used * kIndirectCommandWords);
}

std::vector<uint32_t> PassLists::nearestFirst(const core::Vec3& wsTowardsLight) const {
    // Along any ray of a sun above the horizon, nearer the sun is higher: a linear key
    // dot(p, a) orders every ray's points as the depth test does whenever dot(a, wsTowardsLight)
    // > 0. Of those keys, height (a = up) ignores where a batch lies across the ground: the
    // light's own distance (a = wsTowardsLight) ranks a ground by its centre, which for a ground
    // wider than what stands on it can lie nearer the sun than a roof over its far part (and a
    // warped map's depth orders the points of one ray only). A sun on the horizon leaves height
    // no order along its rays: its distance does.
    const core::Vec3 key = wsTowardsLight.y > 1e-3 ? core::Vec3(0.0, 1.0, 0.0) : wsTowardsLight;
    std::vector<double> nearness(m_batchBounds.size(), -INFINITY); // empty batches last
    for (size_t b = 0; b < nearness.size(); ++b)
        if (!m_batchBounds[b].isEmpty()) nearness[b] = glm::dot(m_batchBounds[b].center(), key);
    std::vector<uint32_t> order(nearness.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return nearness[a] > nearness[b]; });
    return order;
}

void PassLists::uploadCameraClustered() {
    const std::vector<uint32_t>& indices = m_cameraClustered.indices;
    const size_t words = std::max<size_t>(indices.size(), 1); // a buffer of size 0 cannot be bound
    if (words > m_cameraClusteredCapacity) {
        m_cameraClusteredCapacity = std::max(words, 2 * m_cameraClusteredCapacity);
        m_cameraClusteredBuffer = createBuffer(nullptr, m_cameraClusteredCapacity * sizeof(uint32_t));
    }
    if (!indices.empty())
        uploadToBuffer(m_cameraClusteredBuffer.id(), 0, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data());
    m_cameraClustered.buffer = m_cameraClusteredBuffer.id();
    m_cameraClustered.offset = 0;
}

void PassLists::collectClustered(std::span<const visibility::HalfSpace> volume, const LodChoice* lod, PassList& out) {
    m_clusteredMeeting.clear();
    for (const uint32_t instance : m_clusteredInstances)
        if (!visibility::isOutside(volume, m_visibility->hierarchy().itemBounds(instance)))
            m_clusteredMeeting.push_back(instance);
    m_visibility->fromItems(m_clusteredMeeting, lod, out);
}

void PassLists::planSunMaps(const PassPlanInputs& in, std::vector<PassList*>& lists) {
    const RenderSettings& settings = in.settings;
    const bool gpu = settings.culling == Culling::Gpu;
    const LodProjection cameraProjection = cameraProjectionOf(in.camera, settings);
    m_sun.resize(virtualMaps(in.setup) ? 0 : in.setup.views.size());
    m_sunClustered.resize(gpu ? m_sun.size() : 0);
    const std::vector<uint32_t> order = nearestFirst(in.wsTowardsLight);
    for (size_t i = 0; i < m_sun.size(); ++i) {
        // No near plane: the pass clamps depth, so casters between the light and the near
        // plane are drawn at depth 0 and must not be culled. Levels by texels of this map.
        const core::Mat4& clipFromWorld = in.setup.views[i].clipFromWorld;
        const LodChoice lod = lodChoiceOf({clipFromWorld, 0.5 * in.setup.mapSize, settings.lodTexelError},
                                          cameraProjection, true, settings);
        const std::vector<visibility::HalfSpace> volume = visibility::clipVolume(clipFromWorld, false);
        m_sun[i].batchOrder = order;
        if (gpu) {
            // The GPU culls every caster but the large clustered meshes (the terrain); of those the
            // CPU lists the instances meeting the map, which draw their clusters meeting it, as a
            // virtual page's do (unmasked: the terrain is the receiver the masks are made of).
            const GpuReceiverMask mask = GpuReceiverMask::of(*m_receiverMasks, in.setup, i);
            m_gpuCulling->cull(GpuCulling::kCameraPasses + i, volume, settings.lod ? &lod : nullptr,
                               GpuCulling::Phase::All, m_sun[i], masked(in.setup, settings) ? &mask : nullptr, 1,
                               /*leaveClustered=*/true);
            collectClustered(volume, settings.lod ? &lod : nullptr, m_sunClustered[i]);
            m_sunClustered[i].batchOrder = order;
            lists.push_back(&m_sunClustered[i]);
            continue;
        }
        m_visibility->collect(volume, settings.culling != Culling::Off, settings.lod ? &lod : nullptr, m_sun[i],
                              m_masks ? &(*m_masks)[i] : nullptr);
        lists.push_back(&m_sun[i]);
    }
    if (gpu) m_costs.inGl += m_gpuCulling->takeGlTimes();
}

size_t PassLists::firstLocalPass(const core::ShadowSetup& setup) {
    return GpuCulling::kCameraPasses + (virtualMaps(setup) ? 0 : setup.views.size());
}

size_t PassLists::firstPagePass(const PassPlanInputs& in) {
    return firstLocalPass(in.setup) + LocalShadowMaps::listCount(in.localLights, in.localPass);
}

void PassLists::planLocal(const PassPlanInputs& in) {
    // Full meshes (levels are chosen for the sun's maps and the camera); a point light's layered
    // pass culled to the cube around its range. With GPU culling, each list culled on the GPU
    // in a pass of its own, after the sun's.
    const bool cull = in.settings.culling != Culling::Off, gpu = in.settings.culling == Culling::Gpu;
    const core::LocalLighting& lights = in.localLights;
    m_local.resize(LocalShadowMaps::listCount(lights, in.localPass));
    m_localFaces.assign(m_local.size(), 1);
    m_localVolumes.assign(m_local.size(), {});
    m_localClustered.resize(gpu ? m_local.size() : 0);
    size_t next = 0;
    const auto collect = [&](std::span<const visibility::HalfSpace> volume, uint32_t replicas = 1) {
        if (cull) m_localVolumes[next].assign(volume.begin(), volume.end()); // else every cluster
        PassList& list = m_local[next];
        if (gpu) {
            // The large clustered meshes (the terrain) left to the CPU, as the sun's maps leave them.
            m_gpuCulling->cull(firstLocalPass(in.setup) + next, volume, nullptr, GpuCulling::Phase::All, list, nullptr,
                               replicas, /*leaveClustered=*/true);
            collectClustered(volume, nullptr, m_localClustered[next]);
        } else {
            m_visibility->collect(volume, cull, nullptr, list);
        }
        ++next;
    };
    for (size_t p = 0; p < lights.points.size(); ++p) {
        const core::ShadowSetup& cube = lights.pointSetups[p];
        if (in.localPass == LocalPass::PerFace) {
            for (const core::ShadowView& view : cube.views) collect(visibility::clipVolume(view.clipFromWorld, false));
        } else if (cube.views.empty()) {
            m_local[next++] = {};
        } else {
            // Layered from the vertex shader, every instance is drawn once per kept face; from
            // the geometry shader, drawn once and amplified (counted per face all the same, as
            // LocalShadowMaps::draw counts).
            const bool perInstance = in.localPass == LocalPass::VertexLayer;
            if (!perInstance) m_localFaces[next] = uint32_t(cube.views.size());
            collect(rangeBox(lights.points[p].wsPosition, lights.points[p].range),
                    perInstance ? uint32_t(cube.views.size()) : 1u);
        }
    }
    for (const core::ShadowSetup& spot : lights.spotSetups) {
        if (spot.views.empty())
            m_local[next++] = {};
        else
            collect(visibility::clipVolume(spot.views[0].clipFromWorld, false));
    }
}

std::optional<core::Vec2> PassLists::lastVisibleDepth() {
    m_depthRangeWanted = true; // from now on every pre-pass is reduced as it is drawn
    return visibleDepthNow();
}

std::optional<core::Vec2> PassLists::visibleDepthNow() {
    if (m_prepassUnreduced) {
        m_depthRange->reduce(*m_cameraDepth);
        m_prepassUnreduced = false;
    }
    return m_depthRange->read();
}

void PassLists::move(uint32_t globalInstance, const core::Aabb& wsBox) {
    // Virtual maps redraw the pages under where it was and where it is.
    m_movedBoxes.push_back(m_visibility->hierarchy().itemBounds(globalInstance));
    m_movedBoxes.push_back(wsBox);
    m_keptCamera.reset(); // its list and depth no longer hold
    m_visibility->move(globalInstance, wsBox);
    m_gpuCulling->move(globalInstance, wsBox);
}

void PassLists::afterMoves() {
    if (m_visibility->rebuildIfDegraded()) m_occlusion->hierarchyRebuilt();
}

} // namespace shadowkit::gl
