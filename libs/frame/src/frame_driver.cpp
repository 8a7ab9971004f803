#include "shadowkit/frame/frame_driver.h"

#include "shadowkit/core/visible_depth.h"

#include <chrono>
#include <utility>

namespace shadowkit::frame {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

FrameDriver::FrameDriver(FrameConfig config) : m_config(std::move(config)) { reset(); }

core::Result<FrameDriver> FrameDriver::create(FrameConfig config) {
    if (auto s = config.check(); !s) return s.errorInfo();
    return FrameDriver(std::move(config));
}

void FrameDriver::reset() {
    m_hysteresis.reset();
    m_chooser.reset();
    if (m_config.heldLattices) m_hysteresis.emplace(*m_config.heldLattices);
    if (m_config.automatic) m_chooser.emplace(*m_config.automatic);
}

core::Status FrameDriver::setConfig(FrameConfig config) {
    if (auto s = config.check(); !s) return s;
    m_config = std::move(config);
    reset();
    return core::Ok{};
}

core::Result<PreparedFrame> FrameDriver::prepare(gl::Renderer& renderer, const scene::ResolvedView& view) {
    PreparedFrame f;
    f.view = view;
    f.inputs = m_config.technique;
    f.inputs.camera = view.camera;
    f.inputs.light = view.light;
    f.inputs.wsSceneBounds = renderer.wsSceneBounds(); // O(1): the instance hierarchy's root
    f.inputs.virtualMaps.imageHeight = view.height;    // a pixel's footprint: the clipmap's level rule
    f.settings = m_config.render;
    f.settings.width = view.width;
    f.settings.height = view.height;
    f.settings.sun = view.sun;
    f.settings.culling = renderer.culling(m_config.render.culling); // auto: what this driver runs best
    // The sun's size where the view or its path gives one (a sunset path's sun, a view of its own).
    if (view.sunAngleDegrees) f.settings.sunAngleDegrees = *view.sunAngleDegrees;
    f.settings.fogDensity = static_cast<float>(m_config.fogDensity.value_or(view.fogDensity));
    f.settings.bias = m_config.bias.resolve(f.inputs, f.settings.filter);

    // 1. Local lights: independent of the sun's set-up, needed by every pass after this.
    auto lighting = localLightingFor(m_config, view, f.inputs.wsSceneBounds);
    if (!lighting) return lighting.errorInfo();
    if (auto s = renderer.setLocalLights(std::move(lighting).value()); !s) return s.errorInfo();

    // 2–3. One read-back before the passes where both want one. Auto reads the receivers back
    // (a low-resolution eval pass: depth and normals), and the visible depth range is taken from
    // that same read-back; without auto, a camera pre-pass at the frame's resolution (culled as
    // the unrefined set-up would cull: the range does not depend on the shadow maps) gives it.
    const auto prePassStart = std::chrono::steady_clock::now();
    std::optional<core::RasterBuffers> receivers;
    if (m_chooser) {
        auto readBack = readReceivers(renderer, f.inputs, f.settings);
        if (!readBack) return readBack.errorInfo();
        receivers = std::move(readBack).value();
        ++f.prePasses.submissions, ++f.prePasses.readBacks;
    }
    if (m_config.visibleDepthFromFrame) {
        if (receivers) {
            if (const auto range = core::visibleDepthRange(receivers->viewDepth)) f.inputs.visibleDepth = *range;
        } else {
            auto unrefined = core::computeShadowSetup(f.inputs);
            if (!unrefined) return unrefined.errorInfo();
            auto range = renderer.visibleDepth(f.inputs.camera, f.inputs.light, *unrefined, f.settings);
            if (!range) return range.errorInfo();
            if (*range) f.inputs.visibleDepth = **range;
            ++f.prePasses.submissions, ++f.prePasses.readBacks;
        }
    }

    // 3. Auto: the receivers' samples, then the choice; the bias follows the chosen technique.
    if (m_chooser) {
        const std::vector<core::ReceiverSample> samples =
            core::receiverSamples(*receivers, f.inputs.camera, f.inputs.light, gl::ReceiverSampling{}.maxSamples);
        const auto start = std::chrono::steady_clock::now();
        auto choice = m_chooser->choose(f.inputs, f.settings.width, f.settings.height, samples);
        if (!choice) return choice.errorInfo();
        f.autoMilliseconds = millisecondsSince(start);
        f.autoChoice = std::move(choice).value();
        f.inputs = f.autoChoice->inputs;
        f.settings.bias = m_config.bias.resolve(f.inputs, f.settings.filter);
    }
    f.prePasses.milliseconds = millisecondsSince(prePassStart);

    // 4. The set-up: held or fresh.
    const auto start = std::chrono::steady_clock::now();
    auto setup = m_hysteresis ? m_hysteresis->next(f.inputs) : core::computeShadowSetup(f.inputs);
    if (!setup) return setup.errorInfo();
    f.setupMilliseconds = millisecondsSince(start);
    f.setup = std::move(setup).value();
    if (m_hysteresis) f.refits = m_hysteresis->lastRefits();
    return f;
}

namespace {

// The cheapest shadow set-up there is, for a pass whose shadow term nothing reads.
core::Result<core::ShadowSetup> cheapestSetup(const core::ShadowSetupInputs& inputs) {
    core::ShadowSetupInputs cheapest = inputs;
    cheapest.technique = core::Technique::Standard;
    cheapest.mapSize = 64;
    return core::computeShadowSetup(cheapest);
}

} // namespace

core::Result<core::RasterBuffers> readReceivers(gl::Renderer& renderer, const core::ShadowSetupInputs& inputs,
                                                const gl::RenderSettings& settings,
                                                const gl::ReceiverSampling& sampling) {
    auto setup = cheapestSetup(inputs);
    if (!setup) return setup.errorInfo();
    return gl::readReceivers(renderer, inputs.camera, inputs.light, *setup, settings, sampling);
}

core::Result<std::vector<core::ReceiverSample>> sampleReceivers(gl::Renderer& renderer,
                                                                const core::ShadowSetupInputs& inputs,
                                                                const gl::RenderSettings& settings,
                                                                const gl::ReceiverSampling& sampling) {
    auto raster = readReceivers(renderer, inputs, settings, sampling);
    if (!raster) return raster.errorInfo();
    return core::receiverSamples(*raster, inputs.camera, inputs.light, sampling.maxSamples);
}

core::Result<DrawnFrame> FrameDriver::draw(gl::Renderer& renderer, const scene::ResolvedView& view) {
    auto prepared = prepare(renderer, view);
    if (!prepared) return prepared.errorInfo();
    const PreparedFrame& f = *prepared;
    const auto start = std::chrono::steady_clock::now();
    auto stats = renderer.render(f.view.camera, f.view.light, f.setup, f.settings);
    if (!stats) return stats.errorInfo();
    return DrawnFrame{std::move(prepared).value(), *stats, millisecondsSince(start)};
}

} // namespace shadowkit::frame
