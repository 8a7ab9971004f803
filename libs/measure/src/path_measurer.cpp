#include "shadowkit/measure/path_measurer.h"

#include "shadowkit/scene/animation.h"

namespace shadowkit::measure {

core::Status PathMeasurer::animateTo(double time) {
    m_moved.clear();
    scene::animate(m_world, time, &m_moved);
    return m_measurer.moveInstances(m_world, m_moved);
}

core::Result<PathFrame> PathMeasurer::next(double time, const scene::ResolvedView& view,
                                           const MeasureOptions& options) {
    if (auto s = animateTo(time); !s) return s.errorInfo();
    auto prepared = m_driver.prepare(m_measurer.renderer(), view);
    if (!prepared) return prepared.errorInfo();
    auto measured = m_measurer.measure(*prepared, options);
    if (!measured) return measured.errorInfo();
    PathFrame out{std::move(prepared).value(), std::move(measured).value(), std::nullopt};
    eval::ShadowStates states = eval::shadowStates(view.camera, *out.measurement.truth, out.measurement.comparison);
    if (m_previous) {
        // The previous frame's shadows at this frame's points: its casters, light and set-up.
        const bool castersMoved = m_world.animated() && m_previous->time != time;
        if (castersMoved)
            if (auto s = animateTo(m_previous->time); !s) return s.errorInfo();
        const bool sameLight = m_previous->light.wsDirection == view.light.wsDirection;
        auto before = m_measurer.shadowsAt(out.measurement, view.camera, m_previous->setup, m_previous->light,
                                           m_previous->settings, !castersMoved && sameLight);
        if (!before) return before.errorInfo();
        // A deformed mesh's own pixels have no "same point" in the frame before (temporal.h).
        std::vector<uint32_t> reshaped;
        if (m_previous->time != time)
            for (const scene::MeshDeformation& deformation : m_world.deformations)
                for (uint32_t i = 0; i < m_world.batches[deformation.batch].worldFromObject.size(); ++i)
                    reshaped.push_back(m_world.globalIndex({deformation.batch, i}));
        out.temporal = eval::compareFrames(m_previous->states, states, *before, {}, reshaped);
        if (options.levelPops) {
            // This frame again, at this frame's places, with the levels the previous camera chose.
            if (castersMoved)
                if (auto s = animateTo(time); !s) return s.errorInfo();
            gl::RenderSettings settings = out.frame.settings;
            settings.lodCamera = m_previous->camera;
            auto previousLevels =
                m_measurer.renderer().renderEvalBuffers(view.camera, view.light, out.measurement.setup, settings);
            if (!previousLevels) return previousLevels.errorInfo();
            out.temporal->levelPops = eval::levelPops(out.measurement.raster, *previousLevels);
        }
    }
    m_previous = Previous{time, std::move(states), out.measurement.setup, view.light, out.frame.settings, view.camera};
    return out;
}

} // namespace shadowkit::measure
