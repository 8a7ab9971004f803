// shadowkit conventions, written once (docs/architecture.md, Conventions).
//
// Spaces
//   world  right-handed, +Y up, metres.
//   view   camera at the origin looking down -Z (GL look-at), +Y up.
//   light  a directional light's view: looks along the light's travel direction (-Z in
//          light space), so +Z points towards the sun. x/y span the shadow map.
//   clip   after a projection; depth in [0,1] (glClipControl(GL_LOWER_LEFT,
//          GL_ZERO_TO_ONE)): 0 is nearest the eye / the light.
//   texture (ts) shadow-map coordinates in [0,1]^2, ts = cs.xy * 0.5 + 0.5.
//   scene  (qs) world translated to a floating origin: q = p - origin, the origin a scene's
//          scene::Scene::wsOrigin (or a tile's centre). core::rebased re-expresses a set-up
//          there; libs/gl draws everything in it (float sees numbers of the scene's size).
//   eye-relative  world translated by -eye (ShadowSetup::wsEye): q = p - eye, what a
//          camera-relative renderer feeds the *FromEyeRelative matrices.
//
// Matrices are glm, column-major, acting on column vectors, and named bFromA:
//   clipFromWorld = clipFromLight * lightFromWorld.
// Positions and vectors carry their space as a prefix where it is not obvious:
//   ws (world), qs (scene), vs (view), ls (light), cs (clip), ts (shadow texture).
// The scene's space is the world with its origin moved, so code that holds only one of the two
// (libs/gl, whose every GPU-side position is the scene's; an engine rendering camera-relative)
// keeps the world names, ws and *FromWorld. qs is written where both meet: the conversion
// itself (core::rebased, gl/src/scene_frame.h's SceneFrame::rebasedSetup).
//
// A directional light's `direction` is the direction the light travels (sun -> scene).
// Sun angles: elevation above the horizon; azimuth clockwise seen from above, 0 = -Z
// ("north"), 90 = +X ("east"). The direction *towards* the sun is
//   (sin az cos el, sin el, -cos az cos el).
//
// The core computes in double precision: shadow set-ups over kilometres of terrain with
// a near plane of centimetres lose whole texels in float (Filament multiplies these
// chains in double for the same reason). Convert to float at the GPU boundary.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace shadowkit::core {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using Vec4 = glm::dvec4;
using Mat3 = glm::dmat3;
using Mat4 = glm::dmat4;

/// How a projection maps depth to clip depth: [0, 1] (shadowkit's own, Vulkan, Direct3D, Metal,
/// OpenGL with glClipControl(..., GL_ZERO_TO_ONE)) or OpenGL's default [-1, 1]. Engines choose
/// theirs for their camera (engine_camera.h) and for the maps (output_conventions.h).
enum class ClipDepthRange { ZeroToOne, MinusOneToOne };

/// True when no component is NaN or infinite.
template <glm::length_t N>
bool isFinite(const glm::vec<N, double>& v) {
    for (glm::length_t i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
inline bool isFinite(const Mat4& m) { return isFinite(m[0]) && isFinite(m[1]) && isFinite(m[2]) && isFinite(m[3]); }

// SK_ASSERT: programmer mistakes only (a broken precondition of a library function).
// Bad data from users, files or the environment is reported as a value instead
// (see result.h). Kept on in release builds: the checks are cheap and a silent NaN
// matrix is far more expensive to debug.
#define SK_ASSERT(cond, msg)                                                                                           \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            std::fprintf(stderr, "shadowkit: assertion failed: %s (%s:%d)\n", msg, __FILE__, __LINE__);                \
            std::abort();                                                                                              \
        }                                                                                                              \
    } while (false)

} // namespace shadowkit::core
