#include "shadowkit/measure/frame_costs.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowkit::measure {
namespace {

// The values after the first (a camera cut), or the first alone when there is no other.
std::vector<double> steady(const std::vector<double>& values) {
    return values.size() > 1 ? std::vector<double>(values.begin() + 1, values.end()) : values;
}

} // namespace

Spread spreadOf(std::vector<double> v) {
    std::erase_if(v, [](double x) { return std::isnan(x); }); // late figures that never came
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    return {v.front(), v[v.size() / 2], v.back()};
}

nlohmann::json toJson(const Spread& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

void FrameCosts::add(const frame::DrawnFrame& drawn, const gl::Traffic& traffic, double animateMilliseconds) {
    const gl::FrameStats& stats = drawn.stats;
    m_readBacks.push_back(double(traffic.readBacks));
    m_bytesUploaded.push_back(double(traffic.bytesUploaded));
    m_bytesReadBack.push_back(double(traffic.bytesReadBack));
    m_dispatches.push_back(double(traffic.dispatches));
    m_workGroups.push_back(double(traffic.workGroups));
    m_setup.push_back(drawn.frame.setupMilliseconds);
    m_animate.push_back(animateMilliseconds);
    m_frameCpu.push_back(animateMilliseconds + drawn.frame.prePasses.milliseconds + drawn.frame.setupMilliseconds +
                         drawn.milliseconds);
    m_cull.push_back(stats.cullMilliseconds);
    m_cullGl.push_back(stats.cullGlMilliseconds);
    m_cullOwn.push_back(stats.cullOwnCpuMilliseconds);
    m_lists.push_back(stats.listCpuMilliseconds);
    m_prepass.push_back(stats.occlusionMilliseconds);
    m_masks.push_back(stats.receiverMaskMilliseconds);
    const double unknown = std::numeric_limits<double>::quiet_NaN(); // until late figures come
    m_shadowGpu.push_back(stats.gpuFiguresLate ? unknown : stats.shadow.gpuMilliseconds);
    m_mainGpu.push_back(stats.gpuFiguresLate ? unknown : stats.main.gpuMilliseconds);
    m_localGpu.push_back(stats.gpuFiguresLate ? unknown : stats.local.gpuMilliseconds);
    m_frameNumbers.push_back(stats.frame);
    const visibility::CoherentCullingStats& o = stats.occlusion;
    m_nodesVisited.push_back(double(o.nodesVisited));
    m_queries.push_back(double(o.queriesIssued));
    m_nodesQueried.push_back(double(o.nodesQueried));
    m_multiQueryFailures.push_back(double(o.multiQueryFailures));
    m_waits.push_back(double(o.waits));
    if (const auto& v = stats.virtualPages) {
        m_pagesRendered.push_back(double(v->pagesRendered));
        m_requestsAge.push_back(double(v->marksAge));
        m_tableBytes.push_back(double(v->tableBytes));
        m_pagesOnGpu.push_back(double(v->pagesCulledOnGpu));
    }
    m_last = stats;
    addLate(stats.gpuFigures);
}

void FrameCosts::addLate(std::span<const gl::GpuFigures> figures) {
    for (const gl::GpuFigures& f : figures) {
        const auto at = std::find(m_frameNumbers.begin(), m_frameNumbers.end(), f.frame);
        if (at == m_frameNumbers.end()) continue; // another view's frame
        const size_t i = size_t(at - m_frameNumbers.begin());
        m_shadowGpu[i] = f.shadowMilliseconds;
        m_mainGpu[i] = f.mainMilliseconds;
        m_localGpu[i] = f.localMilliseconds;
        if (i + 1 == m_frameNumbers.size()) f.fill(m_last);
    }
}

int FrameCosts::framesTimed() const {
    return static_cast<int>(
        std::count_if(m_shadowGpu.begin(), m_shadowGpu.end(), [](double v) { return !std::isnan(v); }));
}

Spread FrameCosts::setupRest() const { return spreadOf(steady(m_setup)); }

Spread FrameCosts::readBacks() const { return spreadOf(steady(m_readBacks)); }
Spread FrameCosts::bytesUploaded() const { return spreadOf(steady(m_bytesUploaded)); }
Spread FrameCosts::bytesReadBack() const { return spreadOf(steady(m_bytesReadBack)); }
Spread FrameCosts::dispatches() const { return spreadOf(steady(m_dispatches)); }
Spread FrameCosts::workGroups() const { return spreadOf(steady(m_workGroups)); }
Spread FrameCosts::pagesRendered() const { return spreadOf(steady(m_pagesRendered)); }
Spread FrameCosts::requestsAge() const { return spreadOf(steady(m_requestsAge)); }
Spread FrameCosts::tableBytes() const { return spreadOf(steady(m_tableBytes)); }
Spread FrameCosts::pagesCulledOnGpu() const { return spreadOf(steady(m_pagesOnGpu)); }

std::vector<double> FrameCosts::steadyFrameCpu() const { return steady(m_frameCpu); }

FrameCosts::Occlusion FrameCosts::occlusion() const {
    return {spreadOf(steady(m_nodesVisited)), spreadOf(steady(m_queries)), spreadOf(steady(m_nodesQueried)),
            spreadOf(steady(m_multiQueryFailures)), spreadOf(steady(m_waits))};
}

nlohmann::json FrameCosts::json() const {
    nlohmann::json j = {{"frame_cpu_ms", toJson(frameCpu())},
                        {"animate_ms", toJson(animate())},
                        {"frames_timed", framesTimed()},
                        {"setup_first_ms", setupFirst()},
                        {"setup_ms", toJson(setupRest())},
                        {"cull_ms", toJson(cull())},
                        {"cull_own_ms", toJson(cullOwn())},
                        {"cull_gl_ms", toJson(cullGl())},
                        {"list_ms", toJson(lists())},
                        {"read_backs", toJson(readBacks())},
                        {"bytes_uploaded", toJson(bytesUploaded())},
                        {"bytes_read_back", toJson(bytesReadBack())},
                        {"dispatches", toJson(dispatches())},
                        {"work_groups", toJson(workGroups())}};
    for (const auto& [pass, stats, gpu] :
         {std::tuple{"shadow", &m_last.shadow, shadowGpu()}, std::tuple{"local", &m_last.local, localGpu()},
          std::tuple{"main", &m_last.main, mainGpu()}})
        j[pass] = {{"instances", stats->instances},
                   {"triangles", stats->triangles},
                   {"draw_calls", stats->drawCalls},
                   {"gpu_ms", toJson(gpu)}};
    // The last frame's overdraw that reached the maps' depth (fixed maps; 0 texels otherwise).
    j["shadow"]["samples_passed"] = m_last.shadow.samplesPassed;
    j["shadow"]["map_texels"] = m_last.shadow.mapTexels;
    if (m_last.shadow.mapTexels > 0)
        j["shadow"]["samples_per_texel"] = double(m_last.shadow.samplesPassed) / double(m_last.shadow.mapTexels);
    // With opacity layers, their first leaf's samples (depth-tested) and every leaf fragment the
    // transmittance blended, over the same texels.
    j["shadow"]["first_leaf_samples"] = m_last.shadow.firstLeafSamples;
    j["shadow"]["leaf_fragments"] = m_last.shadow.leafFragments;
    // The samples the last frame's main pass wrote into the image (once per covered pixel
    // over the camera's depth pre-pass).
    j["main"]["samples_passed"] = m_last.main.samplesPassed;
    // Fragment-shader invocations in the same spans, where the driver counts them (0: it does not).
    j["shadow"]["fragments_shaded"] = m_last.shadow.fragmentsShaded;
    j["main"]["fragments_shaded"] = m_last.main.fragmentsShaded;
    const Occlusion o = occlusion();
    j["receiver_mask_ms"] = toJson(masks());
    j["occlusion"] = {{"nodes_visited", toJson(o.nodesVisited)},
                      {"queries", toJson(o.queries)},
                      {"nodes_queried", toJson(o.nodesQueried)},
                      {"multi_query_failures", toJson(o.multiQueryFailures)},
                      {"waits", toJson(o.waits)},
                      {"prepass_ms", toJson(prepass())}};
    if (!m_pagesRendered.empty())
        j["virtual"] = {{"pages_rendered", toJson(pagesRendered())},
                        {"requests_age", toJson(requestsAge())},
                        {"table_bytes", toJson(tableBytes())},
                        {"pages_culled_on_gpu", toJson(pagesCulledOnGpu())}};
    return j;
}

FrameCosts::Rates FrameCosts::shadowRates(const gl::DepthLimits& limits) const {
    const double seconds = shadowGpu().median * 1e-3;
    if (!(seconds > 0.0)) return {};
    Rates r;
    r.samplesPerSecond = double(m_last.shadow.samplesPassed) / seconds;
    r.trianglesPerSecond = double(m_last.shadow.triangles) / seconds;
    if (limits.fillSamplesPerSecond > 0.0) r.ofFill = r.samplesPerSecond / limits.fillSamplesPerSecond;
    if (limits.smallTrianglesPerSecond > 0.0) r.ofTriangles = r.trianglesPerSecond / limits.smallTrianglesPerSecond;
    return r;
}

} // namespace shadowkit::measure
