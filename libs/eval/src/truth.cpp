#include "shadowkit/eval/truth.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace shadowkit::eval {
namespace {

// The shadow ray of a surface point: towards the light from just off the surface.
bool reachesLight(const RayScene& rays, const core::Vec3& wsPoint, const core::Vec3& wsNormal,
                  const core::Vec3& towardsLight, double offset) {
    return !rays.occluded(wsPoint + offset * wsNormal, towardsLight, 0.0, std::numeric_limits<double>::infinity());
}

// A local light's truth at `hits`' surfaces: which face it within what it admits (range,
// cone), and of those which reach it along the finite shadow ray from just off the surface.
template <class Admits>
void localLightTruth(const RayScene& rays, const TruthBuffers& hits, const core::Vec3& wsLight,
                     const TruthOptions& options, Admits admits, std::vector<uint8_t>& reached,
                     std::vector<uint8_t>& lit) {
    reached.assign(hits.surfaceId.size(), 0);
    lit.assign(hits.surfaceId.size(), 0);
    const double offset = options.normalOffsetFraction * std::max(rays.sceneDiagonal(), 1.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lit.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            if (hits.surfaceId[i] == 0) continue;
            const core::Vec3 p = hits.wsPosition[i], n(hits.wsNormal[i]);
            const core::Vec3 toLight = wsLight - p;
            const double distance = glm::length(toLight);
            if (!(distance > 0.0) || !admits(p, distance) || !(glm::dot(n, toLight) > 0.0)) continue;
            reached[i] = 1;
            const core::Vec3 origin = p + offset * n;
            const core::Vec3 towards = wsLight - origin;
            lit[i] = !rays.occluded(origin, glm::normalize(towards), 0.0, glm::length(towards));
        }
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
    const double offset = options.normalOffsetFraction * std::max(rays.sceneDiagonal(), 1.0);

    // Rows in chunks so progress can be reported between them from this thread.
    const int chunk = std::max(1, height / 20);
    for (int y0 = 0; y0 < height; y0 += chunk) {
        const int y1 = std::min(height, y0 + chunk);
        tbb::parallel_for(tbb::blocked_range2d<int>(y0, y1, 0, width), [&](const tbb::blocked_range2d<int>& r) {
            for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                    const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
                    RayHit hit;
                    const core::Vec3 dir = primaryRayDirection(camera, width, height, x, y);
                    if (!rays.intersect(camera.wsEye, dir, camera.zNear, camera.zFar, hit)) continue;
                    const core::Vec3 p = camera.wsEye + hit.t * dir;
                    t.surfaceId[i] = hit.instance + 1;
                    t.viewDepth[i] = static_cast<float>(hit.t);
                    t.wsPosition[i] = p;
                    t.wsNormal[i] = glm::vec3(hit.wsGeometricNormal);
                    const double nDotL = glm::dot(hit.wsGeometricNormal, towardsLight);
                    if (!(nDotL > 0.0)) continue;
                    t.facesLight[i] = 1;
                    t.lit[i] = reachesLight(rays, p, hit.wsGeometricNormal, towardsLight, offset);
                }
        });
        if (options.progress) options.progress(double(y1) / height);
    }
    return t;
}

std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::DirectionalLight& light,
                           const TruthOptions& options) {
    std::vector<uint8_t> lit(hits.surfaceId.size(), 0);
    const core::Vec3 towardsLight = light.wsTowardsLight();
    const double offset = options.normalOffsetFraction * std::max(rays.sceneDiagonal(), 1.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lit.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            if (hits.surfaceId[i] == 0) continue;
            const core::Vec3 n(hits.wsNormal[i]);
            if (!(glm::dot(n, towardsLight) > 0.0)) continue;
            lit[i] = reachesLight(rays, hits.wsPosition[i], n, towardsLight, offset);
        }
    });
    return lit;
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
