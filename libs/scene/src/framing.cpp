// Framing a scene without ground (framing.h): along a compass direction and pitch, the least
// eye distance at which every corner of the bounds lies inside the field of view.
#include "framing.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace shadowkit::scene {

core::Aabb framedBounds(const Scene& scene, const core::Aabb& localBounds) {
    // Every placed vertex, or every k-th where there are more than kSamples (an exported forest
    // places tens of millions): the middle 98 % along each axis is what the tails are judged by.
    constexpr size_t kSamples = size_t(1) << 18;
    size_t placed = 0;
    for (const MeshBatch& batch : scene.batches)
        placed += scene.meshes[batch.mesh].vertices.size() * batch.worldFromObject.size();
    if (placed < 100) return localBounds; // too few to tell a backdrop from the model
    const size_t stride = std::max<size_t>(1, placed / kSamples);
    std::vector<core::Vec3> points;
    points.reserve(placed / stride + 1);
    size_t next = 0, base = 0; // the next vertex sampled, the first of the instance at hand
    for (const MeshBatch& batch : scene.batches) {
        const std::vector<Vertex>& vertices = scene.meshes[batch.mesh].vertices;
        for (const glm::mat4& worldFromObject : batch.worldFromObject) {
            for (; next < base + vertices.size(); next += stride)
                points.push_back(core::Vec3(worldFromObject * glm::vec4(vertices[next - base].position, 1.0f)));
            base += vertices.size();
        }
    }
    core::Vec3 low, high;
    std::vector<double> along(points.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (size_t i = 0; i < points.size(); ++i) along[i] = points[i][axis];
        const auto at = [&](double share) {
            const auto nth = along.begin() + std::ptrdiff_t(share * double(along.size() - 1));
            std::nth_element(along.begin(), nth, along.end());
            return *nth;
        };
        low[axis] = at(0.01), high[axis] = at(0.99);
    }
    const core::Aabb middle = core::Aabb::fromMinMax(low, high);
    if (!(middle.diagonal() < kFramedPartShare * localBounds.diagonal())) return localBounds;
    // The tails' vertices near the middle are the model's own (a building at the town's edge):
    // kept; those beyond twice its size, or a twentieth of its diagonal where it is flat along an
    // axis (a town's roofs over a middle that is a plane), are the backdrop.
    const core::Vec3 centre = middle.center(),
                     reach = glm::max(middle.max - centre, core::Vec3(0.05 * middle.diagonal()));
    core::Aabb part;
    for (const core::Vec3& p : points)
        if (glm::all(glm::lessThanEqual(glm::abs(p - centre), 2.0 * reach))) part.extend(p);
    return part;
}

Framing frameBounds(const core::Aabb& bounds, double azimuthRadians, double pitchRadians, double fovYDegrees,
                    double aspect) {
    Framing out;
    const double pitch = std::min(pitchRadians, glm::radians(kFramingMaxPitchDegrees));
    const double az = azimuthRadians;
    const core::Vec3 centre = bounds.center();
    const core::Vec3 forward(std::sin(az) * std::cos(pitch), std::sin(pitch), -std::cos(az) * std::cos(pitch));
    // Straight down (a pitch of −90°, which cos() leaves a hair off vertical) the right vector
    // is still the compass direction's: the cross product is tiny but not zero in doubles.
    const core::Vec3 right = glm::normalize(glm::cross(forward, core::Vec3(0, 1, 0))), up = glm::cross(right, forward);
    // The eye at `distance` back from the centre sees a corner c (x right, y up, z forward of the
    // centre) when |x| <= tanX (distance + z) and |y| <= tanY (distance + z): the least distance
    // for every corner frames the box tightly.
    const double tanY = std::tan(0.5 * glm::radians(fovYDegrees)), tanX = tanY * aspect;
    double distance = 0.0, nearest = INFINITY, farthest = 0.0;
    for (const core::Vec3& corner : bounds.corners()) {
        const core::Vec3 c = corner - centre;
        const double x = glm::dot(c, right), y = glm::dot(c, up), z = glm::dot(c, forward);
        distance = std::max({distance, std::abs(x) / tanX - z, std::abs(y) / tanY - z});
    }
    // A margin round the picture; a box of no size (a point) is seen from a thousandth of a
    // metre — a floor relative to the box, so a model of a millimetre fills the picture too.
    distance = std::max(distance * 1.05, bounds.diagonal() > 0.0 ? 1e-3 * bounds.diagonal() : 1e-3);
    for (const core::Vec3& corner : bounds.corners()) {
        const double depth = distance + glm::dot(corner - centre, forward);
        nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
    }
    out.eye = centre - distance * forward;
    out.direction = forward;
    out.pitchRadians = pitch;
    out.zNear = std::max(0.9 * nearest, 1e-3 * farthest);
    out.zFar = 1.1 * farthest;
    out.fogDensity = 0.3 / out.zFar;
    return out;
}

} // namespace shadowkit::scene
