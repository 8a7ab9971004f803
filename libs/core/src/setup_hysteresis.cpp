#include "shadowkit/core/setup_hysteresis.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {

Status validate(const HysteresisOptions& o) {
    if (!(o.radiusMetres > 0.0 && std::isfinite(o.radiusMetres))) return fieldError("hysteresis.radius", "must be > 0 metres");
    if (!(o.turnDegrees >= 0.0 && o.turnDegrees <= 45.0)) return fieldError("hysteresis.turn", "must be in [0, 45] degrees");
    return Ok{};
}

PerspectiveCamera enclosingCamera(const PerspectiveCamera& camera, const HysteresisOptions& options) {
    const double tanY = std::tan(0.5 * glm::radians(camera.fovYDegrees)), tanX = camera.aspect * tanY;
    const Vec3 forward = glm::normalize(camera.wsDirection);
    const Vec3 right = glm::normalize(glm::cross(forward, camera.wsUp));
    const Vec3 up = glm::cross(right, forward);
    // How wide must the view be to hold every turned camera? Turning a pyramid widens it by
    // more than the turn at its corners (pitching it down swings a corner sideways too), so
    // the corner rays of cameras turned by α (and α/2) all round are measured in this frame,
    // with their own right and up vectors, and the widest taken (0.1 % spare for the sampling).
    const double turn = glm::radians(options.turnDegrees);
    double wideX = tanX, wideY = tanY;
    for (const double angle : {0.5 * turn, turn})
        for (int k = 0; k < 72; ++k) {
            const double phi = 2.0 * 3.14159265358979323846 * k / 72.0;
            const Vec3 axis = std::cos(phi) * right + std::sin(phi) * up; // ⟂ forward
            const Vec3 d = forward * std::cos(angle) + glm::cross(axis, forward) * std::sin(angle);
            const Vec3 r = glm::cross(d, camera.wsUp);
            if (!(glm::length(r) > 1e-9)) continue;
            const Vec3 rn = glm::normalize(r), un = glm::cross(rn, d);
            for (const double sx : {-1.0, 1.0})
                for (const double sy : {-1.0, 1.0}) {
                    const Vec3 corner = d + sx * tanX * rn + sy * tanY * un;
                    const double along = glm::dot(corner, forward);
                    if (!(along > 1e-9)) continue;
                    wideX = std::max(wideX, std::abs(glm::dot(corner, right)) / along);
                    wideY = std::max(wideY, std::abs(glm::dot(corner, up)) / along);
                }
        }
    wideX *= 1.001, wideY *= 1.001;
    // Back far enough that the ball of radius r round the eye is inside: every face plane
    // (half-angle atan(wide)) is b · sin(half-angle) from the axis point b behind the eye.
    const double back = options.radiusMetres / std::sin(std::atan(std::min(wideX, wideY)));
    PerspectiveCamera out = camera;
    out.wsEye = camera.wsEye - back * forward;
    out.fovYDegrees = std::min(glm::degrees(2.0 * std::atan(wideY)), 179.0);
    out.aspect = wideX / std::tan(0.5 * glm::radians(out.fovYDegrees));
    // The far plane beyond every other frustum's farthest corner; the near plane no farther
    // than the nearest a real eye can be.
    out.zFar = back + options.radiusMetres + camera.zFar * std::sqrt(1.0 + tanX * tanX + tanY * tanY);
    out.zNear = std::min(camera.zNear, std::max(back - options.radiusMetres, 1e-3 * camera.zNear));
    return out;
}

bool SetupHysteresis::holds(const ShadowSetupInputs& in) const {
    if (!m_fit) return false;
    const ShadowSetupInputs& was = m_fit->inputs;
    const PerspectiveCamera &c = in.camera, &f = was.camera;
    if (in.light.wsDirection != was.light.wsDirection || in.technique != was.technique || in.mapSize != was.mapSize ||
        c.fovYDegrees != f.fovYDegrees || c.aspect != f.aspect || c.zNear != f.zNear || c.zFar != f.zFar)
        return false;
    // The scene may only have shrunk: a caster beyond the fitted bounds could be missed.
    const Aabb& b = in.wsSceneBounds;
    if (!b.isEmpty() && !(was.wsSceneBounds.contains(b.min) && was.wsSceneBounds.contains(b.max))) return false;
    if (glm::distance(c.wsEye, f.wsEye) > m_options.radiusMetres) return false;
    const double cosTurn = glm::dot(glm::normalize(c.wsDirection), glm::normalize(f.wsDirection));
    return cosTurn >= std::cos(glm::radians(m_options.turnDegrees));
}

Result<ShadowSetup> SetupHysteresis::next(const ShadowSetupInputs& inputs) {
    if (auto s = validate(m_options); !s) return s.errorInfo();
    m_refitted = !holds(inputs);
    if (!m_refitted) return m_fit->setup;
    ShadowSetupInputs enclosing = inputs;
    enclosing.camera = enclosingCamera(inputs.camera, m_options);
    auto setup = computeShadowSetup(enclosing);
    if (!setup) return setup;
    m_fit = Fit{inputs, *setup};
    return setup;
}

} // namespace shadowkit::core
