#include "shadowkit/measure/measurer.h"

#include "shadowkit/eval/ray_scene.h"
#include "shadowkit/gl/context.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <tuple>

namespace shadowkit::measure {
namespace {

// Everything the truth depends on; compared exactly (a moved camera is another truth).
struct TruthKey {
    core::Vec3 eye, direction, up, light;
    double fov, aspect, zNear, zFar;
    int width, height;
    bool operator==(const TruthKey&) const = default;
};

TruthKey keyOf(const core::PerspectiveCamera& c, const core::DirectionalLight& l, int width, int height) {
    return {c.wsEye, c.wsDirection, c.wsUp, l.wsDirection, c.fovYDegrees, c.aspect, c.zNear, c.zFar, width, height};
}

// A 1280×720 truth holds about 30 MB: enough for a compare grid's few cameras.
constexpr size_t kTruthCacheSize = 4;

} // namespace

struct Measurer::Impl {
    std::unique_ptr<gl::Context> context; // null when the caller owns the context
    std::unique_ptr<gl::Renderer> renderer;
    std::unique_ptr<eval::RayScene> rays;
    double rayTracerSeconds = 0.0;
    std::deque<std::pair<TruthKey, std::shared_ptr<const eval::TruthBuffers>>> truths; // most recent first
};

Measurer::Measurer() : m_impl(std::make_unique<Impl>()) {}

core::Result<eval::PreviousShadowsHere> Measurer::shadowsAt(const Measurement& current,
                                                            const core::PerspectiveCamera& camera,
                                                            const core::ShadowSetup& otherSetup,
                                                            const core::DirectionalLight& otherLight,
                                                            const gl::RenderSettings& settings, bool sameTruth) {
    auto raster = m_impl->renderer->renderEvalBuffers(camera, otherLight, otherSetup, settings);
    if (!raster) return raster.errorInfo();
    eval::PreviousShadowsHere out;
    out.raster = std::move(raster).value();
    out.truthLit = sameTruth ? current.truth->lit : eval::litAt(*m_impl->rays, *current.truth, otherLight);
    return out;
}

core::Status Measurer::moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved) {
    if (moved.empty()) return core::Ok{};
    if (auto s = m_impl->renderer->moveInstances(scene, moved); !s) return s;
    if (auto s = m_impl->rays->moveInstances(scene, moved); !s) return s;
    m_impl->truths.clear(); // every cached truth saw the old places
    return core::Ok{};
}
Measurer::~Measurer() {
    m_impl->renderer.reset(); // GL objects go before the context that owns them
    m_impl->context.reset();
}

core::Result<std::unique_ptr<Measurer>> Measurer::createHeadless(const scene::Scene& scene) {
    auto context = gl::Context::createHeadless();
    if (!context) return context.errorInfo();
    auto measurer = create(scene);
    if (measurer) (*measurer)->m_impl->context = std::move(context).value();
    return measurer;
}

core::Result<std::unique_ptr<Measurer>> Measurer::create(const scene::Scene& scene) {
    auto measurer = std::unique_ptr<Measurer>(new Measurer);
    Impl& m = *measurer->m_impl;
    const auto start = std::chrono::steady_clock::now();
    auto rays = eval::RayScene::build(scene);
    if (!rays) return rays.errorInfo();
    m.rayTracerSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.rays = std::move(rays).value();
    auto renderer = gl::Renderer::create(scene);
    if (!renderer) return renderer.errorInfo();
    m.renderer = std::move(renderer).value();
    return measurer;
}

gl::Renderer& Measurer::renderer() { return *m_impl->renderer; }
const eval::RayScene& Measurer::rays() const { return *m_impl->rays; }
std::string Measurer::contextDescription() const {
    return m_impl->context ? m_impl->context->description() : std::string();
}
double Measurer::rayTracerBuildSeconds() const { return m_impl->rayTracerSeconds; }

std::shared_ptr<const eval::TruthBuffers> Measurer::truth(const core::PerspectiveCamera& camera,
                                                          const core::DirectionalLight& light, int width, int height,
                                                          const std::function<void(double)>& progress) {
    auto& cache = m_impl->truths;
    const TruthKey key = keyOf(camera, light, width, height);
    for (auto it = cache.begin(); it != cache.end(); ++it)
        if (it->first == key) {
            auto found = *it;
            cache.erase(it);
            cache.push_front(found);
            return found.second;
        }
    eval::TruthOptions options;
    options.progress = progress;
    auto truth = std::make_shared<const eval::TruthBuffers>(
        eval::computeTruth(*m_impl->rays, camera, light, width, height, options));
    cache.emplace_front(key, truth);
    if (cache.size() > kTruthCacheSize) cache.pop_back();
    return truth;
}

core::Result<Measurement> Measurer::measure(const core::ShadowSetupInputs& inputs, const gl::RenderSettings& settings,
                                            const MeasureOptions& options) {
    frame::PreparedFrame f;
    f.view.camera = inputs.camera;
    f.view.light = inputs.light;
    f.inputs = inputs;
    f.inputs.virtualMaps.imageHeight = settings.height; // a pixel's footprint: the clipmap's level rule
    auto setup = core::computeShadowSetup(f.inputs);
    if (!setup) return setup.errorInfo();
    f.setup = std::move(setup).value();
    f.settings = settings;
    return measure(f, options);
}

core::Result<Measurement> Measurer::measure(const frame::PreparedFrame& frame, const MeasureOptions& options) {
    const core::ShadowSetupInputs& inputs = frame.inputs;
    const gl::RenderSettings& settings = frame.settings;
    // A camera whose aspect is not the picture's draws the view stretched, and the truth traces
    // it stretched alike: a comparison of another picture than the one asked for
    // (scene::ResolvedView::setSize keeps the two together).
    const double pictureAspect = double(settings.width) / double(settings.height);
    if (!(std::abs(inputs.camera.aspect - pictureAspect) <= 1e-3 * pictureAspect))
        return core::makeError(fmt::format("measure: the camera's aspect {:.4f} is not its picture's, {}×{} ({:.4f})",
                                           inputs.camera.aspect, settings.width, settings.height, pictureAspect));
    Measurement m;
    m.visibleDepth = inputs.visibleDepth;
    m.setup = frame.setup;
    m.bias = gl::biasFor(m.setup, settings);
    gl::Renderer& renderer = *m_impl->renderer;
    std::optional<gl::LevelsDrawn> levels; // with options.levelMap: of the frame's own passes, as virtualPages
    // With the shaded frame, the eval pass is drawn inside it, over the same maps and lists.
    if (options.shadedImage) {
        auto drawn = renderer.renderWithEvalBuffers(inputs.camera, inputs.light, m.setup, settings);
        if (!drawn) return drawn.errorInfo();
        m.raster = std::move(drawn->second);
        m.image = renderer.readColor();
    } else {
        auto raster = renderer.renderEvalBuffers(inputs.camera, inputs.light, m.setup, settings);
        if (!raster) return raster.errorInfo();
        m.raster = std::move(raster).value();
    }
    m.virtualPages = renderer.lastVirtualPages(), m.shadowPass = renderer.lastShadowPass();
    if (options.levelMap) levels = renderer.levelsDrawn();
    m.truth = truth(inputs.camera, inputs.light, settings.width, settings.height, options.truthProgress);
    auto comparison = eval::compare(m.raster, *m.truth, options.compare);
    if (!comparison) return comparison.errorInfo();
    m.comparison = std::move(comparison).value();
    if (levels && settings.sun) {
        static_assert(gl::kLevelNotDrawn == eval::kLevelNotDrawn);
        m.levels = eval::levelMap(m.raster.surfaceId, eval::castersAt(*m_impl->rays, *m.truth, inputs.light),
                                  levels->camera, levels->sun, m.raster.width, m.raster.height);
    }
    if (settings.sunAngleDegrees > 0.0 && settings.sun) {
        m.softTruth = eval::computeSoftTruth(
            *m_impl->rays, *m.truth, {inputs.light.wsTowardsLight(), settings.sunAngleDegrees}, options.softTruth);
        m.soft = eval::compareSoft(m.raster.shadowTerm, *m.softTruth, m.comparison.classes, settings.sunAngleDegrees);
    }
    const core::LocalLighting& local = renderer.localLights();
    if (local.empty()) return m;
    if (settings.sun) m.lights.push_back({"sun", static_cast<int>(m.setup.views.size()), 0, m.comparison});
    for (size_t i = 0; i < local.size(); ++i) {
        auto lightRaster =
            renderer.renderEvalBuffers(inputs.camera, inputs.light, m.setup, settings, static_cast<int>(i));
        if (!lightRaster) return lightRaster.errorInfo();
        const bool point = i < local.points.size();
        const size_t k = point ? i : i - local.points.size();
        const core::ShadowSetup& lightSetup = point ? local.pointSetups[k] : local.spotSetups[k];
        const eval::TruthBuffers lightTruth = point ? eval::underLight(*m_impl->rays, *m.truth, local.points[k])
                                                    : eval::underLight(*m_impl->rays, *m.truth, local.spots[k]);
        auto lightComparison = eval::compare(*lightRaster, lightTruth, options.compare);
        if (!lightComparison) return lightComparison.errorInfo();
        const core::Vec3 wsLight = point ? local.points[k].wsPosition : local.spots[k].wsPosition;
        const double radius = point ? local.points[k].radius : local.spots[k].radius;
        std::optional<eval::SoftFigures> soft;
        if (radius > 0.0) // a lamp with a size: its penumbrae against the sphere's soft truth
            soft = eval::compareSoft(
                lightRaster->shadowTerm,
                eval::computeSphereSoftTruth(*m_impl->rays, lightTruth, {wsLight, radius}, options.softTruth),
                lightComparison->classes, 0.0);
        m.lights.push_back({std::string(point ? "point[" : "spot[") + std::to_string(k) + "]",
                            static_cast<int>(lightSetup.views.size()), lightSetup.skippedFaces,
                            std::move(lightComparison).value(), radius, soft});
    }
    std::vector<const eval::Comparison*> parts;
    for (const LightMeasurement& l : m.lights) parts.push_back(&l.comparison);
    auto combined = eval::combine(parts);
    if (!combined) return combined.errorInfo();
    m.comparison = std::move(combined).value();
    return m;
}

eval::VirtualPagesReport virtualPagesReport(const gl::VirtualPageStats& v) {
    return {.pagesRequested = v.pagesRequested,
            .pagesRendered = v.pagesRendered,
            .pagesResident = v.pagesResident,
            .pagesFellBack = v.pagesFellBack,
            .pagesDeferred = v.pagesDeferred,
            .levelsBehind = v.levelsBehind,
            .lagFrames = v.lagFrames,
            .requestsAge = v.marksAge,
            .poolPages = v.poolPages,
            .poolBytes = v.poolBytes,
            .opacityBytes = v.opacityBytes,
            .shadowTriangles = v.triangles};
}

eval::ViewReport viewReport(const Measurement& m, const gl::RenderSettings& settings, const std::string& view,
                            const std::string& sceneName, uint64_t seed) {
    eval::ViewReport report;
    report.view = view;
    report.technique = std::string(core::techniqueName(m.setup.technique));
    report.scene = sceneName;
    report.seed = seed;
    report.width = settings.width;
    report.height = settings.height;
    report.mapSize = m.setup.mapSize;
    report.maps = static_cast<int>(m.setup.views.size());
    report.bias = m.bias;
    report.filter = core::filterName(settings.filter);
    report.blurIterations = settings.blur.iterations;
    report.foliageOpacity = settings.foliageOpacity;
    report.fallbacks = m.setup.fallbacks;
    report.visibleDepth = m.visibleDepth;
    report.figures = m.comparison.figures;
    if (const auto& v = m.virtualPages) report.virtualPages = virtualPagesReport(*v);
    report.soft = m.soft;
    if (m.truth && m.truth->seconds > 0.0) {
        report.truthSeconds = m.truth->seconds;
        report.truthRaysPerSecond = double(m.truth->rays) / m.truth->seconds;
    }
    for (const LightMeasurement& l : m.lights)
        report.lights.push_back({l.light, l.maps, l.skippedFaces, l.comparison.figures, l.radius, l.soft});
    return report;
}

} // namespace shadowkit::measure
