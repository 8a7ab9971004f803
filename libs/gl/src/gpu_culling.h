// GPU-driven culling (Culling::Gpu): every instance tested in compute passes that write the
// draw lists and glDrawElementsIndirect commands themselves, so the CPU issues a fixed set
// of draws per pass (one per batch and level, or per batch where vertex stages read each
// command's base instance: GpuScene::draw) and never learns, or waits for, what is drawn.
//
// Based on: Haar & Aaltonen 2015 ("GPU-Driven Rendering Pipelines", SIGGRAPH Advances
// course): culling in compute passes writing indirect draws, and two-phase occlusion against
// a hierarchical depth buffer (Greene et al. 1993) as zeux/niagara and UE5's two-pass HZB do
// it (docs/references.md). The camera pass first draws, into its depth
// pre-pass, the instances visible last frame that are still in the frustum; reduces that
// depth to a pyramid of farthest depths; tests every instance in the frustum against it and
// draws the newly visible ones too. What passes the test is next frame's "visible last
// frame". No frame is ever wrong: the pyramid holds only depths of drawn geometry, so an
// instance culled is hidden by something drawn this frame (with the grown boxes CHC++'s
// queries use). Shadow maps keep the instances meeting their volume, like the CPU path.
//
// The tests are the CPU path's (visibility.cpp): the same half-spaces, the same level of
// detail rule, in double precision, and lists in increasing instance order (gpu_cull.comp),
// so the lists equal Visibility::collect's and the pixels a CPU-culled frame's. Receiver masks
// (Bittner et al. 2011) are tested on the GPU too, at the mask's full resolution, and so are
// the local lights' lists and the virtual pages': all of a frame's pages in one set of three
// dispatches (cullPasses; gl_WorkGroupID.y the page), but for the large clustered meshes, whose
// clusters the CPU picks per page.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "receiver_masks.h"
#include "render_targets.h"
#include "stopwatch.h"
#include "uniforms.h"
#include "visibility.h"

#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/scene/mesh_lod.h"
#include "shadowkit/scene/scene.h"

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace shadowkit::gl {

// A shadow map's receiver mask left on the GPU (ReceiverMasks::markOnGpu).
struct GpuReceiverMask {
    GLuint buffer = 0; // ReceiverMasks::dilatedMasks()
    int map = 0, mapCount = 1;
    core::Mat4 clipFromWorld{1.0};                  // the map's
    std::optional<core::Vec4> linearDepthFromWorld; // the linear layout's depth row
    // Shadow view `view` of `setup`, whose masks `masks` marked (ReceiverMasks::markOnGpu).
    static GpuReceiverMask of(const ReceiverMasks& masks, const core::ShadowSetup& setup, size_t view);
};

class GpuCulling {
public:
    // `scene` as the renderer was created with it; `gpuScene` must outlive the culling.
    static std::unique_ptr<GpuCulling> create(const scene::Scene& scene, std::span<const scene::MeshLods> lods,
                                              const GpuScene& gpuScene);

    // Compiles the passes' programs, once: a renderer that never culls on the GPU never
    // pays for them. An environment error where the driver rejects them (they need doubles).
    core::Status buildPrograms();

    // An instance moved: its new box (in the scene's coordinates).
    void move(uint32_t globalInstance, const core::Aabb& box);
    // Drops what was visible last frame: the next camera pass draws nothing early.
    void forget();

    // Makes room for a frame of `passes` lists (each the capacity of every instance at every
    // level) and their commands. Lists of an earlier frame are not kept.
    void beginFrame(size_t passes);
    // The lists' memory a frame may take: the passes past it (virtual pages beyond the room for
    // them) are the CPU's to cull.
    static constexpr size_t kListBudgetBytes = size_t(256) << 20;
    // How many passes' lists fit kListBudgetBytes (at least one).
    size_t passesWithinBudget() const;

    // Which instances of those meeting the volume a pass keeps.
    enum class Phase {
        All,          // every one
        LastVisible,  // those the last camera pass found visible
        NewlyVisible, // those not visible last frame that the depth pyramid does not hide
        Visible,      // those the pyramid does not hide, either kind; recorded for next frame
    };
    // One pass into region `pass` (< the frame's passes): `out` becomes a list the GPU writes,
    // drawn by GpuScene::draw through its indirect commands. With a mask (phase All only),
    // only the instances that may shadow a receiver it holds. `replicas`: each kept instance is
    // drawn that many times (a point light's cube faces, each copy to its own layer).
    // `leaveClustered`: the batches whose meshes draw by clusters (GpuScene::drawsByClusters) are
    // left out, for the CPU to draw of them what meets the volume (a virtual page's terrain).
    void cull(size_t pass, std::span<const visibility::HalfSpace> volume, const LodChoice* lod, Phase phase,
              PassList& out, const GpuReceiverMask* mask = nullptr, uint32_t replicas = 1, bool leaveClustered = false);
    // One pass of several culled at once: what it keeps and its own level-of-detail projection.
    struct PassVolume {
        std::vector<visibility::HalfSpace> volume;
        LodProjection projection; // LodChoice::pass; the rest of the choice is the dispatch's
    };
    // Passes firstPass, firstPass + 1, … into out[0], out[1], …, as many cull()s of phase All with
    // no mask and one replica would, each with `lod` but its own projection — in one set of three
    // dispatches whatever their number (a frame's virtual pages).
    void cullPasses(size_t firstPass, std::span<const PassVolume> passes, const LodChoice* lod, bool leaveClustered,
                    std::span<PassList> out);

    // The camera's two-phase pass (passes 0 to kCameraPasses − 1): the early and late
    // instances drawn into `target`'s depth (cleared here; the camera's Frame uniforms must
    // be bound), `out` the union the camera pass draws. With `clustered` (a CPU list, uploaded:
    // the large clustered meshes in view), those meshes are left out of every phase and drawn
    // instead by their clusters in view with the early instances, before the pyramid is built.
    void camera(const core::PerspectiveCamera& camera, const LodChoice* lod, CameraDepthTarget& target, PassList& out,
                const PassList* clustered = nullptr);
    static constexpr size_t kCameraPasses = 3;

    // The instances and triangles each list drew, read back from its commands: one read of the
    // whole command buffer (one wait for the GPU, one synchronisation counted) however many lists
    // are asked for. Draw calls are the drawing code's to count (GpuScene::draw).
    std::vector<DrawStats> submitted(std::span<const PassList* const> lists) const;
    DrawStats submitted(const PassList& list) const;
    DrawStats submitted(std::span<const PassList> lists) const; // their sum
    // What a list drew, from a copy of the whole command buffer (`commands`, commandWords() of
    // them): the parse submitted() makes after its read, and gpu_figures.h after a late one.
    static DrawStats drawnBy(std::span<const uint32_t> commands, int64_t indirect, std::span<const uint32_t> count);
    GLuint commandBuffer() const { return m_commands.id(); }
    size_t commandWords() const { return m_commandWords; }
    // A list's contents in the CPU path's layout (indices, first, count), read back.
    PassList read(const PassList& list) const;

    // Time of the last camera() and cull()s inside GL calls (dispatches, the pre-pass's draws).
    const CpuTimes& glTimes() const { return m_gl; }
    CpuTimes takeGlTimes() { return std::exchange(m_gl, {}); }

private:
    GpuCulling(const GpuScene& gpuScene) : m_scene(gpuScene) {}
    void buildPyramid(const CameraDepthTarget& target);
    // A pass's region of the lists: every instance at every level.
    size_t regionWords() const { return kMaxLodLevels * std::max<size_t>(m_instanceCount, 1); }
    struct GpuPass; // gpu_cull.comp's Pass
    static GpuPass gpuPass(std::span<const visibility::HalfSpace> volume, const LodProjection* projection);
    // gpu_cull.comp's three stages over `passes` (uploaded at firstPass onwards), with the phase,
    // mask and occlusion uniforms the caller set: the commands and lists of each, described in `out`.
    void run(size_t firstPass, std::span<const GpuPass> passes, const LodChoice* lod, bool leaveClustered,
             uint32_t replicas, std::span<PassList> out);
    // Where pass `pass`'s list and commands lie, into `out`.
    void describe(size_t pass, bool shadowChain, PassList& out) const;

    const GpuScene& m_scene;
    Program m_stages[3], m_pyramidProgram;
    ProgramPair m_depthPrograms; // the camera depth pre-pass
    Buffer m_instances, m_chunks, m_batches, m_levels, m_flags, m_ranks, m_chunkSums;
    size_t m_scratchPasses = 0; // passes m_ranks and m_chunkSums hold at once
    Buffer m_lists, m_commands, m_passes;
    size_t m_commandWords = 0; // m_commands' size in words
    size_t m_instanceCount = 0, m_chunkCount = 0, m_batchCount = 0;
    std::vector<uint32_t> m_batchFirst, m_batchSize;      // per scene batch
    std::vector<uint32_t> m_cameraLevels, m_shadowLevels; // per scene batch
    std::vector<float> m_scales;                          // per instance, as Visibility's
    size_t m_passCapacity = 0;                            // regions in m_lists
    Buffer m_pyramid;                                     // every level, one after the other (depth_pyramid.comp)
    int m_pyramidWidth = 0, m_pyramidHeight = 0, m_pyramidLevels = 0;
    std::array<glm::ivec4, kCullMaxPyramidLevels> m_pyramidLayout{}; // per level: width, height, offset
    // The camera pass's, for the occlusion test: its projection, eye and pixels.
    glm::mat4 m_cameraClipFromWorld{1.0f};
    glm::vec3 m_wsEye{0.0f};
    glm::ivec2 m_viewport{1, 1};
    PassList m_early, m_late;
    CpuTimes m_gl;
};

} // namespace shadowkit::gl
