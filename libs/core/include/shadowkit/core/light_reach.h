// How far a local light reaches when an engine gives it a fall-off rather than a range.
//
// The fixed-function pipelines' attenuation — OpenGL's lighting equations (the compatibility
// profile's), Direct3D 9's, and with them OpenSceneGraph's osg::Light and OGRE's
// Light::setAttenuation — scales a local light's colour at distance d by
//
//     a(d) = 1 / (kc + kl·d + kq·d²),
//
// which never reaches zero. A shadow map over "everything the light reaches" then spans the
// whole scene; engines that ask for a range instead (OGRE's, Unreal's attenuation radius) cut
// the light where it no longer shows. This does that for the rest: the light reaches d while
// its brightest channel, times a(d), lights a white surface facing it by at least `cutoff` of
// full white — by default 1/256, one step of an 8-bit channel. Solved in closed form: kq·d² +
// kl·d + kc = I / cutoff.
#pragma once

#include "shadowkit/core/result.h"

namespace shadowkit::core {

/// A light's fall-off: it lights at distance d with its colour times 1 / (constant + linear·d
/// + quadratic·d²) (OpenGL's and OSG's defaults: 1, 0, 0 — no fall-off).
struct Attenuation {
    double constant = 1.0;  ///< kc: the light's colour divided by it at the light itself
    double linear = 0.0;    ///< kl, per metre
    double quadratic = 0.0; ///< kq, per square metre
};

/// One step of an 8-bit channel: below it a light no longer shows in an 8-bit frame.
inline constexpr double kDefaultReachCutoff = 1.0 / 256.0;

/// The cutoff in (0, 1), the fraction of full white below which a light is taken not to reach;
/// the error's field is "reach.cutoff".
Status validateReachCutoff(double cutoff);

/// The distance beyond which a light of brightest channel `intensity` (its colour's largest
/// component, ≥ 0) with this attenuation lights a white surface facing it by less than
/// `cutoff`: infinity where it never falls that far (no linear or quadratic term), 0 where it
/// never lights that much (intensity 0, or a constant term above intensity / cutoff). Fails
/// in one line for a negative or non-finite coefficient (fields "attenuation.constant",
/// "attenuation.linear", "attenuation.quadratic"), a negative or non-finite intensity
/// ("light.intensity"), a bad cutoff, or a light brighter than infinitely close (all three
/// coefficients 0).
Result<double> attenuationReach(const Attenuation& attenuation, double intensity, double cutoff = kDefaultReachCutoff);

/// The attenuation (constant 1, linear 0) of a light of brightest channel `intensity` whose
/// reach at `cutoff` is `range` metres: how an application gives an engine with attenuation
/// alone a light of a given range. Precondition: range > 0 and finite, intensity / cutoff > 1.
Attenuation quadraticAttenuationReaching(double range, double intensity, double cutoff = kDefaultReachCutoff);

} // namespace shadowkit::core
