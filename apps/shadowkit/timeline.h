// Time in the command line: --path (a camera path), --frames a:b (which of its frames),
// --time T (one moment), --sun-path NAME|FILE|off; and --out patterns for sequences.
// Resolves them into the frames to draw and the view at each frame's time.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/camera_path.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/scene/views.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace shadowkit::app {

struct TimedFrame {
    int number = 0;    // frame of the path (0 without one)
    double time = 0.0; // seconds
};

struct Timeline {
    std::optional<scene::CameraPath> path; // its camera keys (its sun keys moved to sunKeys)
    std::vector<scene::SunKey> sunKeys;    // --sun-path's, else the path's own; empty: the view's sun
    bool holdSun = false;                  // --sun-path off
    std::vector<TimedFrame> frames;        // what to draw, in order
    double framesPerSecond = 30.0;         // of the path (for videos)

    bool moment = false; // --time: one moment, not a numbered frame of the path

    bool isSequence() const { return path.has_value() && frames.size() > 1; }
    // Whether each frame drawn is a frame of the path, with its number (not --time's moment).
    bool framesNumbered() const { return path.has_value() && !moment; }
    // The view at time t: the path's camera (else `still`, the --view), the sun from
    // --sun-path, else the path's own sun keys, else `still`'s (its size likewise: the keys'
    // "angle" where they give one, else `still`'s); `off` holds the sun where it is at the path's start. `stillSize`:
    // the image size is `still`'s (--size given), not the path's.
    core::Result<scene::ResolvedView> viewAt(const scene::ResolvedView& still, const scene::Scene& scene, double t,
                                             bool stillSize = false) const;
    // Before any frame is drawn: where the path frames a loaded scene, the box it frames in every
    // frame, into still.pathFramedBox (scene::framedOverPath: `scene` animated to the path's
    // frames and left at the first drawn); then every frame's view, so that a path whose eye meets
    // its target between two keys fails now, naming the moment, rather than frames (or a ray
    // tracer's build) into the run. Says on stderr (`sayFraming`) when the path frames a loaded
    // scene rather than following its keys.
    core::Status prepareViews(scene::ResolvedView& still, scene::Scene& scene, bool stillSize = false,
                              bool sayFraming = true) const;
};

struct TimelineOptions {
    std::string path, frames, sunPath;
    std::optional<double> time;

    // withFrames false: without --frames (the viewer plays the path instead).
    void addTo(CLI::App& cmd, bool withFrames = true);
    // Loads the paths and lists the frames; errors name the flag.
    core::Result<Timeline> resolve() const;
};

// `pattern` with its one printf-style frame number (%d, %4d, %04d) replaced by `frame`;
// fails, naming --out, when there is not exactly one.
core::Result<std::string> frameFileName(const std::string& pattern, int frame);

} // namespace shadowkit::app
