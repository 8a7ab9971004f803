// Ray-traced truth per pixel (docs/references.md, evaluation §3): a primary ray through the pixel centre
// finds the surface the camera pass shows (past the backs of single-sided surfaces, which it
// culls); a shadow ray towards the light decides lit or shadowed.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/eval/ray_scene.h"

#include <functional>
#include <vector>

namespace shadowkit::eval {

struct TruthBuffers {
    int width = 0, height = 0;
    // Row-major, top row first.
    std::vector<uint32_t> surfaceId;    // global instance index + 1; 0 where the ray missed
    std::vector<float> viewDepth;       // metres along the view direction (0 on a miss)
    std::vector<core::Vec3> wsPosition; // hit point (double: float has a 6 cm step 1,000 km out)
    std::vector<glm::vec3> wsNormal;    // geometric normal facing the viewer
    std::vector<uint8_t> facesLight;    // N·L > kFacingCosine (facesLight below)
    std::vector<uint8_t> lit;           // the shadow ray reached the light (only where facesLight)
    // What computing it took: wall seconds, and rays traced (primary and shadow).
    double seconds = 0.0;
    uint64_t rays = 0;
};

// Whether a surface faces a light: one rule for the truth and the sampling model (core/light.h).
using core::facesLight;
using core::kFacingCosine;

struct TruthOptions {
    // Shadow-ray start offset along the geometric normal, as a fraction of the scene
    // diagonal: 1e-5 is 1.5 cm on the 1 km forest — above float rounding at that range,
    // below any feature that casts a shadow.
    double normalOffsetFraction = 1e-5;
    // Called with the fraction done (0..1), from the calling thread only.
    std::function<void(double)> progress;
};

// Uses every core (TBB) for the rays.
TruthBuffers computeTruth(const RayScene& rays, const core::PerspectiveCamera& camera,
                          const core::DirectionalLight& light, int width, int height, const TruthOptions& options = {});

// The truth at given surface points (`hits`, e.g. another frame's) under another light or
// with casters moved: per pixel, 1 where the point faces the light and its shadow ray reaches
// it, else 0 (also where `hits` has no surface).
std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::DirectionalLight& light,
                           const TruthOptions& options = {});

// The casters of the sun's truth at `hits`' surfaces: per pixel, the global instance + 1 of the
// first surface its shadow ray meets, where the point faces the light and its ray is blocked
// (`hits.lit` 0); 0 elsewhere. The same rays as litAt's, traced for their nearest hit.
std::vector<uint32_t> castersAt(const RayScene& rays, const TruthBuffers& hits, const core::DirectionalLight& light,
                                const TruthOptions& options = {});

// The truth for a local light at the surface points of `hits`: per pixel, 1 where the point
// lies within the light's range (and, for a spot light, inside its cone), faces the light,
// and the segment from it to the light is free; else 0 (also where `hits` has no surface).
std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::PointLight& light,
                           const TruthOptions& options = {});
std::vector<uint8_t> litAt(const RayScene& rays, const TruthBuffers& hits, const core::SpotLight& light,
                           const TruthOptions& options = {});

// `hits`' surfaces under a local light, for eval::compare: facesLight marks the points the light
// reaches (facing it, in its range and cone), lit those whose segment to it is free.
TruthBuffers underLight(const RayScene& rays, const TruthBuffers& hits, const core::PointLight& light,
                        const TruthOptions& options = {});
TruthBuffers underLight(const RayScene& rays, const TruthBuffers& hits, const core::SpotLight& light,
                        const TruthOptions& options = {});

// A primary ray through the centre of pixel (x, y), top row first, scaled so that its
// parameter t is the view depth (t = near on the near plane).
core::Vec3 primaryRayDirection(const core::PerspectiveCamera& camera, int width, int height, int x, int y);

} // namespace shadowkit::eval
