// What a view's frames cost (`shadowkit bench`): each frame's CPU and GPU figures collected
// (FrameDriver::draw's DrawnFrame), then their spread — min / median / max over the frames — and
// the JSON row `bench --json` writes. Timings are figures to print, never to assert.
#pragma once

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/depth_limits.h"
#include "shadowkit/gl/read_backs.h"

#include <nlohmann/json_fwd.hpp>

#include <span>
#include <vector>

namespace shadowkit::measure {

struct Spread {
    double min = 0.0, median = 0.0, max = 0.0;
};
// The spread of `values` (upper median for an even count); zeros for none.
Spread spreadOf(std::vector<double> values);
nlohmann::json toJson(const Spread& spread); // {"min", "median", "max"}

class FrameCosts {
public:
    // The next frame of the view; the first is a camera cut (CHC++'s counts skip it).
    // `traffic`: what GL was asked to move and wait for during the frame (gl::trafficSoFar()
    // before and after it): its synchronous GPU-to-CPU reads, each a stall on a GPU, and the
    // bytes it uploaded and read back.
    // A frame drawn with late figures (gl::Renderer::readGpuFiguresLate) has its GPU times and
    // GPU-culled counts filled when they come back, with a later frame or from addLate().
    // `animateMilliseconds`: what placing the frame's movers and posing its deformed meshes cost
    // before it was drawn (scene::animate and Renderer::moveInstances: uploads and refits), part
    // of the frame's CPU side.
    void add(const frame::DrawnFrame& drawn, const gl::Traffic& traffic = {}, double animateMilliseconds = 0.0);
    // Figures read late: each into its frame, when that frame is one of this view's; a frame
    // whose figures never came (the GPU too far behind) is left out of the GPU spreads.
    void addLate(std::span<const gl::GpuFigures> figures);
    int frames() const { return static_cast<int>(m_setup.size()); }
    // Frames whose GPU times came back: with late figures, a frame the GPU was too far behind
    // for has none, and the GPU spreads are over the rest.
    int framesTimed() const;
    // The last frame's pass statistics (triangles, instances, draws; with late figures, once
    // they came back).
    const gl::FrameStats& last() const { return m_last; }

    // The set-up's CPU ms: the first frame computes the focus body; the rest of a still view get
    // it remembered (their spread; the first's alone with one frame).
    double setupFirst() const { return m_setup.empty() ? 0.0 : m_setup.front(); }
    Spread setupRest() const;
    Spread cull() const { return spreadOf(m_cull); }           // culling's CPU ms, all of it
    Spread cullOwn() const { return spreadOf(m_cullOwn); }     // of which culling's own thread time
    Spread cullGl() const { return spreadOf(m_cullGl); }       // of which in GL (pre-pass, queries, waits)
    Spread lists() const { return spreadOf(m_lists); }         // of which levels and lists
    Spread shadowGpu() const { return spreadOf(m_shadowGpu); } // the sun's pass, GPU ms
    Spread mainGpu() const { return spreadOf(m_mainGpu); }     // the camera's pass, GPU ms
    Spread localGpu() const { return spreadOf(m_localGpu); }   // the local lights' maps, GPU ms
    Spread prepass() const { return spreadOf(m_prepass); }     // the camera's culling pass, CPU ms
    Spread masks() const { return spreadOf(m_masks); }         // the receiver masks, CPU ms
    Spread animate() const { return spreadOf(m_animate); }     // movers placed, meshes posed, uploaded: CPU ms
    Spread readBacks() const;                                  // per steady frame (after the first)
    Spread bytesUploaded() const;                              // per steady frame
    Spread bytesReadBack() const;                              // per steady frame
    Spread dispatches() const;                                 // compute dispatches, per steady frame
    Spread workGroups() const;                                 // their work groups, per steady frame
    // Technique virtual, per steady frame: the pages drawn, how many frames old the page requests
    // read were (0: the frame's own; −1: none arrived), and the bytes the page table took (its
    // changed entries, 8 bytes each). Zeros without virtual maps.
    Spread pagesRendered() const;
    Spread requestsAge() const;
    Spread tableBytes() const;
    Spread pagesCulledOnGpu() const; // of pagesRendered, culled by the GPU-driven path's compute passes
    // The whole CPU side of a steady frame (after the first), in ms: its animation (movers placed,
    // deformed meshes posed, both uploaded and refitted), its pre-passes (a measured visible
    // depth, auto's receivers) and set-up, then
    // Renderer::render's wall-clock — culling, levels and lists, uniforms and every GL call made.
    // On a GPU that is what the application's thread pays a frame (nothing in it waits for the
    // GPU once figures are read late); on a software rasteriser it includes the drawing itself.
    Spread frameCpu() const { return spreadOf(steadyFrameCpu()); }
    // CHC++'s counts over the steady frames (after the first; the first alone with one frame).
    struct Occlusion {
        Spread nodesVisited, queries, nodesQueried, multiQueryFailures, waits;
    };
    Occlusion occlusion() const;

    // The cost fields of a bench row: frame_cpu_ms, animate_ms, frames_timed, setup_first_ms, setup_ms, cull_ms,
    // cull_own_ms, cull_gl_ms, list_ms, read_backs, bytes_uploaded, bytes_read_back, dispatches, work_groups, shadow,
    // local and main
    // ({instances, triangles, draw_calls, gpu_ms}), receiver_mask_ms, occlusion ({nodes_visited, queries,
    // nodes_queried, multi_query_failures, waits, prepass_ms}), and with virtual maps `virtual` ({pages_rendered,
    // requests_age, table_bytes}).
    nlohmann::json json() const;

    // The sun's pass against this GL's ceilings (gl/depth_limits.h): the samples it wrote and the
    // triangles it submitted in the last frame over its median GPU time, each as a fraction of
    // the depth fill rate and of the small-triangle rate. The larger fraction is what bounds it;
    // both far below 1 is time lost to neither (state changes, draws, stalls). Zeros without a
    // shadow pass time or fixed maps (virtual pages count no samples).
    struct Rates {
        double samplesPerSecond = 0.0, trianglesPerSecond = 0.0;
        double ofFill = 0.0, ofTriangles = 0.0;
    };
    Rates shadowRates(const gl::DepthLimits& limits) const;

private:
    std::vector<double> steadyFrameCpu() const;

    std::vector<double> m_frameCpu, m_setup, m_cull, m_cullOwn, m_cullGl, m_lists, m_shadowGpu, m_mainGpu, m_localGpu,
        m_prepass, m_masks, m_animate;
    std::vector<double> m_readBacks, m_bytesUploaded, m_bytesReadBack, m_dispatches, m_workGroups;
    std::vector<int64_t> m_frameNumbers; // gl::FrameStats::frame of each
    std::vector<double> m_nodesVisited, m_queries, m_nodesQueried, m_multiQueryFailures, m_waits;
    std::vector<double> m_pagesRendered, m_requestsAge, m_tableBytes, m_pagesOnGpu; // technique virtual
    gl::FrameStats m_last;
};

} // namespace shadowkit::measure
