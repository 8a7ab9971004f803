// What `shadowkit eval` keeps between evaluations when it serves several (--serve, used by
// shadowkit sweep): the scene and the measurer — its GL context, compiled programs, BVHs and
// the truths it caches per camera, sun and image size — reused while the scene's options and
// moment stay the same, so a sweep's worker builds them once, not once a cell.
#pragma once

#include "options.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene.h"

#include <memory>
#include <string>

namespace shadowkit::app {

class EvalSession {
public:
    // The scene of `options` with its movers where they are at `time`, and a measurer over it:
    // the kept ones when they were made for the same options and time, else built (printing what
    // was built, as a single evaluation does).
    core::Status prepare(const SceneOptions& options, double time);
    scene::Scene& scene() { return *m_scene; }
    measure::Measurer& measurer() { return *m_measurer; }
    // Forget everything (after a failed evaluation, whose GL state is not to be trusted).
    void reset();

private:
    std::string m_key;
    std::unique_ptr<scene::Scene> m_scene; // its address is the measurer's: kept stable
    std::unique_ptr<measure::Measurer> m_measurer;
};

// shadowkit eval --serve: reads one JSON array of eval arguments per line on stdin, runs each as
// `shadowkit eval ARGS` would run (its table on stdout, errors on stderr) with one session, and
// after each prints a line "shadowkit-serve: exit CODE" on stdout. Returns at the end of input.
int serveEvaluations();

} // namespace shadowkit::app
