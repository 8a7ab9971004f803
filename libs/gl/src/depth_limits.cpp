// The limits benchmark (depth_limits.h): the GL's depth fill and triangle rates. Each draw is
// timed alone by the wall clock between two glFinish calls, not by timestamp queries: a
// deferred rasteriser (llvmpipe) stamps a single draw when it is queued and rasterises it at the
// flush after it (measured: 67 M samples "in 0.17 ms"). On a GPU the finish adds tens of
// microseconds to draws of milliseconds. Its work is counted by GL_SAMPLES_PASSED.
#include "shadowkit/gl/depth_limits.h"

#include "gl_shaders.h"
#include "pass_samples.h"
#include "program.h"
#include "render_targets.h"

#include <algorithm>
#include <chrono>
#include <string>

namespace shadowkit::gl {
namespace {

core::Status check(const DepthLimitsOptions& o) {
    auto inRange = [](int v, int lo, int hi) { return v >= lo && v <= hi; };
    if (!inRange(o.mapTexels, 16, 16384)) return core::fieldError("limits.map_texels", "must be in [16, 16384]");
    if (!inRange(o.fillLayers, 1, 1024)) return core::fieldError("limits.fill_layers", "must be in [1, 1024]");
    if (!inRange(o.gridCells, 1, 4096)) return core::fieldError("limits.grid_cells", "must be in [1, 4096]");
    if (!inRange(o.largeTriangles, 2, 65536) || o.largeTriangles % 2 != 0)
        return core::fieldError("limits.large_triangles", "must be even and in [2, 65536]");
    if (!inRange(o.repeats, 1, 100)) return core::fieldError("limits.repeats", "must be in [1, 100]");
    return core::Ok{};
}

struct Timed {
    double milliseconds = 0.0; // the fastest of the repeats
    uint64_t samples = 0;      // written by the first
};

enum Mode { kFill = 0, kGrid = 1, kLarge = 2 };

} // namespace

core::Result<DepthLimits> measureDepthLimits(const DepthLimitsOptions& o) {
    if (auto s = check(o); !s) return s.errorInfo();
    auto program = buildProgram("depth limits", {shaders::kDepthLimitsVert}, {shaders::kEmptyFrag});
    if (!program) return program.errorInfo();
    auto target = ShadowTarget::create(o.mapTexels, 1);
    if (!target) return target.errorInfo();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao); // attribute-less: positions come from gl_VertexID
    const VertexArray vertexArray(vao);

    const GLuint id = program->id();
    const GLint mode = glGetUniformLocation(id, "mode"), count = glGetUniformLocation(id, "count");
    glBindFramebuffer(GL_FRAMEBUFFER, target->framebuffer.id());
    target->attachLayer(0);
    glViewport(0, 0, o.mapTexels, o.mapTexels);
    glUseProgram(id);
    glBindVertexArray(vao);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);

    PassSamples samples;
    // Each draw from a cleared map, timed alone: nothing else may overlap it.
    auto time = [&](Mode m, int n, GLsizei vertices) {
        Timed t;
        for (int r = 0; r < o.repeats; ++r) {
            const float clearDepth = 1.0f;
            glClearNamedFramebufferfv(target->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
            glProgramUniform1i(id, mode, m);
            glProgramUniform1i(id, count, n);
            glFinish(); // the clear and anything before it done
            if (r == 0) samples.begin();
            const auto start = std::chrono::steady_clock::now();
            glDrawArrays(GL_TRIANGLES, 0, vertices);
            glFinish();
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            if (r == 0) {
                samples.end();
                t.samples = samples.samples();
            }
            t.milliseconds = r == 0 ? ms : std::min(t.milliseconds, ms);
        }
        return t;
    };
    const Timed fill = time(kFill, o.fillLayers, 6 * o.fillLayers);
    const Timed grid = time(kGrid, o.gridCells, 6 * o.gridCells * o.gridCells);
    const Timed large = time(kLarge, o.largeTriangles, 3 * o.largeTriangles);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    auto perSecond = [](double amount, double ms) { return ms > 0.0 ? amount / (ms * 1e-3) : 0.0; };
    DepthLimits limits;
    limits.fillSamples = fill.samples;
    limits.gridSamples = grid.samples;
    limits.smallTriangles = 2ull * uint64_t(o.gridCells) * uint64_t(o.gridCells);
    limits.largeTriangles = uint64_t(o.largeTriangles);
    limits.fillMilliseconds = fill.milliseconds;
    limits.smallMilliseconds = grid.milliseconds;
    limits.largeMilliseconds = large.milliseconds;
    // The fill rate from what GL counted, not from what was asked.
    limits.fillSamplesPerSecond = perSecond(double(fill.samples), fill.milliseconds);
    limits.smallTrianglesPerSecond = perSecond(double(limits.smallTriangles), grid.milliseconds);
    limits.largeTrianglesPerSecond = perSecond(double(limits.largeTriangles), large.milliseconds);
    return limits;
}

} // namespace shadowkit::gl
