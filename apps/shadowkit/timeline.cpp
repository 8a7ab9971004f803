#include "timeline.h"

#include "common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

namespace shadowkit::app {
namespace {

// "a:b", "a:", ":b" or "a" -> [first, end) within [0, count).
core::Result<std::pair<int, int>> parseFrameRange(const std::string& text, int count) {
    auto bad = [&] {
        return core::makeError(fmt::format(
            "--frames: expected a:b, a:, :b or a (frame numbers of the path, 0 to {}), got '{}'", count - 1, text));
    };
    auto number = [](const std::string& s, int& out) {
        if (s.empty() || s.size() > 9 ||
            !std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
            return false;
        out = std::stoi(s);
        return true;
    };
    const size_t colon = text.find(':');
    int first = 0, end = count;
    if (colon == std::string::npos) {
        if (!number(text, first)) return bad();
        end = first + 1;
    } else {
        const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
        if ((!a.empty() && !number(a, first)) || (!b.empty() && !number(b, end)) || (a.empty() && b.empty()))
            return bad();
    }
    if (end > count && first < count)
        return core::makeError(
            fmt::format("--frames: '{}' reaches past the path's {} frames (0 to {})", text, count, count - 1));
    if (first >= count || first >= end)
        return core::makeError(
            fmt::format("--frames: '{}' selects no frame of the path's {} (0 to {})", text, count, count - 1));
    return std::pair{first, end};
}

} // namespace

void TimelineOptions::addTo(CLI::App& cmd, bool withFrames) {
    cmd.add_option("--path", path, "camera path: a name from data/paths (flythrough, orbit, day) or a .json file");
    if (withFrames)
        cmd.add_option("--frames", frames, "frames of the path to draw: a:b (a to b-1), a:, :b or a (default: all)");
    cmd.add_option("--time", time, "draw one moment, in seconds (movers, sun path and camera path at that time)");
    cmd.add_option(
        "--sun-path", sunPath,
        "the sun's motion: a path name or .json file with sun keys, or 'off' to hold the sun where it starts "
        "(default: the camera path's own sun keys, else the view's fixed sun)");
}

core::Result<Timeline> TimelineOptions::resolve() const {
    Timeline timeline;
    if (!path.empty()) {
        auto p = scene::findCameraPath(path, dataDirectory() / "paths");
        if (!p) return core::makeError("--path: " + p.error());
        timeline.path = std::move(p).value();
    }
    if (timeline.path) timeline.sunKeys = std::exchange(timeline.path->sun, {});
    if (!sunPath.empty() && sunPath != "off") {
        auto p = scene::findCameraPath(sunPath, dataDirectory() / "paths");
        if (!p) return core::makeError("--sun-path: " + p.error());
        if (p->sun.empty()) return core::makeError("--sun-path: " + sunPath + " has no \"sun\" keys");
        timeline.sunKeys = p->sun;
    }
    timeline.holdSun = sunPath == "off";
    if (time && !std::isfinite(*time)) return core::makeError("--time: must be a finite number of seconds");
    if (time && !frames.empty()) return core::makeError("--frames: cannot be combined with --time (one moment)");
    if (!frames.empty() && !timeline.path) return core::makeError("--frames: needs --path");
    if (time) {
        timeline.frames.push_back({0, *time});
        timeline.moment = true;
    } else if (timeline.path) {
        const scene::CameraPath& p = *timeline.path;
        int first = 0, end = p.frames;
        if (!frames.empty()) {
            auto range = parseFrameRange(frames, p.frames);
            if (!range) return range.errorInfo();
            std::tie(first, end) = *range;
        }
        for (int f = first; f < end; ++f) timeline.frames.push_back({f, p.timeOfFrame(f)});
        const double duration = p.endTime() - p.startTime();
        if (p.frames > 1 && duration > 0.0) timeline.framesPerSecond = (p.frames - 1) / duration;
    } else {
        timeline.frames.push_back({0, 0.0});
    }
    return timeline;
}

core::Result<scene::ResolvedView> Timeline::viewAt(const scene::ResolvedView& still, const scene::Scene& scene,
                                                   double t, bool stillSize) const {
    // Where the sun comes from, and when: held where it is at the path's start with `off`.
    const double sunTime = holdSun ? (path ? path->startTime() : 0.0) : t;
    core::DirectionalLight sun = still.light;
    std::optional<double> sunAngle = still.sunAngleDegrees; // the sun keys' size, else the view's
    if (!sunKeys.empty()) {
        const scene::SunKey key = scene::sunAt(sunKeys, sunTime);
        auto light = core::DirectionalLight::fromSunAngles(key.elevationDegrees, key.azimuthDegrees);
        if (!light) return core::makeError("--sun-path: " + light.error());
        sun = *light;
        if (key.angleDegrees) sunAngle = key.angleDegrees;
    }
    if (!path) {
        scene::ResolvedView view = still;
        view.light = sun;
        view.sunAngleDegrees = sunAngle;
        return view;
    }
    // --size takes the path's place before the camera is placed: a framed scene is fitted to
    // the picture's shape.
    scene::CameraPath sized = *path;
    if (stillSize) sized.width = still.width, sized.height = still.height;
    auto view = scene::viewAt(sized, scene, t, sun, still.pathFramedBox);
    if (!view) return core::makeError("--path: " + view.error());
    view->sunAngleDegrees = sunAngle;
    return view;
}

core::Status Timeline::prepareViews(scene::ResolvedView& still, scene::Scene& scene, bool stillSize,
                                    bool sayFraming) const {
    if (path) still.pathFramedBox = scene::framedOverPath(*path, scene, frames.front().time);
    bool framed = false;
    for (const TimedFrame& frame : frames) {
        auto view = viewAt(still, scene, frame.time, stillSize);
        if (!view) return view.errorInfo();
        framed = framed || (path && view->framed);
    }
    if (framed && sayFraming)
        fmt::print(stderr,
                   "--path {}: framing the loaded scene in every frame, from the compass direction and pitch of the "
                   "path's camera (it says \"on_loaded_scene\": \"frame\")\n",
                   path->name);
    return core::Ok{};
}

core::Result<std::string> frameFileName(const std::string& pattern, int frame) {
    const size_t percent = pattern.find('%');
    auto bad = [&] {
        return core::makeError("--out: a sequence needs one frame-number pattern such as frames/%04d.png, got '" +
                               pattern + "'");
    };
    if (percent == std::string::npos) return bad();
    size_t i = percent + 1;
    const bool zeros = i < pattern.size() && pattern[i] == '0';
    if (zeros) ++i;
    int width = 0;
    while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) && width < 100)
        width = width * 10 + (pattern[i++] - '0');
    if (i >= pattern.size() || pattern[i] != 'd' || pattern.find('%', i) != std::string::npos) return bad();
    std::string number = std::to_string(frame);
    if (int(number.size()) < width) number.insert(0, size_t(width) - number.size(), zeros ? '0' : ' ');
    return pattern.substr(0, percent) + number + pattern.substr(i + 1);
}

} // namespace shadowkit::app
