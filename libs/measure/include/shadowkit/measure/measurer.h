// The measure pipeline, once: shadow set-up → evaluation buffers (GL) → ray-traced truth
// (Embree) → per-pixel comparison and figures. Every front end that asks "how wrong are
// these shadows?" calls this: `shadowkit eval` and `compare`, the integration tests, and
// later the viewer, camera paths and the Python bindings.
//
// This library is where GL and the evaluation meet: libs/eval never sees GL, libs/gl
// never sees Embree; the GL side hands core::RasterBuffers over here.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/setup_hysteresis.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/eval/level_map.h"
#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/report.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/eval/temporal.h"
#include "shadowkit/eval/truth.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace shadowkit::gl {
class Context;
}
namespace shadowkit::eval {
class RayScene;
}

namespace shadowkit::measure {

struct MeasureOptions {
    // Also draw the shaded frame and read it back (Measurement::image).
    bool shadedImage = false;
    // Also find which level of detail drew each pixel's surface and its caster (Measurement::levels):
    // a shadow ray more per shadowed pixel, and GPU-culled lists read back.
    bool levelMap = false;
    // Along a path (PathMeasurer): also draw each frame again with the levels of detail the
    // previous frame's camera chose, for eval::levelPops — one more camera pass and shadow pass a
    // frame.
    bool levelPops = false;
    // Ray-tracing progress, 0..1, from the calling thread; called only when the truth for
    // this camera is not cached yet.
    std::function<void(double)> truthProgress;
    eval::CompareOptions compare;
    // With a sun of some size (the frame's gl::RenderSettings::sunAngleDegrees > 0), the frame
    // is also compared with the soft truth of that disk (eval::computeSoftTruth, Measurement::soft).
    eval::SoftTruthOptions softTruth;
};

// One light of a frame with several: its name ("sun", "point[0]", "spot[1]"), maps and figures.
struct LightMeasurement {
    std::string light;
    int maps = 1;
    int skippedFaces = 0;
    eval::Comparison comparison;
    double radius = 0.0;                   // a lamp's size in metres: then its soft figures
    std::optional<eval::SoftFigures> soft; // against eval::computeSphereSoftTruth
};

struct Measurement {
    core::ShadowSetup setup; // what the frame was drawn with
    core::BiasSettings bias; // and its bias (gl::biasFor)
    std::optional<core::Vec2>
        visibleDepth;           // the set-up's visible range (measured with FrameConfig::visibleDepthFromFrame)
    core::RasterBuffers raster; // the GL side's per-pixel buffers
    std::shared_ptr<const eval::TruthBuffers> truth; // shared with the cache
    // Per-pixel classes and the figures: of the sun, or with spot and point lights of every
    // light together (eval::combine; `lights` holds each).
    eval::Comparison comparison;
    std::vector<LightMeasurement> lights;             // when the renderer has local lights: the sun (if on), then each
    scene::Image image;                               // the shaded frame, with MeasureOptions::shadedImage
    std::optional<gl::VirtualPageStats> virtualPages; // technique virtual: the frame's pages
    gl::PassStats shadowPass;                         // what the frame's sun shadow pass drew
    std::optional<eval::SoftFigures> soft;            // with RenderSettings::sunAngleDegrees > 0 and the sun on
    std::optional<eval::SoftTruth> softTruth;         // the per-pixel truth those figures compare with
    std::optional<eval::LevelMap> levels;             // with MeasureOptions::levelMap and the sun on
    const eval::Figures& figures() const { return comparison.figures; }
};

class Measurer {
public:
    // With its own headless GL context (EGL), made current on return.
    static core::Result<std::unique_ptr<Measurer>> createHeadless(const scene::Scene& scene);
    // In the caller's current GL context (a viewer's window), which must outlive this.
    static core::Result<std::unique_ptr<Measurer>> create(const scene::Scene& scene);
    ~Measurer();
    Measurer(const Measurer&) = delete;
    Measurer& operator=(const Measurer&) = delete;

    // A prepared frame (frame::FrameDriver::prepare with this measurer's renderer: its set-up
    // and settings, the renderer's local lights set for its camera) drawn into the evaluation
    // buffers and compared with the truth for its camera, sun and size. The local lights are
    // measured too, each against its own truth; with settings.sun false the sun is not.
    core::Result<Measurement> measure(const frame::PreparedFrame& frame, const MeasureOptions& options = {});
    // The same for a set-up computed afresh from `inputs` (camera, light, bounds, technique,
    // map size), drawn with `settings` (width and height are the image's; a camera of another
    // aspect is an error) and whatever local lights the renderer holds: a test's single frame.
    core::Result<Measurement> measure(const core::ShadowSetupInputs& inputs, const gl::RenderSettings& settings,
                                      const MeasureOptions& options = {});

    // Ray-traced truth, cached per camera, light and image size (the last few kept): cells
    // of a comparison grid, or frames of a still camera, share it.
    std::shared_ptr<const eval::TruthBuffers> truth(const core::PerspectiveCamera& camera,
                                                    const core::DirectionalLight& light, int width, int height,
                                                    const std::function<void(double)>& progress = {});

    // This frame's surface points (`current`, measured from `camera`) under another frame's
    // shadows (eval::compareFrames): that frame's set-up and light drawn and looked up from
    // this camera, with the casters where the renderer and ray tracer now hold them (move
    // them there first), and the truth at this frame's hit points. `sameTruth`: the light and
    // casters are those of `current`, whose truth is then reused exactly.
    core::Result<eval::PreviousShadowsHere> shadowsAt(const Measurement& current, const core::PerspectiveCamera& camera,
                                                      const core::ShadowSetup& otherSetup,
                                                      const core::DirectionalLight& otherLight,
                                                      const gl::RenderSettings& settings, bool sameTruth);

    // Instances that moved (scene::animate's list) in `scene`, the scene this was created
    // with: the renderer and the ray tracer take their new places, and cached truths go.
    core::Status moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved);

    gl::Renderer& renderer();
    // The ray tracer's scene (Embree): thread-safe to query, e.g. eval::underLight off the GL thread.
    const eval::RayScene& rays() const;
    // The GL context's description when this measurer owns one ("4.5 (Core Profile) Mesa ..."), else "".
    std::string contextDescription() const;
    double rayTracerBuildSeconds() const; // time to build the Embree scene (BVHs)

private:
    Measurer();
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

// A frame's virtual pages as `eval` reports them (eval sees no gl).
eval::VirtualPagesReport virtualPagesReport(const gl::VirtualPageStats& pages);

// The figures of one measurement as a row of `shadowkit eval --json` (eval::ViewReport);
// `filter` is the filter's text form (core::filterName).
eval::ViewReport viewReport(const Measurement& measurement, const gl::RenderSettings& settings, const std::string& view,
                            const std::string& sceneName, uint64_t seed);

} // namespace shadowkit::measure
