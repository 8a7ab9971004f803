// The temporal protocol of a sequence, once: each frame drawn through the frame driver and
// measured against its truth, then compared with the previous frame's shadows at this frame's
// surface points — the casters moved back where they stood, the previous frame's set-up and
// sun drawn from this camera (Measurer::shadowsAt) — for flicker (eval::compareFrames); and, with
// MeasureOptions::levelPops, with the levels of detail the previous camera chose (eval::levelPops).
// `shadowkit eval --path`, Python and the temporal tests measure sequences through it.
#pragma once

#include "shadowkit/eval/temporal.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene.h"

#include <optional>
#include <vector>

namespace shadowkit::measure {

struct PathFrame {
    frame::PreparedFrame frame;
    Measurement measurement;
    std::optional<eval::TemporalFigures> temporal; // none on the first frame
};

class PathMeasurer {
public:
    // `world` is the scene `measurer` was created with; its movers are animated here. The
    // driver holds what persists from frame to frame (held lattices, auto's tracking).
    PathMeasurer(Measurer& measurer, scene::Scene& world, frame::FrameDriver& driver)
        : m_measurer(measurer), m_world(world), m_driver(driver) {}

    // The frame at `time` seen as `view` (a camera path's view at that time): the movers
    // placed at `time`, the frame prepared and measured, and after the first frame its
    // temporal figures against the previous one. Times may go backwards (any frame is a
    // function of its time alone).
    core::Result<PathFrame> next(double time, const scene::ResolvedView& view, const MeasureOptions& options = {});

    // Forget the previous frame (a cut): the next frame has no temporal figures.
    void reset() { m_previous.reset(); }

private:
    core::Status animateTo(double time);

    struct Previous {
        double time = 0.0;
        eval::ShadowStates states;
        core::ShadowSetup setup;
        core::DirectionalLight light;
        gl::RenderSettings settings;
        core::PerspectiveCamera camera;
    };
    Measurer& m_measurer;
    scene::Scene& m_world;
    frame::FrameDriver& m_driver;
    std::optional<Previous> m_previous;
    std::vector<uint32_t> m_moved;
};

} // namespace shadowkit::measure
