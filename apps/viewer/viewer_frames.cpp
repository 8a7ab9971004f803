#include "viewer_frames.h"

#include "frame_config_options.h"

#include <fmt/format.h>

namespace shadowkit::viewer {

std::string vec3Text(const core::Vec3& v) { return fmt::format("{:.6g},{:.6g},{:.6g}", v.x, v.y, v.z); }

core::Status ViewerFrames::setOptions(const app::StateOptions& state, scene::Scene& world, double now) {
    auto parsed = parseFrameOptions(state);
    if (!parsed) return app::withFlagName(parsed.errorInfo());
    auto timeline = (*parsed)->timeline.resolve();
    if (!timeline) return timeline.errorInfo();
    auto still = (*parsed)->view.resolve(world);
    if (!still) return still.errorInfo();
    if (timeline->path) still->pathFramedBox = scene::framedOverPath(*timeline->path, world, now);
    auto config = app::frameConfigOf((*parsed)->technique, (*parsed)->render, (*parsed)->lights);
    if (!config) return config.errorInfo();
    auto driver = frame::FrameDriver::create(std::move(config).value());
    if (!driver) return app::withFlagName(driver.errorInfo());
    m_options = std::move(parsed).value();
    m_timeline = std::move(timeline).value();
    m_still = std::move(still).value();
    m_driver = std::move(driver).value();
    return core::Ok{};
}

void ViewerFrames::cut() {
    if (m_driver) m_driver->reset();
}

core::Result<frame::DrawnFrame> ViewerFrames::draw(gl::Renderer& renderer, const scene::Scene& world,
                                                   const core::Vec3& wsEye, const core::Vec3& wsDirection, int width,
                                                   int height, double t) {
    if (!ready()) return core::makeError("viewer: no valid options to draw with");
    scene::ResolvedView view = *m_still;
    // What the state file will say: render --state reads these texts back.
    auto eye = app::parseVec3("--eye", vec3Text(wsEye));
    auto direction = app::parseVec3("--dir", vec3Text(wsDirection));
    if (!eye || !direction) return core::makeError("viewer: the camera is not finite");
    view.camera.wsEye = *eye;
    view.camera.wsDirection = *direction;
    view.setSize(width, height);
    if (auto s = view.camera.validate(); !s) return s.errorInfo();
    auto timed = m_timeline->viewAt(view, world, t, true);
    if (!timed) return timed.errorInfo();
    return m_driver->draw(renderer, *timed);
}

} // namespace shadowkit::viewer
