#include "occlusion_culling.h"

#include "camera_programs.h"
#include "gl_shaders.h"
#include "program.h"
#include "stopwatch.h"
#include "uniforms.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::gl {
namespace {

// Eye moves and turns beyond which the last frame's visibility is a poor guess; below them
// CHC++'s coherence holds (a camera path moves centimetres to a metre a frame). A cut is a
// cost decision only: the traversal is conservative with any history.
constexpr double kCutDistance = 10.0; // metres
constexpr double kCutCosine = 0.94;   // about 20 degrees

// Grows a query box: a node's own bound is tangent to its geometry (a tree's box sits on
// the terrain), and depth is resolved only to ~1e-4 of the distance at the far end of a
// 32-bit float depth buffer, so a box touching an occluder must not lose to it.
glm::vec4 grown(const core::Vec3& p, double margin, double sign) {
    return glm::vec4(glm::vec3(p + sign * margin), 1.0f);
}

} // namespace

OcclusionCuller::OcclusionCuller(Visibility& visibility, const GpuScene& scene)
    : m_visibility(visibility), m_scene(scene), m_chc(visibility.hierarchy()) {}

OcclusionCuller::~OcclusionCuller() {
    if (!m_queries.empty()) glDeleteQueries(static_cast<GLsizei>(m_queries.size()), m_queries.data());
}

core::Result<std::unique_ptr<OcclusionCuller>> OcclusionCuller::create(Visibility& visibility, const GpuScene& scene) {
    auto culler = std::unique_ptr<OcclusionCuller>(new OcclusionCuller(visibility, scene));
    using namespace shaders;
    auto depth = buildCameraDepthPrePass("camera depth pre-pass");
    if (!depth) return depth.errorInfo();
    auto box = buildProgram("occlusion query boxes", {kFrameGlsl, kOcclusionBoxVert}, {kEmptyFrag});
    if (!box) return box.errorInfo();
    if (auto s = checkUniformBlock(*box, "occlusion culling", "Frame", sizeof(FrameUniforms), frameFields()); !s)
        return s.errorInfo();
    culler->m_depthPrograms = std::move(depth).value();
    culler->m_boxProgram = std::move(box).value();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    culler->m_emptyVertexArray = VertexArray(vao);
    return culler;
}

bool OcclusionCuller::isCut(const core::PerspectiveCamera& c, int width, int height) const {
    if (!m_last) return true;
    const core::PerspectiveCamera& l = m_last->camera;
    return width != m_last->width || height != m_last->height || c.fovYDegrees != l.fovYDegrees ||
           c.aspect != l.aspect || c.zNear != l.zNear || c.zFar != l.zFar ||
           glm::distance(c.wsEye, l.wsEye) > kCutDistance ||
           glm::dot(glm::normalize(c.wsDirection), glm::normalize(l.wsDirection)) < kCutCosine;
}

visibility::CoherentCullingStats OcclusionCuller::frame(const core::PerspectiveCamera& camera, const LodChoice* lod,
                                                        CameraDepthTarget& target, std::vector<uint32_t>& drawn) {
    const bool cut = isCut(camera, target.width, target.height);
    if (cut) m_chc.reset();
    m_last = CameraKey{camera, target.width, target.height};
    m_lod = lod;
    m_gl = {};
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
    glViewport(0, 0, target.width, target.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    m_frustum = visibility::clipVolume(camera.clipFromWorld());
    const std::vector<visibility::HalfSpace>& frustum = m_frustum;
    // The eye's distance to the near plane's corners: a box closer than that may be clipped.
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5), tanX = tanY * camera.aspect;
    const double nearMargin = 1.01 * camera.zNear * std::sqrt(1.0 + tanX * tanX + tanY * tanY);
    auto once = [&] {
        target.clear();
        m_boxCursor = m_listCursor = 0;
        return m_chc.frame(frustum, camera.wsEye, nearMargin, *this, drawn);
    };
    visibility::CoherentCullingStats stats = once();
    std::vector<uint32_t> previous;
    for (int settle = 1; cut && settle < kMaxSettleFrames; ++settle) {
        const Stopwatch finish;
        glFinish(); // the last frame's checks must be back for the next to learn from them
        m_gl += finish.elapsed();
        previous.assign(drawn.begin(), drawn.end());
        std::sort(previous.begin(), previous.end());
        stats = once();
        std::vector<uint32_t> now(drawn.begin(), drawn.end());
        std::sort(now.begin(), now.end());
        if (now == previous) break;
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return stats;
}

void OcclusionCuller::prepass(std::span<const visibility::HalfSpace> frustum, const LodChoice* lod,
                              CameraDepthTarget& target, std::span<const uint32_t> items) {
    m_frustum.assign(frustum.begin(), frustum.end());
    m_lod = lod;
    m_gl = {};
    m_listCursor = 0;
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
    glViewport(0, 0, target.width, target.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    target.clear();
    draw(items);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void OcclusionCuller::draw(std::span<const uint32_t> items) {
    m_visibility.fromItems(items, m_lod, m_drawList);
    const Stopwatch inGl;
    const size_t n = m_drawList.indices.size();
    if (m_listCursor + n > m_listCapacity) {
        m_listCapacity = std::max({m_listCursor + n, 2 * m_listCapacity, size_t(4096)});
        m_lists = createBuffer(nullptr, m_listCapacity * sizeof(uint32_t)); // the old one lives while in use
        m_listCursor = 0;
    }
    uploadToBuffer(m_lists.id(), static_cast<GLintptr>(m_listCursor * sizeof(uint32_t)),
                   static_cast<GLsizeiptr>(n * sizeof(uint32_t)), m_drawList.indices.data());
    m_drawList.offset = static_cast<uint32_t>(m_listCursor);
    m_listCursor += n;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, m_lists.id());
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    // A large mesh (a kilometre of terrain) by its clusters in the camera's view, as the camera pass draws it.
    m_scene.draw(m_drawList, m_depthPrograms.passPrograms(), m_frustum);
    m_unflushed = true;
    m_gl += inGl.elapsed();
}

uint32_t OcclusionCuller::issue(std::span<const uint32_t> nodes) {
    const visibility::InstanceHierarchy& hierarchy = m_visibility.hierarchy();
    const core::Vec3 eye = m_last->camera.wsEye;
    m_boxStaging.clear();
    for (const uint32_t node : nodes) {
        const core::Aabb& box = hierarchy.nodeBounds(node);
        const double margin = 0.01 + 1e-3 * std::sqrt(box.distanceSquared(eye));
        m_boxStaging.push_back(grown(box.min, margin, -1.0));
        m_boxStaging.push_back(grown(box.max, margin, +1.0));
    }
    const size_t n = nodes.size();
    const Stopwatch inGl;
    if (m_boxCursor + n > m_boxCapacity) {
        m_boxCapacity = std::max({m_boxCursor + n, 2 * m_boxCapacity, size_t(1024)});
        m_boxes = createBuffer(nullptr, m_boxCapacity * 2 * sizeof(glm::vec4));
        m_boxCursor = 0;
    }
    uploadToBuffer(m_boxes.id(), static_cast<GLintptr>(m_boxCursor * 2 * sizeof(glm::vec4)),
                   static_cast<GLsizeiptr>(m_boxStaging.size() * sizeof(glm::vec4)), m_boxStaging.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBoxesBinding, m_boxes.id());
    glUseProgram(m_boxProgram.id());
    glUniform1ui(kBoxOffsetLocation, static_cast<GLuint>(m_boxCursor));
    m_boxCursor += n;
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE); // the eye is outside every queried box: back faces lie behind front faces
    glBindVertexArray(m_emptyVertexArray.id());

    if (m_freeQueries.empty()) {
        GLuint id = 0;
        glCreateQueries(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, 1, &id);
        m_freeQueries.push_back(static_cast<uint32_t>(m_queries.size()));
        m_queries.push_back(id);
    }
    const uint32_t handle = m_freeQueries.back();
    m_freeQueries.pop_back();
    glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, m_queries[handle]);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(n));
    glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
    glBindVertexArray(0);
    m_unflushed = true;
    m_gl += inGl.elapsed();
    return handle;
}

bool OcclusionCuller::available(uint32_t query) {
    // The first poll after new draws or queries hands them to the driver (Mesa submits its
    // queued work when a result is asked for; we flush explicitly so that every driver starts
    // on it while the traversal goes on): GL work, timed as such. Later polls only read a
    // fence and count as the culling's own cost, untimed: timing each would cost more
    // than the call.
    GLuint ready = 0;
    if (m_unflushed) {
        const Stopwatch inGl;
        glGetQueryObjectuiv(m_queries[query], GL_QUERY_RESULT_AVAILABLE, &ready);
        glFlush();
        m_unflushed = false;
        m_gl += inGl.elapsed();
    } else {
        glGetQueryObjectuiv(m_queries[query], GL_QUERY_RESULT_AVAILABLE, &ready);
    }
    return ready != 0;
}

bool OcclusionCuller::visible(uint32_t query) {
    GLuint samples = 0;
    const Stopwatch inGl;
    glGetQueryObjectuiv(m_queries[query], GL_QUERY_RESULT, &samples); // blocks if not back yet
    m_gl += inGl.elapsed();
    m_freeQueries.push_back(query);
    return samples != 0;
}

} // namespace shadowkit::gl
