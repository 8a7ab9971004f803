#include "gpu_figures.h"

#include "gpu_culling.h"

#include "shadowkit/gl/read_backs.h"

#include <algorithm>
#include <cstring>

namespace shadowkit::gl {
namespace {

// A slot's layout: twelve 64-bit query results, then the commands (if any).
enum Stamp : size_t {
    ShadowStart,
    ShadowEnd,
    LocalStart,
    LocalEnd,
    MainStart,
    MainEnd,
    Samples,
    MainSamples,
    Shaded,
    MainShaded,
    FirstLeafSamples,
    LeafSamples,
    kStamps
};
constexpr size_t kCommandsOffset = 128;
static_assert(kStamps * sizeof(uint64_t) <= kCommandsOffset);

} // namespace

void GpuFigures::fill(FrameStats& stats) const {
    stats.shadow.gpuMilliseconds = shadowMilliseconds;
    stats.shadow.samplesPassed = samplesPassed;
    stats.shadow.mapTexels = mapTexels;
    stats.local.gpuMilliseconds = localMilliseconds;
    stats.main.gpuMilliseconds = mainMilliseconds;
    stats.main.samplesPassed = mainSamplesPassed;
    stats.shadow.fragmentsShaded = fragmentsShaded;
    stats.main.fragmentsShaded = mainFragmentsShaded;
    stats.shadow.firstLeafSamples = firstLeafSamples;
    stats.shadow.leafFragments = leafFragments;
    if (shadowInstances) stats.shadow.instances = *shadowInstances, stats.shadow.triangles = *shadowTriangles;
    if (mainInstances) stats.main.instances = *mainInstances, stats.main.triangles = *mainTriangles;
    if (localInstances) stats.local.instances = *localInstances, stats.local.triangles = *localTriangles;
}

std::vector<GpuFigures> GpuFigureRing::record(int64_t frame, const FrameFigureSources& sources) {
    // What came back since the last frame, oldest first (fences pass in submission order).
    std::vector<GpuFigures> arrived;
    for (int64_t i = m_next - kFrames; i < m_next; ++i) {
        if (i < 0) continue;
        Slot& slot = m_slots[size_t(i % kFrames)];
        if (!slot.read.pending()) continue; // collected already
        if (!slot.read.arrived()) break;
        arrived.push_back(collect(slot));
    }

    Slot& slot = m_slots[size_t(m_next++ % kFrames)];
    slot.read.dropFence(); // one left: the GPU is kFrames behind; those figures are lost, not waited for
    slot.read.reserve(kCommandsOffset + sources.commandWords * sizeof(uint32_t));
    const GLuint buffer = slot.read.id();
    const auto stamp = [buffer](GLuint query, Stamp at) {
        glGetQueryBufferObjectui64v(query, buffer, GL_QUERY_RESULT, GLintptr(at * sizeof(uint64_t)));
        detail::countBytesReadBack(sizeof(uint64_t)); // into host memory, as copyToHost
    };
    const PassTimer* timers[3] = {&sources.shadow, &sources.local, &sources.main};
    for (size_t t = 0; t < 3; ++t) {
        slot.timed[t] = timers[t]->stamped();
        if (!slot.timed[t]) continue;
        stamp(timers[t]->startQuery(), Stamp(2 * t));
        stamp(timers[t]->endQuery(), Stamp(2 * t + 1));
    }
    // Each pass's samples written and, where the driver counts them, fragments shaded.
    const auto count = [&](const PassSamples& pass, Stamp samples, Stamp shaded, bool& counted, bool& shadedCounted) {
        counted = pass.counted();
        shadedCounted = counted && pass.shadedQuery() != 0;
        if (counted) stamp(pass.query(), samples);
        if (shadedCounted) stamp(pass.shadedQuery(), shaded);
    };
    count(sources.samples, Samples, Shaded, slot.counted, slot.shaded);
    count(sources.mainSamples, MainSamples, MainShaded, slot.mainCounted, slot.mainShaded);
    // The opacity layers' two draws: their samples written, all bench reports of them.
    const auto countSamples = [&](const PassSamples* pass, Stamp samples, bool& counted) {
        counted = pass != nullptr && pass->counted();
        if (counted) stamp(pass->query(), samples);
    };
    countSamples(sources.firstLeafSamples, FirstLeafSamples, slot.firstLeafCounted);
    countSamples(sources.leafSamples, LeafSamples, slot.leavesCounted);
    if (sources.commands) {
        // The culling's compute passes wrote the commands: visible to a copy after this barrier.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        copyToHost(sources.commands, buffer, 0, GLintptr(kCommandsOffset),
                   GLsizeiptr(sources.commandWords * sizeof(uint32_t)));
    }
    slot.read.fence();
    slot.frame = frame;
    slot.mapTexels = sources.mapTexels;
    slot.lists = sources.lists;
    slot.sunDrawnOnCpu = sources.sunDrawnOnCpu;
    slot.localDrawnOnCpu = sources.localDrawnOnCpu;
    slot.mainDrawnOnCpu = sources.mainDrawnOnCpu;
    return arrived;
}

void GpuFigureRing::take(FrameStats& stats, const FrameFigureSources& sources, bool late) {
    stats.gpuFigures = record(stats.frame, sources);
    stats.gpuFiguresLate = late;
    if (late) {
        if (sources.commands)
            for (PassStats* pass : {&stats.shadow, &stats.local, &stats.main}) pass->instances = pass->triangles = 0;
        return;
    }
    for (const GpuFigures& f : finish()) {
        if (f.frame == stats.frame)
            f.fill(stats);
        else
            stats.gpuFigures.push_back(f); // an earlier frame's, read late before this one
    }
}

std::vector<GpuFigures> GpuFigureRing::finish() {
    std::vector<GpuFigures> arrived;
    bool waited = false;
    for (int64_t i = m_next - kFrames; i < m_next; ++i) {
        if (i < 0) continue;
        Slot& slot = m_slots[size_t(i % kFrames)];
        if (!slot.read.pending()) continue;
        if (!waited) detail::countReadBack(); // one wait: later fences pass right after it
        waited = true;
        if (!slot.read.waited()) {
            slot.read.dropFence(); // a lost context: nothing more will come back
            continue;
        }
        arrived.push_back(collect(slot));
    }
    return arrived;
}

GpuFigures GpuFigureRing::collect(Slot& slot) {
    slot.read.dropFence();
    uint64_t stamps[kStamps] = {};
    std::memcpy(stamps, slot.read.data(), sizeof stamps);
    const auto ms = [&](size_t t) {
        const uint64_t start = stamps[2 * t], end = stamps[2 * t + 1];
        return slot.timed[t] && end > start ? double(end - start) * 1e-6 : 0.0;
    };
    GpuFigures figures{.frame = slot.frame,
                       .shadowMilliseconds = ms(0),
                       .localMilliseconds = ms(1),
                       .mainMilliseconds = ms(2),
                       .samplesPassed = slot.counted ? stamps[Samples] : 0,
                       .mapTexels = slot.mapTexels,
                       .mainSamplesPassed = slot.mainCounted ? stamps[MainSamples] : 0,
                       .fragmentsShaded = slot.shaded ? stamps[Shaded] : 0,
                       .mainFragmentsShaded = slot.mainShaded ? stamps[MainShaded] : 0,
                       .firstLeafSamples = slot.firstLeafCounted ? stamps[FirstLeafSamples] : 0,
                       .leafFragments = slot.leavesCounted ? stamps[LeafSamples] : 0};
    if (slot.lists.empty()) return figures;
    const auto* words = reinterpret_cast<const uint32_t*>(static_cast<const char*>(slot.read.data()) + kCommandsOffset);
    const std::span<const uint32_t> commands(words, (slot.read.bytes() - kCommandsOffset) / sizeof(uint32_t));
    DrawStats drawn[3];
    drawn[size_t(CulledListShape::Pass::Sun)] = slot.sunDrawnOnCpu;
    drawn[size_t(CulledListShape::Pass::Local)] = slot.localDrawnOnCpu;
    drawn[size_t(CulledListShape::Pass::Camera)] = slot.mainDrawnOnCpu;
    for (const CulledListShape& list : slot.lists) {
        DrawStats d = GpuCulling::drawnBy(commands, list.indirect, list.count);
        d.instances *= list.faces, d.triangles *= list.faces;
        drawn[size_t(list.pass)] += d;
    }
    using Pass = CulledListShape::Pass;
    figures.mainInstances = drawn[size_t(Pass::Camera)].instances;
    figures.mainTriangles = drawn[size_t(Pass::Camera)].triangles;
    figures.shadowInstances = drawn[size_t(Pass::Sun)].instances;
    figures.shadowTriangles = drawn[size_t(Pass::Sun)].triangles;
    const bool local = std::ranges::any_of(slot.lists, [](const auto& l) { return l.pass == Pass::Local; });
    if (local) {
        figures.localInstances = drawn[size_t(Pass::Local)].instances;
        figures.localTriangles = drawn[size_t(Pass::Local)].triangles;
    }
    return figures;
}

} // namespace shadowkit::gl
