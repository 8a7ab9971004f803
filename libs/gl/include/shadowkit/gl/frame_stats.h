// What a frame cost, per pass: GPU time, what was submitted, and where culling's CPU time
// went (Renderer::render's result).
#pragma once

#include "shadowkit/core/virtual_page_cache.h"
#include "shadowkit/visibility/coherent_culling.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace shadowkit::gl {

// The level of detail each instance was drawn at in a frame (Renderer::levelsDrawn), per global
// instance (batches in Scene order): 0 the full mesh, kLevelNotDrawn where the pass drew none.
inline constexpr uint8_t kLevelNotDrawn = 0xff;
struct LevelsDrawn {
    std::vector<uint8_t> camera; // the camera pass
    std::vector<uint8_t> sun;    // the sun's maps, or the virtual pages drawn: the finest level any drew it at
};

// What a pass drew at each level of detail in a frame (Renderer::workByLevel): the instances and
// the triangles of their levels, level 0 the full meshes, and of them the alpha-tested batches'
// (leaves, cards and their billboard clouds) apart. An instance crossing between two levels
// (RenderSettings::lodFade) is drawn, and counted, at both. Whole levels: a large mesh whose
// instance a pass draws cluster by cluster (the CPU's lists: the clusters meeting a map, a page
// or the camera's view) counts all of its level's triangles; PassStats counts those drawn.
struct LevelWork {
    size_t instances = 0, triangles = 0;
    size_t alphaTestedInstances = 0, alphaTestedTriangles = 0;
};
struct WorkByLevel {
    std::vector<LevelWork> camera; // one entry per level, finest first
    std::vector<LevelWork> sun;    // every sun map's or virtual page's list together
};

struct PassStats {
    double gpuMilliseconds = 0.0; // between two GL timestamp queries
    size_t instances = 0;         // submitted (over every map, for the shadow pass)
    size_t triangles = 0;         // submitted
    size_t drawCalls = 0;
    // Shadow pass: samples that passed the depth test (written), and the texels of the maps drawn
    // (the fixed maps, or the virtual pages drawn this frame, guard bands and all: none in a frame
    // that draws no page); their ratio is the overdraw that reaches the depth buffer (1 at best).
    // Main (camera) pass: the samples its depth test passed, the fragments written into the image:
    // at most one per pixel over the camera's depth pre-pass (RenderSettings width × height).
    uint64_t samplesPassed = 0;
    // Fragment-shader invocations in the same span as samplesPassed, where the driver counts
    // them (ARB_pipeline_statistics_query; 0 where not): more than samplesPassed by the
    // fragments shaded and then rejected — by a late depth test, or a discard (pass_samples.h;
    // llvmpipe's counter is not to be trusted: samplesPassed itself in its shadow passes, 0
    // under a discarding shader in a probe).
    uint64_t fragmentsShaded = 0;
    uint64_t mapTexels = 0;
    // Shadow pass with opacity layers (RenderSettings::foliageOpacity), over the same texels: the
    // samples the first leaf's draw passed — depth-tested, about one a texel the leaves cover when
    // they come nearest the sun first — and the fragments the transmittance's draw blended, every
    // leaf's (no depth test). Neither is in samplesPassed, which counts the opaque casters' depth.
    uint64_t firstLeafSamples = 0, leafFragments = 0;
};

// Virtual shadow maps' pages in one frame (docs/virtual-shadow-maps.md): the page cache's
// figures (core::PageCacheStats: requested, resident, rendered, fallen back, deferred, levels
// behind and their lag, slots), and what the GPU side adds.
struct VirtualPageStats : core::PageCacheStats {
    int64_t poolBytes = 0;    // the atlas's depth, 4 bytes a texel (guard bands included)
    int64_t opacityBytes = 0; // with --foliage-opacity: the opacity layers' atlases beside it, mips included
    size_t triangles = 0;     // drawn into the pages rendered this frame
    int64_t tableBytes = 0;   // uploaded into the page table this frame: its changed entries, or all of it when new
    // Of the pages rendered, those whose casters GPU-driven culling chose (Culling::Gpu, within
    // the room its lists' memory allows; the rest, and on the other paths every page, the CPU's).
    int pagesCulledOnGpu = 0;
};

// A frame's figures that only the GPU knows, as they come back frames later when the renderer
// reads them late (Renderer::readGpuFiguresLate): its passes' GPU times, the samples the sun
// maps' depth tests passed, and with Culling::Gpu what the GPU-culled lists drew.
struct FrameStats;
struct GpuFigures {
    int64_t frame = 0; // the frame they describe: its FrameStats::frame
    double shadowMilliseconds = 0.0, localMilliseconds = 0.0, mainMilliseconds = 0.0;
    uint64_t samplesPassed = 0; // the sun's maps or pages (PassStats::samplesPassed)
    uint64_t mapTexels = 0;
    uint64_t mainSamplesPassed = 0; // the main pass's (PassStats::samplesPassed of FrameStats::main)
    uint64_t fragmentsShaded = 0, mainFragmentsShaded = 0; // PassStats::fragmentsShaded of shadow and main
    uint64_t firstLeafSamples = 0, leafFragments = 0;      // the shadow pass's opacity layers' (PassStats)
    // Culling::Gpu: instances and triangles submitted by the culled lists (the other cullings'
    // counts are known on the CPU: FrameStats::shadow, local and main carry them). The local
    // lights' (when there are any) count each instance once per map face it is drawn into, as
    // FrameStats::local.
    std::optional<size_t> shadowInstances, shadowTriangles, mainInstances, mainTriangles;
    std::optional<size_t> localInstances, localTriangles;
    // Into the GPU fields of their frame's stats (as render() fills them when it waits).
    void fill(FrameStats& stats) const;
};

struct FrameStats {
    // This frame's number (render() calls since the renderer was created, from 1).
    int64_t frame = 0;
    // Read late: no GPU time, sample count or GPU-culled count in `shadow`, `local` and `main`
    // (those of this frame are not back yet), and the figures of earlier frames that came back
    // since the last frame, oldest first.
    bool gpuFiguresLate = false;
    std::vector<GpuFigures> gpuFigures;
    PassStats shadow, main;
    PassStats local;               // every local light's maps (Renderer::setLocalLights), faces written counted
    int localMaps = 0;             // spot maps and cube faces drawn
    int skippedFaces = 0;          // cube faces left out: they see nothing of the view
    double cullMilliseconds = 0.0; // CPU: choosing every pass's instances and uploading the lists
    // Of cullMilliseconds, the time inside GL calls that do or await the GPU's work: the
    // camera depth pre-pass's draws, the occlusion queries and their results (blocking when
    // not back), the settle loop after a camera cut, the receiver masks' compute pass and
    // read-back. On llvmpipe that is the rasteriser itself.
    double cullGlMilliseconds = 0.0;
    // Culling's own CPU cost: the CPU time of the calling thread in culling outside those GL
    // calls and outside list building — the hierarchy queries, the CHC++ traversal and its
    // polls, the masks' decoding, dilation and caster tests. Thread time, not wall-clock: on
    // llvmpipe the rasteriser's threads share the cores.
    double cullOwnCpuMilliseconds = 0.0;
    // Of cullMilliseconds, thread CPU time choosing every drawn instance's level of detail and
    // building the passes' lists: per instance drawn, culled or not (so not culling's cost).
    double listCpuMilliseconds = 0.0;
    // Culling::Occlusion: the CHC++ pre-pass (counted in cullMilliseconds, with its waits).
    visibility::CoherentCullingStats occlusion;
    // Wall time of the CHC++ pre-pass, or with Culling::Gpu of the camera's two-phase pass (its
    // culling dispatches, depth pyramid and both pre-pass draws); counted in cullMilliseconds.
    double occlusionMilliseconds = 0.0;
    double receiverMaskMilliseconds = 0.0;        // CPU, incl. the read-back (counted in cullMilliseconds)
    std::optional<VirtualPageStats> virtualPages; // technique virtual
};

} // namespace shadowkit::gl
