#include "shadowkit/eval/truth.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
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

// The shadow ray of a surface point: towards the light from just off the surface.
Ray shadowRay(const core::Vec3& wsPoint, const core::Vec3& wsNormal, const core::Vec3& towardsLight, double offset) {
    return {wsPoint + offset * wsNormal, towardsLight, 0.0, std::numeric_limits<double>::infinity()};
}

// For the pixels i in [begin, end) whose `rayOf(i)` gives a ray, `trace(rays, pixels)` with up
// to eight of them at a time: neighbouring pixels' shadow rays are coherent, and the ray tracer's
// packet kernels take them together.
constexpr size_t kBatch = 8; // rays per call: the packet kernels' width

template <class RayOf, class Trace>
void inBatches(size_t begin, size_t end, RayOf rayOf, Trace trace) {
    std::array<Ray, kBatch> batch;
    std::array<size_t, kBatch> pixel;
    size_t count = 0;
    const auto flush = [&] {
        trace(std::span<const Ray>(batch.data(), count), std::span<const size_t>(pixel.data(), count));
        count = 0;
    };
    for (size_t i = begin; i < end; ++i) {
        const std::optional<Ray> ray = rayOf(i);
        if (!ray) continue;
        pixel[count] = i;
        batch[count++] = *ray;
        if (count == kBatch) flush();
    }
    flush();
}

// lit[i] = the ray reaches the light, for the pixels whose `rayOf(i)` gives a shadow ray.
template <class RayOf>
void traceLit(const RayScene& rays, size_t begin, size_t end, RayOf rayOf, std::vector<uint8_t>& lit) {
    std::array<uint8_t, kBatch> occluded;
    inBatches(begin, end, rayOf, [&](std::span<const Ray> batch, std::span<const size_t> pixels) {
        rays.occluded(batch, std::span(occluded.data(), batch.size()));
        for (size_t k = 0; k < batch.size(); ++k) lit[pixels[k]] = !occluded[k];
    });
}

// The sun's shadow ray of `hits`' pixel i, where it has a surface facing the light.
std::optional<Ray> sunShadowRay(const TruthBuffers& hits, size_t i, const core::Vec3& towardsLight, double offset) {
    const core::Vec3 n(hits.wsNormal[i]);
    if (hits.surfaceId[i] == 0 || !facesLight(n, towardsLight)) return std::nullopt;
    return shadowRay(hits.wsPosition[i], n, towardsLight, offset);
}

// A local light's truth at `hits`' surfaces: which face it within what it admits (range,
// cone), and of those which reach it along the finite shadow ray from just off the surface.
template <class Admits>
void localLightTruth(const RayScene& rays, const TruthBuffers& hits, const core::Vec3& wsLight,
                     const TruthOptions& options, Admits admits, std::vector<uint8_t>& reached,
                     std::vector<uint8_t>& lit) {
    reached.assign(hits.surfaceId.size(), 0);
    lit.assign(hits.surfaceId.size(), 0);
    const double offset = rays.shadowRayOffset(options.normalOffsetFraction);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lit.size()), [&](const tbb::blocked_range<size_t>& r) {
        traceLit(
            rays, r.begin(), r.end(),
            [&](size_t i) -> std::optional<Ray> {
                if (hits.surfaceId[i] == 0) return std::nullopt;
                const core::Vec3 p = hits.wsPosition[i], n(hits.wsNormal[i]);
                const core::Vec3 toLight = wsLight - p;
                const double distance = glm::length(toLight);
                if (!(distance > 0.0) || !admits(p, distance) || !facesLight(n, toLight / distance))
                    return std::nullopt;
                reached[i] = 1;
                const core::Vec3 origin = p + offset * n;
                const core::Vec3 towards = wsLight - origin;
                return Ray{origin, glm::normalize(towards), 0.0, glm::length(towards)};
            },
            lit);
    });
}

auto admitsPoint(const core::PointLight& light) {
    return [range = light.range](const core::Vec3&, double d) { return d <= range; };
}
auto admitsSpot(const core::SpotLight& light) {
    return [&light, axis = glm::normalize(light.wsDirection),
            cosHalf = std::cos(0.5 * glm::radians(light.coneDegrees))](const core::Vec3& p, double d) {
        return d <= light.range && glm::dot(p - light.wsPosition, axis) >= cosHalf * d;
    };
}

} // namespace

core::Vec3 primaryRayDirection(const core::PerspectiveCamera& camera, int width, int height, int x, int y) {
    const double ty = std::tan(0.5 * glm::radians(camera.fovYDegrees));
    const double ndcX = (x + 0.5) / width * 2.0 - 1.0;
    const double ndcY = 1.0 - (y + 0.5) / height * 2.0;
    const core::Vec3 forward = glm::normalize(camera.wsDirection);
    const core::Vec3 right = glm::normalize(glm::cross(forward, camera.wsUp));
    const core::Vec3 up = glm::cross(right, forward);
    // View-space direction (ndcX·tx, ndcY·ty, -1): unit length along the view axis.
    return forward + ndcX * ty * camera.aspect * right + ndcY * ty * up;
}

TruthBuffers computeTruth(const RayScene& rays, const core::PerspectiveCamera& camera,
                          const core::DirectionalLight& light, int width, int height, const TruthOptions& options) {
    TruthBuffers t;
    t.width = width;
    t.height = height;
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    t.surfaceId.assign(n, 0);
    t.viewDepth.assign(n, 0.0f);
    t.wsPosition.assign(n, core::Vec3(0.0));
    t.wsNormal.assign(n, glm::vec3(0.0f));
    t.facesLight.assign(n, 0);
    t.lit.assign(n, 0);
    const core::Vec3 towardsLight = light.wsTowardsLight();
    const double offset = rays.shadowRayOffset(options.normalOffsetFraction);

    const auto start = std::chrono::steady_clock::now();
    std::atomic<uint64_t> shadowRays{0};
    // Rows in chunks so progress can be reported between them from this thread; within a
    // chunk, tiles of 4 × 2 pixels: a tile's primary rays, then the shadow rays of those that
    // face the light, go through the ray tracer as one 8-wide packet each (coherent rays
    // traverse its hierarchy together; each answer is the one-ray query's).
    constexpr int kTileW = 4, kTileH = 2;
    const int chunk = std::max(kTileH, height / 20 / kTileH * kTileH);
    for (int y0 = 0; y0 < height; y0 += chunk) {
        const int y1 = std::min(height, y0 + chunk);
        const tbb::blocked_range2d<int> tiles(0, (y1 - y0 + kTileH - 1) / kTileH, 0, (width + kTileW - 1) / kTileW);
        tbb::parallel_for(tiles, [&](const tbb::blocked_range2d<int>& r) {
            uint64_t traced = 0;
            std::array<Ray, kTileW * kTileH> primary, shadow;
            std::array<size_t, kTileW * kTileH> pixel, shadowPixel;
            std::array<uint8_t, kTileW * kTileH> hit, occluded;
            std::array<RayHit, kTileW * kTileH> hits;
            for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
                    size_t count = 0;
                    for (int y = y0 + ty * kTileH; y < std::min(y1, y0 + (ty + 1) * kTileH); ++y)
                        for (int x = tx * kTileW; x < std::min(width, (tx + 1) * kTileW); ++x) {
                            pixel[count] = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
                            primary[count++] = {camera.wsEye, primaryRayDirection(camera, width, height, x, y),
                                                camera.zNear, camera.zFar};
                        }
                    rays.intersect(std::span(primary.data(), count), std::span(hit.data(), count),
                                   std::span(hits.data(), count), Faces::AsTheCameraSees);
                    size_t shadows = 0;
                    for (size_t k = 0; k < count; ++k) {
                        if (!hit[k]) continue;
                        const size_t i = pixel[k];
                        const core::Vec3 p = camera.wsEye + hits[k].t * primary[k].direction;
                        const core::Vec3& wsNormal = hits[k].wsGeometricNormal;
                        t.surfaceId[i] = hits[k].instance + 1;
                        t.viewDepth[i] = static_cast<float>(hits[k].t);
                        t.wsPosition[i] = p;
                        t.wsNormal[i] = glm::vec3(wsNormal);
                        if (!facesLight(wsNormal, towardsLight)) continue;
                        t.facesLight[i] = 1;
                        shadowPixel[shadows] = i;
                        shadow[shadows++] = shadowRay(p, wsNormal, towardsLight, offset);
                    }
                    rays.occluded(std::span(shadow.data(), shadows), std::span(occluded.data(), shadows));
                    for (size_t k = 0; k < shadows; ++k) t.lit[shadowPixel[k]] = !occluded[k];
                    traced += shadows;
                }
            shadowRays.fetch_add(traced, std::memory_order_relaxed);
        });
        if (options.progress) options.progress(double(y1) / height);
    }
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    t.rays = n + shadowRays.load();
    return t;
}

std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::DirectionalLight& light,
                           const TruthOptions& options) {
    std::vector<uint8_t> lit(hits.surfaceId.size(), 0);
    const core::Vec3 towardsLight = light.wsTowardsLight();
    const double offset = rays.shadowRayOffset(options.normalOffsetFraction);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lit.size()), [&](const tbb::blocked_range<size_t>& r) {
        traceLit(
            rays, r.begin(), r.end(), [&](size_t i) { return sunShadowRay(hits, i, towardsLight, offset); }, lit);
    });
    return lit;
}

std::vector<uint32_t> castersAt(const RayScene& rays, const TruthBuffers& hits, const core::DirectionalLight& light,
                                const TruthOptions& options) {
    std::vector<uint32_t> caster(hits.surfaceId.size(), 0);
    const core::Vec3 towardsLight = light.wsTowardsLight();
    const double offset = rays.shadowRayOffset(options.normalOffsetFraction);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, caster.size()), [&](const tbb::blocked_range<size_t>& r) {
        std::array<uint8_t, kBatch> hit;
        std::array<RayHit, kBatch> nearest;
        inBatches(
            r.begin(), r.end(),
            [&](size_t i) { return hits.lit[i] ? std::nullopt : sunShadowRay(hits, i, towardsLight, offset); },
            [&](std::span<const Ray> batch, std::span<const size_t> pixels) {
                rays.intersect(batch, std::span(hit.data(), batch.size()), std::span(nearest.data(), batch.size()));
                for (size_t k = 0; k < batch.size(); ++k)
                    if (hit[k]) caster[pixels[k]] = nearest[k].instance + 1;
            });
    });
    return caster;
}

std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::PointLight& light,
                           const TruthOptions& options) {
    std::vector<uint8_t> reached, lit;
    localLightTruth(rays, hits, light.wsPosition, options, admitsPoint(light), reached, lit);
    return lit;
}

std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::SpotLight& light,
                           const TruthOptions& options) {
    std::vector<uint8_t> reached, lit;
    localLightTruth(rays, hits, light.wsPosition, options, admitsSpot(light), reached, lit);
    return lit;
}

TruthBuffers underLight(const RayScene& rays, const TruthBuffers& hits, const core::PointLight& light,
                        const TruthOptions& options) {
    TruthBuffers t = hits;
    localLightTruth(rays, hits, light.wsPosition, options, admitsPoint(light), t.facesLight, t.lit);
    return t;
}

TruthBuffers underLight(const RayScene& rays, const TruthBuffers& hits, const core::SpotLight& light,
                        const TruthOptions& options) {
    TruthBuffers t = hits;
    localLightTruth(rays, hits, light.wsPosition, options, admitsSpot(light), t.facesLight, t.lit);
    return t;
}

} // namespace shadowkit::eval
