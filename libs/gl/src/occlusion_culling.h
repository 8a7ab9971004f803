// Occlusion culling of the camera pass: CHC++ (core/coherent_culling.h) on hardware
// occlusion queries. Runs as a depth pre-pass into a CameraDepthTarget: the instances it
// finds visible are drawn there as it goes (depth and view depth), the queries draw node
// boxes against that depth with GL_ANY_SAMPLES_PASSED_CONSERVATIVE. The camera pass then
// draws exactly the instances drawn here.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "render_targets.h"
#include "stopwatch.h"
#include "visibility.h"

#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/visibility/coherent_culling.h"

#include <optional>
#include <vector>

namespace shadowkit::gl {

class OcclusionCuller final : public visibility::OcclusionQueries {
public:
    // `visibility` and `scene` must outlive the culler.
    static core::Result<std::unique_ptr<OcclusionCuller>> create(Visibility& visibility, const GpuScene& scene);
    ~OcclusionCuller() override;

    // One frame into `target` (cleared here); the camera's Frame uniforms must be bound.
    // After a camera cut — the first frame, a jump of the eye, a turn, a new projection — the
    // history is dropped and the pre-pass repeats until the drawn set stops changing (at most
    // kMaxSettleFrames), so the frame returned is the steady state a running application
    // reaches. `drawn`: the global instance indices drawn.
    visibility::CoherentCullingStats frame(const core::PerspectiveCamera& camera, const LodChoice* lod,
                                           CameraDepthTarget& target, std::vector<uint32_t>& drawn);
    static constexpr int kMaxSettleFrames = 4;
    // Time of the last frame() (or prepass()) inside GL calls that do or await the GPU's
    // work: drawing the pre-pass, the query boxes, reading results (blocking when one is not
    // back), the settle loop's glFinish; polling for results is the culling's own. On llvmpipe that is the rasteriser
    // itself, on a GPU mostly the driver; the rest of frame() is the culling's own CPU cost (traversal, LOD choice,
    // draw lists).
    const CpuTimes& glTimes() const { return m_gl; }

    // The hierarchy was rebuilt (Visibility::rebuildIfDegraded): its nodes are new, so the
    // next frame starts as after a camera cut.
    void hierarchyRebuilt() { m_last.reset(); }

    // A plain depth pre-pass of these instances into `target` (cleared here): the camera's
    // depth for receiver masks when occlusion culling is off. A large mesh draws its clusters
    // meeting `frustum` (empty: all of them).
    void prepass(std::span<const visibility::HalfSpace> frustum, const LodChoice* lod, CameraDepthTarget& target,
                 std::span<const uint32_t> items);

    // visibility::OcclusionQueries
    void draw(std::span<const uint32_t> items) override;
    uint32_t issue(std::span<const uint32_t> nodes) override;
    bool available(uint32_t query) override;
    bool visible(uint32_t query) override;

private:
    OcclusionCuller(Visibility& visibility, const GpuScene& scene);
    bool isCut(const core::PerspectiveCamera& camera, int width, int height) const;

    Visibility& m_visibility;
    const GpuScene& m_scene;
    visibility::CoherentCulling m_chc;
    ProgramPair m_depthPrograms; // the camera depth pre-pass
    Program m_boxProgram;
    VertexArray m_emptyVertexArray;
    std::vector<GLuint> m_queries; // pool; a handle is an index
    std::vector<uint32_t> m_freeQueries;
    // Streaming buffers, written front to back through a frame, restarted at each frame.
    Buffer m_boxes, m_lists;
    size_t m_boxCapacity = 0, m_boxCursor = 0;   // in boxes
    size_t m_listCapacity = 0, m_listCursor = 0; // in indices
    std::vector<glm::vec4> m_boxStaging;
    PassList m_drawList;
    std::vector<visibility::HalfSpace> m_frustum; // the camera's: a large mesh draws its clusters in it
    const LodChoice* m_lod = nullptr;
    struct CameraKey {
        core::PerspectiveCamera camera;
        int width = 0, height = 0;
    };
    std::optional<CameraKey> m_last;
    CpuTimes m_gl;
    bool m_unflushed = false; // commands issued since the last glFlush
};

} // namespace shadowkit::gl
