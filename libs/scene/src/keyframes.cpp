// Keyframed motion: glTF 2.0 §3.11 and Appendix C (keyframes.h says how).
#include "shadowkit/scene/keyframes.h"

#include "shadowkit/core/conventions.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {

namespace {

// The shorter-arc spherical interpolation of two unit quaternions (x, y, z, w).
glm::dvec4 slerpShorter(glm::dvec4 a, glm::dvec4 b, double s) {
    double cosine = glm::dot(a, b);
    if (cosine < 0.0) b = -b, cosine = -cosine;                        // q and −q are one rotation: take the nearer
    if (cosine > 1.0 - 1e-9) return glm::normalize(glm::mix(a, b, s)); // nearly equal: lerp is exact enough
    const double angle = std::acos(cosine);
    const double sine = std::sin(angle);
    return (std::sin((1.0 - s) * angle) / sine) * a + (std::sin(s * angle) / sine) * b;
}

glm::dvec4 unitOrIdentity(const glm::dvec4& q) {
    const double length = glm::length(q);
    return length > 0.0 && std::isfinite(length) ? q / length : glm::dvec4(0, 0, 0, 1);
}

} // namespace

glm::dvec4 KeyframeChannel::at(double t, bool rotation) const {
    SK_ASSERT(!times.empty(), "KeyframeChannel::at(): a channel has at least one key");
    const bool cubic = interpolation == Interpolation::CubicSpline;
    SK_ASSERT(values.size() == times.size() * (cubic ? 3 : 1), "KeyframeChannel::at(): a value per key");
    const auto value = [&](size_t k) { return values[cubic ? 3 * k + 1 : k]; };
    if (loopSeconds > 0.0) {
        t = std::fmod(t, loopSeconds);
        if (t < 0.0) t += loopSeconds;
    }
    if (!(t > times.front())) return rotation ? unitOrIdentity(value(0)) : value(0);
    if (!(t < times.back())) return rotation ? unitOrIdentity(value(times.size() - 1)) : value(times.size() - 1);
    // The last key at or before t; t lies strictly inside [times.front(), times.back()).
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double delta = times[k + 1] - times[k];
    const double s = delta > 0.0 ? (t - times[k]) / delta : 0.0;
    switch (interpolation) {
    case Interpolation::Step:
        return rotation ? unitOrIdentity(value(k)) : value(k);
    case Interpolation::Linear:
        return rotation ? slerpShorter(unitOrIdentity(value(k)), unitOrIdentity(value(k + 1)), s)
                        : glm::mix(value(k), value(k + 1), s);
    case Interpolation::CubicSpline: {
        const double s2 = s * s, s3 = s2 * s;
        const glm::dvec4 outTangent = values[3 * k + 2], inTangent = values[3 * (k + 1)];
        const glm::dvec4 v = (2 * s3 - 3 * s2 + 1) * value(k) + delta * (s3 - 2 * s2 + s) * outTangent +
                             (-2 * s3 + 3 * s2) * value(k + 1) + delta * (s3 - s2) * inTangent;
        return rotation ? unitOrIdentity(v) : v;
    }
    }
    return value(k);
}

glm::dmat4 MotionNode::parentFromNodeAt(double t) const {
    if (fixed) return *fixed;
    const glm::dvec3 position = translationKeys ? glm::dvec3(translationKeys->at(t, false)) : translation;
    glm::dquat turn = rotation;
    if (rotationKeys) {
        const glm::dvec4 q = rotationKeys->at(t, true);
        turn = glm::dquat(q.w, q.x, q.y, q.z);
    }
    const glm::dvec3 size = scaleKeys ? glm::dvec3(scaleKeys->at(t, false)) : scale;
    return glm::scale(glm::translate(glm::dmat4(1.0), position) * glm::mat4_cast(turn), size);
}

glm::dmat4 NodeMotion::sceneFromObjectAt(double t) const {
    glm::dmat4 m = sceneFromRoot;
    for (const MotionNode& node : chain) m *= node.parentFromNodeAt(t);
    return m * nodeFromObject;
}

} // namespace shadowkit::scene
