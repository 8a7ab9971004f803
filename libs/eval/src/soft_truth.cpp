// The fraction of the sun's disk, or of a sphere light, each point sees (soft_truth.h). The
// radiance is taken uniform over the disk (no limb darkening), so the visible fraction of its
// solid angle is the visible fraction of its light. Sampling: stratified jittered k × k over the unit square, Shirley
// and Chiu's concentric map to the disk (strata stay compact, so stratification keeps lowering the variance at a
// penumbra's straight edge), radius² as the fraction of the cap's solid angle.
#include "shadowkit/eval/soft_truth.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

namespace shadowkit::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A small counter-based generator (SplitMix64): the jitter of point i's sample j depends only on
// (seed, i, j), so the result does not depend on how TBB splits the work.
double uniform(uint64_t seed, uint64_t point, uint64_t sample) {
    uint64_t z = seed * 0x9E3779B97F4A7C15ull + point * 0xD1B54A32D192ED03ull + sample * 0xABC98388FB8FAC03ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
}

constexpr int kRing = 8; // probe rays on the disk's rim

int side(int count) { return std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))))); }

// The light as a point sees it: a cone of directions round `axis`, and how far a ray towards
// the light along a direction may go before it has reached the light.
struct LightCone {
    core::Vec3 axis;  // unit, towards the light's centre
    double halfAngle; // radians; 0 a point
    // Towards a sphere: its centre relative to the ray's origin, and its radius; the sun: none.
    core::Vec3 toCentre{0.0};
    double radius = -1.0;

    // The segment of a shadow ray along `direction` that must be free: up to the sphere's near
    // surface (b − √(R² − |c − b ω|²), b = c · ω), or to infinity for the sun.
    Ray ray(const core::Vec3& origin, const core::Vec3& direction) const {
        if (radius < 0.0) return {origin, direction, 0.0, std::numeric_limits<double>::infinity()};
        const double b = glm::dot(toCentre, direction);
        const core::Vec3 offAxis = toCentre - b * direction;
        return {origin, direction, 0.0, b - std::sqrt(std::max(radius * radius - glm::dot(offAxis, offAxis), 0.0))};
    }
};

// Counts the visible rays from `origin` of a set of directions over the light's cone, eight at a
// time through the packet kernels; `directionOf(j)` gives ray j of `count`.
template <class DirectionOf>
int visibleRays(const RayScene& rays, const core::Vec3& origin, const LightCone& cone, int count,
                DirectionOf directionOf) {
    std::array<Ray, 8> batch;
    std::array<uint8_t, 8> occluded;
    int visible = 0;
    size_t filled = 0;
    const auto flush = [&] {
        rays.occluded(std::span(batch.data(), filled), std::span(occluded.data(), filled));
        for (size_t i = 0; i < filled; ++i) visible += !occluded[i];
        filled = 0;
    };
    for (int j = 0; j < count; ++j) {
        batch[filled++] = cone.ray(origin, directionOf(j));
        if (filled == batch.size()) flush();
    }
    flush();
    return visible;
}

// Jittered stratum j of a k × k set, (u, v) in [0, 1)², from random stream `stream`.
std::pair<double, double> stratum(int j, int k, uint64_t seed, uint64_t point, uint64_t stream) {
    const uint64_t r = stream + 2 * static_cast<uint64_t>(j);
    return {(j % k + uniform(seed, point, r)) / k, (j / k + uniform(seed, point, r + 1)) / k};
}

// The unit vector at polar angle θ from `axis` (given as 1 - cos θ, exact for tiny angles) and
// azimuth φ (its cosine and sine) in a frame round the axis.
core::Vec3 aroundAxis(const core::Vec3& axis, double oneMinusCos, double cosPhi, double sinPhi) {
    const double cosTheta = 1.0 - oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
    // An orthonormal frame round the axis (Duff et al. 2017's branchless construction).
    const double sign = std::copysign(1.0, axis.z);
    const double p = -1.0 / (sign + axis.z), q = axis.x * axis.y * p;
    const core::Vec3 t(1.0 + sign * axis.x * axis.x * p, sign * q, -sign * axis.x);
    const core::Vec3 b(q, sign + axis.y * axis.y * p, -axis.y);
    return glm::normalize(cosTheta * axis + sinTheta * (cosPhi * t + sinPhi * b));
}

// On the disk's rim, at azimuth φ.
core::Vec3 rimDirection(const core::Vec3& axis, double halfAngle, double phi) {
    const double s = std::sin(0.5 * halfAngle);
    return aroundAxis(axis, 2.0 * s * s, std::cos(phi), std::sin(phi));
}

} // namespace

core::Vec3 coneDirection(const core::Vec3& axis, double halfAngle, double u, double v) {
    // Concentric map (Shirley & Chiu 1997): the square [-1, 1]² onto the unit disk.
    const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
    double r = 0.0, phi = 0.0;
    if (a != 0.0 || b != 0.0) {
        if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = (kPi / 4.0) * (b / a);
        } else {
            r = b;
            phi = kPi / 2.0 - (kPi / 4.0) * (a / b);
        }
    }
    // Uniform in solid angle: 1 - cos θ = r² (1 - cos α), written with sin² (no cancellation).
    // The disk point is (r cos φ, r sin φ) with r of either sign: its azimuth keeps r's sign.
    const double s = std::sin(0.5 * halfAngle);
    const double along = r < 0.0 ? -1.0 : 1.0;
    return aroundAxis(axis, r * r * 2.0 * s * s, along * std::cos(phi), along * std::sin(phi));
}

namespace {

// The soft truth at every point of `hits` that `coneAt(i, origin)` gives a light cone for
// (std::nullopt: not lit by this light at all, NaN); the rest as computeSoftTruth says.
template <class ConeAt>
SoftTruth softTruth(const RayScene& rays, const TruthBuffers& hits, const SoftTruthOptions& options, ConeAt coneAt) {
    const auto start = std::chrono::steady_clock::now();
    SoftTruth out;
    out.width = hits.width, out.height = hits.height;
    const size_t n = hits.surfaceId.size();
    out.visibility.assign(n, std::numeric_limits<float>::quiet_NaN());
    out.standardError.assign(n, 0.0f);
    const double offset = rays.shadowRayOffset(options.normalOffsetFraction);
    const int probeSide = side(options.probes);
    const int sampleSide = std::max(side(options.samples), probeSide);
    std::atomic<uint64_t> traced{0}, penumbra{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& range) {
        uint64_t myRays = 0, myPenumbra = 0;
        for (size_t i = range.begin(); i < range.end(); ++i) {
            if (hits.surfaceId[i] == 0) continue;
            const core::Vec3 normal(hits.wsNormal[i]);
            const core::Vec3 origin = hits.wsPosition[i] + offset * normal;
            const std::optional<LightCone> cone = coneAt(i, normal, origin);
            if (!cone) continue;
            if (cone->halfAngle <= 0.0) { // a point: the hard truth's one ray, exactly
                const Ray r = cone->ray(origin, cone->axis);
                out.visibility[i] = rays.occluded(r.origin, r.direction, r.tNear, r.tFar) ? 0.f : 1.f;
                ++myRays;
                continue;
            }
            // Probes: a ring on the disk's rim (a random turn per point) and a stratified set inside.
            // A straight edge cutting off more than 1.3 % of the disk on either side meets the
            // ring (a segment deeper than 1 - cos(π / 8) of the radius spans more than 45° of rim),
            // so points the probes call umbra or full light are within 1.3 % of it.
            const double turn = 2.0 * kPi * uniform(options.seed, i, 1u << 30);
            const int probes = kRing + probeSide * probeSide;
            const int seen = visibleRays(rays, origin, *cone, probes, [&](int j) {
                if (j < kRing) return rimDirection(cone->axis, cone->halfAngle, turn + 2.0 * kPi * j / kRing);
                const auto [u, v] = stratum(j - kRing, probeSide, options.seed, i, 0);
                return coneDirection(cone->axis, cone->halfAngle, u, v);
            });
            myRays += probes;
            if (seen == 0 || seen == probes) {
                out.visibility[i] = seen == 0 ? 0.f : 1.f;
                continue;
            }
            // A penumbra: a fresh, finer set (its own sample stream), the probes not reused, so the
            // estimate is the stratified set's alone.
            const int samples = sampleSide * sampleSide;
            const int visible = visibleRays(rays, origin, *cone, samples, [&](int j) {
                const auto [u, v] = stratum(j, sampleSide, options.seed, i, 1u << 20);
                return coneDirection(cone->axis, cone->halfAngle, u, v);
            });
            myRays += samples;
            ++myPenumbra;
            const double v = static_cast<double>(visible) / samples;
            out.visibility[i] = static_cast<float>(v);
            out.standardError[i] = static_cast<float>(std::sqrt(v * (1.0 - v) / samples));
        }
        traced.fetch_add(myRays, std::memory_order_relaxed);
        penumbra.fetch_add(myPenumbra, std::memory_order_relaxed);
    });
    out.rays = traced.load();
    out.penumbraPoints = penumbra.load();
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace

SoftTruth computeSoftTruth(const RayScene& rays, const TruthBuffers& hits, const SunDisk& sun,
                           const SoftTruthOptions& options) {
    const LightCone cone{glm::normalize(sun.wsTowardsSun), 0.5 * sun.angularDiameterDegrees * kPi / 180.0};
    return softTruth(rays, hits, options, [&](size_t, const core::Vec3& normal, const core::Vec3&) {
        return facesLight(normal, cone.axis) ? std::optional(cone) : std::nullopt;
    });
}

SoftTruth computeSphereSoftTruth(const RayScene& rays, const TruthBuffers& underLight, const SphereLight& light,
                                 const SoftTruthOptions& options) {
    return softTruth(rays, underLight, options,
                     [&](size_t i, const core::Vec3&, const core::Vec3& origin) -> std::optional<LightCone> {
                         if (!underLight.facesLight[i]) return std::nullopt; // out of its reach
                         const core::Vec3 toCentre = light.wsCentre - origin;
                         const double distance = glm::length(toCentre);
                         // Inside the sphere (or at its centre) the whole light is seen.
                         const double sinHalf = std::min(light.radius / std::max(distance, 1e-300), 1.0);
                         return LightCone{toCentre / distance, std::asin(sinHalf), toCentre, light.radius};
                     });
}

SoftFigures compareSoft(std::span<const float> shadowTerm, const SoftTruth& soft, std::span<const PixelClass> classes,
                        double sunAngleDegrees) {
    SoftFigures f;
    f.sunAngleDegrees = sunAngleDegrees;
    f.truthSeconds = soft.seconds;
    f.truthRays = soft.rays;
    const size_t n = std::min({shadowTerm.size(), soft.visibility.size(), classes.size()});
    double sum = 0.0, penumbraSum = 0.0;
    int64_t wrong = 0, trueBand = 0, renderedBand = 0; // 10–90 %: the width the penumbra tests measure
    for (size_t i = 0; i < n; ++i) {
        const PixelClass c = classes[i];
        const bool valid = c == PixelClass::LitCorrect || c == PixelClass::ShadowCorrect ||
                           c == PixelClass::FalseShadow || c == PixelClass::FalseLit;
        const float truth = soft.visibility[i];
        if (!valid || std::isnan(truth)) continue;
        const double error = std::abs(static_cast<double>(shadowTerm[i]) - truth);
        ++f.comparedPx;
        sum += error;
        wrong += error > 0.25;
        trueBand += truth > 0.1f && truth < 0.9f;
        renderedBand += shadowTerm[i] > 0.1f && shadowTerm[i] < 0.9f;
        if (truth > 0.02f && truth < 0.98f) {
            ++f.penumbraPx;
            penumbraSum += error;
        }
    }
    if (f.comparedPx > 0) {
        f.softMae = sum / static_cast<double>(f.comparedPx);
        f.softWrongPct = 100.0 * static_cast<double>(wrong) / static_cast<double>(f.comparedPx);
    }
    if (f.penumbraPx > 0) f.penumbraMae = penumbraSum / static_cast<double>(f.penumbraPx);
    f.penumbraWidthRatio = trueBand > 0 ? static_cast<double>(renderedBand) / static_cast<double>(trueBand) : NAN;
    return f;
}

} // namespace shadowkit::eval
