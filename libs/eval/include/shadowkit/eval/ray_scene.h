// Exact ray queries against a shadowkit scene (Embree 3): the ground truth.
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <limits>
#include <memory>
#include <span>

namespace shadowkit::eval {

struct RayHit {
    double t = 0.0;                 // ray parameter of the hit
    uint32_t instance = 0;          // global instance index (batches in Scene order)
    core::Vec3 wsGeometricNormal{}; // unit, world space, facing against the ray
};

// A ray for the batched queries: origin + t·direction, t in [tNear, tFar].
struct Ray {
    core::Vec3 origin{0.0};
    core::Vec3 direction{0.0, 0.0, -1.0};
    double tNear = 0.0;
    double tFar = std::numeric_limits<double>::infinity();
};

// Which sides of a surface a query meets. Light meets both sides of every surface (a
// single-sided wall still stops the sun, and a shadow ray may leave from inside a model).
// A camera sees what the camera pass draws: the back of a single-sided surface is culled
// there (scene::Scene::seenFromFrontOnly), so a camera ray passes through it to what lies
// behind, where the raster shows that too.
enum class Faces { Both, AsTheCameraSees };

// Rays come in world coordinates (double); the BVHs hold the scene in its own coordinates
// (scene::Scene::wsOrigin at 0), where Embree's floats keep their precision, and each ray's
// origin is moved there in double before it becomes float.
class RayScene {
public:
    // One Embree scene per mesh, instanced once per placement (10,000 trees share four
    // BVHs). Embree errors come back as one line.
    static core::Result<std::unique_ptr<RayScene>> build(const scene::Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // Nearest hit of origin + t·direction for t in [tNear, tFar]; false on a miss.
    bool intersect(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar, RayHit& hit,
                   Faces faces = Faces::Both) const;
    // Anything hit for t in [tNear, tFar]?
    bool occluded(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar) const;
    // The same for many rays, eight at a time through Embree's packet kernels: coherent rays (a
    // screen tile's, or their shadow rays towards the sun) traverse the hierarchy together. Each
    // result is what the one-ray query gives for that ray. `hit[i]` / `occluded[i]` 0 or 1;
    // `hits[i]` set where hit[i] is 1. Spans of equal length.
    void intersect(std::span<const Ray> rays, std::span<uint8_t> hit, std::span<RayHit> hits,
                   Faces faces = Faces::Both) const;
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded) const;

    // Instances that moved (scene::animate's list of global indices) take their new
    // transforms from `scene`, the scene this was built from, and a mesh the scene deforms
    // (Scene::deformations) its posed vertices, its own BVH refitted; then the top-level BVH,
    // and which sides of their batches a camera sees (a mirror may have come or gone).
    // Fails, changing nothing, for an index out of range.
    core::Status moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved);

    double sceneDiagonal() const { return m_diagonal; }
    // How far a shadow ray starts off its surface along the normal: `fraction` of the scene's
    // diagonal (TruthOptions::normalOffsetFraction), scaling with the scene — a floor in metres
    // (once 1 m × fraction, 10 µm) carried the rays of a model a millimetre across past the
    // casters that shade it. The scene stands near its own origin (Scene::wsOrigin), so its
    // float coordinates err by about 1e-7 of its size, far below 1e-5 of it.
    double shadowRayOffset(double fraction) const { return fraction * (m_diagonal > 0.0 ? m_diagonal : 1.0); }
    const core::Vec3& wsOrigin() const { return m_wsOrigin; } // the scene's (Scene::wsOrigin)

private:
    RayScene() = default;
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    double m_diagonal = 0.0;
    core::Vec3 m_wsOrigin{0.0};
};

} // namespace shadowkit::eval
