// Error-driven parameters along a camera path: chooseAuto's search (error_driven.h) spread over
// the frames, so that a frame costs a few set-ups instead of dozens.
//
// chooseAuto searches every candidate's parameter from scratch: about 50 set-ups for one map and
// 150 over every split count, 2-40 ms a frame. Along a path the camera moves a little each frame
// and every candidate's optimum moves with it, so the optima can be tracked rather than found
// again: last frame's answer is this frame's best guess, the temporal coherence coherent
// hierarchical culling builds on (Bittner et al. 2004) applied to parameters.
//
// The first frame (and the first after reset()) runs the full search over every receiver and
// keeps each candidate's parameters. Every later frame, over at most AutoOptions::searchSamples
// receivers spread evenly over the read-back:
//   1. the chosen candidate takes one step of an adaptive pattern search along its parameter
//      axis (error_driven.h's ParameterAxis): predicted at its parameter and at a probe one
//      `step` away on the side that last helped; a better probe is kept and the step grows by
//      half, a worse one turns the side and halves the step (LiSPSM probes its other warp axis,
//      cross product or middle vector, every other step instead);
//   2. one other candidate, in turn, takes the same step;
//   3. that candidate replaces the chosen one when its objective beats the chosen one's by
//      AutoOptions::hysteresis.
// A frame thus costs four set-ups and predictions however many candidates the budget allows,
// and a better family is noticed within as many frames as there are candidates (at most ten).
#pragma once

#include "shadowkit/core/error_driven.h"

#include <span>
#include <vector>

namespace shadowkit::core {

/// `--technique auto` along a path: the full search on the first frame, then one tracked step a frame, with hysteresis.
class AutoChooser {
public:
    /// A chooser with these options; the first choose() runs the full search.
    explicit AutoChooser(AutoOptions options) : m_options(options) {}

    /// This frame's choice for `base`'s camera, light and scene box, from the receivers the
    /// camera sees as a width × height image (receiverSamples). Without receivers: the last
    /// choice for this frame, or on the first frame what chooseAuto gives for none. Fails for
    /// invalid options, inputs or image size. Deterministic for the same sequence of calls.
    Result<ParameterChoice> choose(const ShadowSetupInputs& base, int width, int height,
                                   std::span<const ReceiverSample> receivers);

    /// Forget the tracked parameters: the next call searches in full (a cut in the camera path).
    void reset() { m_tracks.clear(); }
    /// The number of candidates tracked (0 before the first search).
    size_t candidates() const { return m_tracks.size(); }
    /// The options it was made with.
    const AutoOptions& options() const { return m_options; }

private:
    struct Track {
        ShadowSetupInputs inputs;
        double step = 0.0; ///< along the parameter axis
        double side = 1.0; ///< +1 or -1: where the next probe goes
        int steps = 0;
    };
    struct Step {
        double objective;
        ShadowSetupInputs inputs;
        std::optional<ShadowSetup> setup;
    };
    Step step(Track& track, const ShadowSetupInputs& base, const SamplingErrorModel& model, int& setups) const;

    AutoOptions m_options;
    std::vector<Track> m_tracks;
    size_t m_chosen = 0, m_nextProbe = 0;
};

} // namespace shadowkit::core
