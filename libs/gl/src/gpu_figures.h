// A frame's figures that only the GPU knows — each pass's GPU time, the samples the sun maps'
// depth tests passed, what the GPU-culled lists drew — gathered by the GPU itself into one
// buffer per frame and read by the CPU frames later, once that frame's fence has passed. Engines
// read their GPU statistics this way: a frame that asks for its own figures must wait for the
// GPU to finish it, a stall of the whole pipeline on a real GPU (Renderer::readGpuFiguresLate).
//
// A ring of kFrames slots, each a persistently mapped buffer the GPU writes in command order: the
// timestamps and the sample count through GL_QUERY_BUFFER (glGetQueryBufferObjectui64v, GL 4.5),
// the GPU-culled lists' indirect commands by glCopyNamedBufferSubData; then a fence. The CPU polls
// the fences with a zero timeout. A slot whose fence has not passed when its turn comes round
// again is dropped, not waited for: the figures are statistics, and a frame never waits for them.
#pragma once

#include "fenced_read.h"
#include "gl_object.h"
#include "gpu_scene.h"
#include "pass_samples.h"
#include "pass_timer.h"

#include "shadowkit/gl/frame_stats.h"

#include <array>
#include <span>
#include <vector>

namespace shadowkit::gl {

// Where a GPU-culled list's draws lie in the commands copied (GpuCulling::drawnBy).
struct CulledListShape {
    enum class Pass { Camera, Sun, Local };
    int64_t indirect = -1;
    std::vector<uint32_t> count; // PassList::count: the ranges that can draw
    Pass pass = Pass::Camera;    // whose figures it adds to
    uint32_t faces = 1;          // map faces a geometry shader writes each drawn instance into
};

// What one frame hands over: the queries its passes ended, and with Culling::Gpu the commands
// buffer its lists drew from.
struct FrameFigureSources {
    const PassTimer& shadow;
    const PassTimer& local;
    const PassTimer& main;
    const PassSamples& samples;     // the sun's maps or pages
    const PassSamples& mainSamples; // the camera's main pass
    uint64_t mapTexels = 0;
    // The sun's opacity layers' two draws (OpacityLayers::firstLeafSamples, leafSamples); null: none.
    const PassSamples* firstLeafSamples = nullptr;
    const PassSamples* leafSamples = nullptr;
    GLuint commands = 0; // 0: no GPU-culled list
    size_t commandWords = 0;
    std::vector<CulledListShape> lists;
    // What the sun's pass drew from lists culled on the CPU beside the GPU's (a virtual page's
    // large clustered meshes, the pages past the GPU's room): added to the GPU-culled lists' count.
    DrawStats sunDrawnOnCpu;
    DrawStats localDrawnOnCpu; // the local maps' likewise (their clustered meshes)
    DrawStats mainDrawnOnCpu;  // the main pass's likewise (the clustered meshes in view)
};

class GpuFigureRing {
public:
    static constexpr int kFrames = 3;

    GpuFigureRing() = default;
    GpuFigureRing(const GpuFigureRing&) = delete;
    GpuFigureRing& operator=(const GpuFigureRing&) = delete;

    // The frame `stats` describes hands over its figures, which the GPU writes after its
    // commands. Late: `stats` gets the earlier frames' figures
    // that came back and none of its own (its GPU-culled counts zeroed: the CPU knows only the
    // lists' capacities); else its own figures after one wait.
    void take(FrameStats& stats, const FrameFigureSources& sources, bool late);
    // Every figure still pending, after one wait for the GPU (counted as a read-back).
    std::vector<GpuFigures> finish();

private:
    // Hands over a frame's figures; returns the earlier frames' that came back meanwhile.
    std::vector<GpuFigures> record(int64_t frame, const FrameFigureSources& sources);

    struct Slot {
        FencedReadBuffer read;
        int64_t frame = 0;
        uint64_t mapTexels = 0;
        bool timed[3] = {false, false, false};
        bool counted = false, mainCounted = false;            // samples written, sun's and main pass's
        bool shaded = false, mainShaded = false;              // fragments shaded
        bool firstLeafCounted = false, leavesCounted = false; // the opacity layers' draws
        std::vector<CulledListShape> lists;
        DrawStats sunDrawnOnCpu, localDrawnOnCpu, mainDrawnOnCpu;
    };
    // The figures of a slot whose fence has passed; frees it.
    GpuFigures collect(Slot& slot);

    std::array<Slot, kFrames> m_slots;
    int64_t m_next = 0; // the slot the next frame takes, modulo kFrames
};

} // namespace shadowkit::gl
