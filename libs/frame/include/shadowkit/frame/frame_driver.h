// One frame, written once. FrameDriver::prepare runs the phases a frame needs before its
// shadow passes, in GPU order, and FrameDriver::draw draws it:
//
//   1. the view's spot and point lights set up for its camera (Renderer::setLocalLights)
//   2. --visible-depth auto: the visible view-depth range — from auto's read-back when auto is
//      on (one submission for both), else a camera depth pre-pass (8 bytes read back)
//   3. --technique auto: receivers read back at a low resolution, the family and parameters
//      chosen or tracked (core::AutoChooser), the bias re-resolved for the choice
//   4. the set-up: held lattices (core::SetupHysteresis) or computed afresh
//   5. draw: culling (CHC++'s pre-pass, receiver masks), shadow passes, main pass — for
//      virtual maps: pre-pass, page marking and allocation, the new pages, main pass
//      — or, in libs/measure, the evaluation buffers and the truth instead of step 5.
//
// What persists between frames lives here: the hysteresis and auto's tracked candidates
// (the renderer keeps CHC++'s state). Every front end — `render`, `eval`, `eval --path`,
// `compare`, `bench`, the viewer, Python — draws its frames through one of these.
#pragma once

#include "shadowkit/core/auto_chooser.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/setup_hysteresis.h"
#include "shadowkit/frame/frame_config.h"
#include "shadowkit/gl/receiver_samples.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/views.h"

#include <optional>
#include <vector>

namespace shadowkit::frame {

// GPU work a frame asked for before its own passes, and what it read back (the cost of
// steps 2 and 3 above; the frame's own culling pre-pass is counted in gl::FrameStats).
struct PrePasses {
    int submissions = 0;       // camera pre-passes and receiver read-back renders
    int readBacks = 0;         // GPU → CPU transfers waited for
    double milliseconds = 0.0; // wall-clock, the GPU's work and the waits included
};

// A frame ready for its shadow passes: what it is drawn with, after steps 1–4.
struct PreparedFrame {
    scene::ResolvedView view;
    core::ShadowSetupInputs inputs; // as the set-up took them: visible depth measured, auto's choice
    core::ShadowSetup setup;
    gl::RenderSettings settings; // the view's size, fog and sun; the bias resolved for the technique
    std::optional<core::ParameterChoice> autoChoice;     // --technique auto: what it chose
    double autoMilliseconds = 0.0;                       // CPU: auto's model and search (not the read-back)
    double setupMilliseconds = 0.0;                      // CPU: step 4
    std::optional<core::SetupHysteresis::Refits> refits; // held lattices: views refitted this frame
    PrePasses prePasses;
};

struct DrawnFrame {
    PreparedFrame frame;
    gl::FrameStats stats;
    double milliseconds = 0.0; // wall-clock of step 5 (Renderer::render), its culling included
};

class FrameDriver {
public:
    // Fails, naming the field, for a configuration FrameConfig::check refuses.
    static core::Result<FrameDriver> create(FrameConfig config);

    // Steps 1–4 for `view` with `renderer` (whose scene box bounds the set-up).
    core::Result<PreparedFrame> prepare(gl::Renderer& renderer, const scene::ResolvedView& view);
    // Steps 1–5: the frame drawn into the renderer's colour target (Renderer::readColor).
    core::Result<DrawnFrame> draw(gl::Renderer& renderer, const scene::ResolvedView& view);

    // A cut: the next frame starts afresh (lattices refitted, auto's full search). Changing
    // the configuration does the same; moving the camera does not.
    void reset();
    // The configuration, to change it: a new configuration is a cut.
    const FrameConfig& config() const { return m_config; }
    core::Status setConfig(FrameConfig config);

private:
    explicit FrameDriver(FrameConfig config);

    FrameConfig m_config;
    std::optional<core::SetupHysteresis> m_hysteresis;
    std::optional<core::AutoChooser> m_chooser;
};

// What `inputs`' camera sees, read back at the sampling's low resolution (gl::readReceivers;
// no shadow pass is drawn, the set-up it checks is a `standard` map of 64² texels): auto's
// receivers and, with it, the visible depth range (steps 2–3).
core::Result<core::RasterBuffers> readReceivers(gl::Renderer& renderer, const core::ShadowSetupInputs& inputs,
                                                const gl::RenderSettings& settings,
                                                const gl::ReceiverSampling& sampling = {});
// core::receiverSamples of those: what auto's choice is made from, and `analyze --candidates`.
core::Result<std::vector<core::ReceiverSample>> sampleReceivers(gl::Renderer& renderer,
                                                                const core::ShadowSetupInputs& inputs,
                                                                const gl::RenderSettings& settings,
                                                                const gl::ReceiverSampling& sampling = {});

} // namespace shadowkit::frame
