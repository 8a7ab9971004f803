// Error-driven parameters along a camera path (auto_chooser.h): each candidate's optimum tracked
// from frame to frame by one step of an adaptive pattern search.
#include "shadowkit/core/auto_chooser.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowkit::core {

namespace {

// Steps along an axis as fractions of its length: the first is a grid step of the full search
// halved; the smallest is finer than the full search's golden section ends (1/72 of the axis);
// the largest crosses a quarter of it in one frame.
constexpr double kFirstStep = 1.0 / 16.0, kSmallestStep = 1.0 / 256.0, kLargestStep = 1.0 / 4.0;
constexpr double kGrow = 1.5, kShrink = 0.5;

LispsmDirection otherDirection(LispsmDirection d) {
    return d == LispsmDirection::CrossProduct ? LispsmDirection::MiddleVector : LispsmDirection::CrossProduct;
}

// Every k-th receiver, at most `count` of them.
std::vector<ReceiverSample> spreadEvenly(std::span<const ReceiverSample> receivers, size_t count) {
    count = std::min(count, receivers.size());
    std::vector<ReceiverSample> out;
    out.reserve(count);
    for (size_t k = 0; k < count; ++k) out.push_back(receivers[k * receivers.size() / count]);
    return out;
}

} // namespace

AutoChooser::Step AutoChooser::step(Track& track, const ShadowSetupInputs& base, const SamplingErrorModel& model,
                                    int& setups) const {
    auto predicted = [&](const ShadowSetupInputs& in) {
        ++setups;
        Step s{std::numeric_limits<double>::infinity(), in, std::nullopt};
        if (auto setup = computeShadowSetup(in)) {
            s.objective = model.objective(*setup);
            s.setup = std::move(setup).value();
        }
        return s;
    };
    Step here = predicted(forThisFrame(track.inputs, base, model));
    const std::optional<ParameterAxis> axis = parameterAxis(here.inputs.technique);
    const bool probeDirection = here.inputs.technique == Technique::Lispsm && track.steps % 2 == 1;
    ++track.steps;
    std::optional<ShadowSetupInputs> probe;
    if (probeDirection) {
        probe = here.inputs;
        probe->lispsm.direction = otherDirection(probe->lispsm.direction);
    } else if (axis) {
        const double x = axis->get(here.inputs);
        const double to = std::clamp(x + track.side * track.step * (axis->hi - axis->lo), axis->lo, axis->hi);
        if (to != x) {
            probe = here.inputs;
            axis->set(*probe, to);
        } else {
            track.side = -track.side; // at the end of the axis: look the other way next time
        }
    }
    if (probe) {
        Step there = predicted(*probe);
        const bool better = there.objective < here.objective;
        if (!probeDirection) {
            track.step = std::clamp(track.step * (better ? kGrow : kShrink), kSmallestStep, kLargestStep);
            if (!better) track.side = -track.side;
        }
        if (better) here = std::move(there);
    }
    track.inputs = here.inputs;
    return here;
}

Result<ParameterChoice> AutoChooser::choose(const ShadowSetupInputs& base, int width, int height,
                                            std::span<const ReceiverSample> receivers) {
    if (auto s = validate(m_options); !s) return s.errorInfo();
    if (auto s = validate(base); !s) return s.errorInfo();
    if (m_tracks.empty() || receivers.empty()) {
        // The first frame, or nothing seen: the full search (or its answer for no samples).
        auto model = SamplingErrorModel::create(base.camera, width, height, receivers);
        if (!model) return model.errorInfo();
        if (!m_tracks.empty()) {
            // Nothing to judge by this frame: keep the choice.
            return ParameterChoice{forThisFrame(m_tracks[m_chosen].inputs, base, *model), {}, 0.0, 0};
        }
        if (model->size() == 0) return chooseAuto(base, m_options, *model);
        auto ranked = rankCandidates(base, m_options, *model);
        if (!ranked) return ranked.errorInfo();
        int setups = 0;
        for (const ParameterChoice& c : *ranked) {
            m_tracks.push_back({c.inputs, kFirstStep, 1.0, 0});
            setups += c.setupsTried;
        }
        m_chosen = 0;
        m_nextProbe = 0;
        ParameterChoice best = ranked->front();
        best.setupsTried = setups;
        return best;
    }
    auto model =
        SamplingErrorModel::create(base.camera, width, height, spreadEvenly(receivers, m_options.searchSamples));
    if (!model) return model.errorInfo();
    int setups = 0;
    Step chosen = step(m_tracks[m_chosen], base, *model, setups);
    if (m_tracks.size() > 1) {
        m_nextProbe = (m_nextProbe + 1) % m_tracks.size();
        if (m_nextProbe == m_chosen) m_nextProbe = (m_nextProbe + 1) % m_tracks.size();
        Step other = step(m_tracks[m_nextProbe], base, *model, setups);
        if (other.objective < (1.0 - m_options.hysteresis) * chosen.objective) {
            m_chosen = m_nextProbe;
            chosen = std::move(other);
        }
    }
    ParameterChoice out{chosen.inputs, {}, chosen.objective, setups};
    if (chosen.setup) out.predicted = model->figures(*chosen.setup);
    return out;
}

} // namespace shadowkit::core
