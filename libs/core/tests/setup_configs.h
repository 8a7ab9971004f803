// Shared by the set-up tests: random camera / light / scene configurations and the
// containment measures they are checked with.
#pragma once

#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/shadow_setup.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace shadowkit::core::testing {

// Uniform numbers and directions from one seeded generator: what the tests' own generators add to.
struct RandomSource {
    explicit RandomSource(unsigned seed) : rng(seed) {}
    std::mt19937 rng;
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
    Vec3 unit() {
        std::normal_distribution<double> n;
        for (;;) {
            const Vec3 v(n(rng), n(rng), n(rng));
            if (glm::length(v) > 1e-3) return glm::normalize(v);
        }
    }
};

// Random camera / light / scene-box configurations, including the degenerate ones
// the issue names: view parallel and anti-parallel to the light, tiny and huge
// near/far ratios, flat and zero-size scene boxes.
class ConfigGenerator {
public:
    explicit ConfigGenerator(unsigned seed) : m_rng(seed) {}

    ShadowSetupInputs next() {
        ShadowSetupInputs in;
        const Vec3 center(uniform(-2000, 2000), uniform(-100, 100), uniform(-2000, 2000));
        Vec3 half(uniform(0, 1500), uniform(0, 60), uniform(0, 1500));
        if (chance(0.03)) half.y = 0.0;     // flat scene (a terrain plane)
        if (chance(0.01)) half = Vec3(0.0); // zero-size scene
        in.wsSceneBounds = Aabb::fromMinMax(center - half, center + half);

        PerspectiveCamera& cam = in.camera;
        // Mostly inside the box, sometimes outside (then B may be empty).
        cam.wsEye = center + Vec3(uniform(-1.2, 1.2) * half.x, uniform(-1, 3) * half.y + uniform(0, 50),
                                  uniform(-1.2, 1.2) * half.z);
        cam.wsDirection = unitVector();
        cam.wsUp = unitVector();
        if (glm::length(glm::cross(cam.wsDirection, cam.wsUp)) < 1e-3) cam.wsUp = Vec3(0, 1, 0);
        if (glm::length(glm::cross(cam.wsDirection, cam.wsUp)) < 1e-3) cam.wsUp = Vec3(1, 0, 0);
        cam.fovYDegrees = uniform(5, 170);
        cam.aspect = uniform(0.3, 3);
        cam.zNear = std::pow(10.0, uniform(-3, 1.5));
        cam.zFar = cam.zNear * std::pow(10.0, uniform(0.01, 6)); // ratios 1.02 .. 1e6

        Vec3 l = unitVector();
        const double r = uniform(0, 1);
        if (r < 0.05)
            l = glm::normalize(cam.wsDirection); // view along the light
        else if (r < 0.10)
            l = -glm::normalize(cam.wsDirection); // looking into the sun
        else if (r < 0.15)
            l = glm::normalize(cam.wsDirection + 1e-7 * unitVector());
        in.light = DirectionalLight{l};

        CascadeOptions& c = in.cascades; // used by csm only
        c.count = 1 + static_cast<int>(uniform(0, 8));
        c.lambda = uniform(0, 1);
        c.warp = chance(0.5) ? CascadeWarp::Lispsm : CascadeWarp::None;
        c.stabilize = c.warp == CascadeWarp::None && chance(0.5);
        c.blendBand = chance(0.5) ? uniform(0, 0.5) : 0.0;
        in.mapSize = chance(0.5) ? 1024 : 2048;
        return in;
    }

    Vec3 unitVector() {
        std::normal_distribution<double> n;
        for (;;) {
            const Vec3 v(n(m_rng), n(m_rng), n(m_rng));
            if (glm::length(v) > 1e-6) return glm::normalize(v);
        }
    }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }
    bool chance(double p) { return uniform(0, 1) < p; }

private:
    std::mt19937 m_rng;
};

// Max distance (in clip units) by which a point lies outside the clip cube x,y in [-1,1], z in [0,1].
inline double outsideClipCube(const Mat4& clipFromWorld, const Vec3& ws) {
    const Vec4 cs = clipFromWorld * Vec4(ws, 1.0);
    const Vec3 ndc = Vec3(cs) / cs.w;
    return std::max({std::abs(ndc.x) - 1.0, std::abs(ndc.y) - 1.0, -ndc.z, ndc.z - 1.0, 0.0});
}

// A random point of the view frustum (uniform in NDC x/y, uniform in view depth).
inline Vec3 pointInFrustum(const PerspectiveCamera& cam, ConfigGenerator& gen) {
    const auto c = cam.wsFrustumCorners();
    const double u = gen.uniform(0, 1), v = gen.uniform(0, 1), t = gen.uniform(0, 1);
    const Vec3 nearPoint = glm::mix(glm::mix(c[0], c[1], u), glm::mix(c[3], c[2], u), v);
    const Vec3 farPoint = glm::mix(glm::mix(c[4], c[5], u), glm::mix(c[7], c[6], u), v);
    return glm::mix(nearPoint, farPoint, t);
}

// Whether each view of a set-up holds B (or the scene box): every technique but the virtual
// clipmap, whose levels hold what the level rule gives them (virtual_clipmap_test.cpp).
inline bool holdsFocusBody(Technique t) { return t != Technique::Virtual; }

// What a view of a set-up for `in` must hold: the whole scene box for `standard`, B for the
// others, each cascade its split's B. A split that sees none of the scene has nothing to hold
// (the stabilised fit then keeps its sphere); every other empty-B case falls back to the
// scene box.
inline std::vector<Vec3> pointsToHold(const ShadowSetupInputs& in, const ShadowSetup& setup, const ShadowView& view) {
    ConvexBody body = setup.body;
    if (in.technique == Technique::Csm) {
        PerspectiveCamera slice = in.camera;
        slice.zNear = view.split->x;
        slice.zFar = view.split->y;
        body = computeFocusBody(slice, in.light, in.wsSceneBounds);
    }
    if (in.technique == Technique::Csm && body.isEmpty() && in.cascades.stabilize) return {};
    std::vector<Vec3> points;
    if (in.technique == Technique::Standard || body.isEmpty()) {
        const auto corners = sceneBoxForFocus(in.wsSceneBounds).corners();
        points.assign(corners.begin(), corners.end());
    } else {
        const ConvexBody::Points vertices = body.vertices();
        points.assign(vertices.begin(), vertices.end());
    }
    return points;
}

} // namespace shadowkit::core::testing
