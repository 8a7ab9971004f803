// Dynamic scenes: a moving caster's shadow follows it, a moving sun moves the shadows, and a
// frame depends on its time alone (Renderer::moveInstances after scene::animate). CTest
// label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace shadowkit;

namespace {

class DynamicsTest : public gl::testing::HeadlessGlTest {};

// A 100 m ground and one 4 m cube that rounds a 12 m circle 5 m above it at 5 m/s.
scene::Scene groundAndMover() {
    scene::Scene s;
    scene::Mesh ground, cube;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {50, 0.05f, 50}, glm::vec3(0.8f));
    scene::addBox(cube, glm::mat4(1.0f), {2, 2, 2}, glm::vec3(0.8f));
    ground.computeBounds();
    cube.computeBounds();
    s.meshes = {ground, cube};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, true}};
    s.tracks.push_back({.batch = 1, .instance = 0, .radius = 12.0, .speed = 5.0, .lift = 5.0});
    scene::animate(s, 0.0);
    return s;
}

core::PerspectiveCamera overhead() {
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 45, 30};
    cam.wsDirection = glm::normalize(core::Vec3(0, -45, -30));
    cam.aspect = 1.0;
    cam.zNear = 1.0;
    cam.zFar = 150.0;
    return cam;
}

struct Frame {
    scene::Image image;
    core::PerspectiveCamera camera;
    // Luminance of the pixel showing the ground point `ws` (y = 0).
    double luminanceAt(const core::Vec3& ws) const {
        const core::Vec4 cs = camera.clipFromWorld() * core::Vec4(ws.x, 0.0, ws.z, 1.0);
        const int x = static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * image.width);
        const int y = static_cast<int>((0.5 - cs.y / cs.w * 0.5) * image.height);
        const uint8_t* p = image.pixel(x, y);
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
};

// Animates the scene to t, hands the moved instances to the renderer, draws.
Frame renderAt(gl::Renderer& renderer, scene::Scene& s, double t, const core::DirectionalLight& sun) {
    std::vector<uint32_t> moved;
    scene::animate(s, t, &moved);
    EXPECT_TRUE(renderer.moveInstances(s, moved));
    const core::PerspectiveCamera cam = overhead();
    const auto setup = core::computeShadowSetup({.camera = cam,
                                                 .light = sun,
                                                 .wsSceneBounds = renderer.wsSceneBounds(),
                                                 .technique = core::Technique::Lispsm,
                                                 .mapSize = 1024});
    EXPECT_TRUE(setup);
    gl::RenderSettings settings;
    settings.width = settings.height = 200;
    settings.fogDensity = 0.0f;
    EXPECT_TRUE(renderer.render(cam, sun, *setup, settings));
    return {renderer.readColor(), cam};
}

bool rayHitsBox(const core::Vec3& origin, const core::Vec3& direction, const core::Aabb& box) {
    double near = 0.0, far = INFINITY;
    for (int a = 0; a < 3; ++a) {
        const double inv = 1.0 / direction[a];
        double t0 = (box.min[a] - origin[a]) * inv, t1 = (box.max[a] - origin[a]) * inv;
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0), far = std::min(far, t1);
    }
    return near <= far;
}

// The truth at ground points round the cube: in its shadow or not. Each point whose state
// holds 0.6 m round it (clear of the shadow's edge by more than a pixel) and that the
// camera sees past the cube there must be dark (< 0.75 of a lit ground pixel) exactly
// when shadowed. Returns the points found shadowed.
std::vector<core::Vec3> expectShadowsAsTruth(const Frame& frame, const scene::Scene& s,
                                             const core::DirectionalLight& sun, const char* what) {
    // The cube turns as it goes round: rays are tested in its object space.
    const core::Mat4 worldFromCube(s.batches[1].worldFromObject[0]);
    const core::Mat4 cubeFromWorld = glm::inverse(worldFromCube);
    const core::Aabb& cube = s.meshes[1].osBounds;
    auto hitsCube = [&](const core::Vec3& wsOrigin, const core::Vec3& wsDirection) {
        return rayHitsBox(core::Vec3(cubeFromWorld * core::Vec4(wsOrigin, 1.0)),
                          core::Vec3(cubeFromWorld * core::Vec4(wsDirection, 0.0)), cube);
    };
    const core::Vec3 centre(worldFromCube[3]);
    auto shadowed = [&](const core::Vec3& p) { return hitsCube(p, sun.wsTowardsLight()); };
    const double lit = frame.luminanceAt(centre + core::Vec3(0, 0, 18)); // towards the camera, far from any shadow
    std::vector<core::Vec3> dark;
    int checked = 0;
    for (int i = -32; i <= 32; ++i)
        for (int j = -32; j <= 32; ++j) {
            const core::Vec3 p(centre.x + 0.5 * i, 0.0, centre.z + 0.5 * j);
            const bool truth = shadowed(p);
            bool clear = !hitsCube(p, frame.camera.wsEye - p);
            for (const core::Vec3 d :
                 {core::Vec3(0.6, 0, 0), core::Vec3(-0.6, 0, 0), core::Vec3(0, 0, 0.6), core::Vec3(0, 0, -0.6)})
                clear = clear && shadowed(p + d) == truth && !hitsCube(p + d, frame.camera.wsEye - p - d);
            if (!clear) continue;
            ++checked;
            if (truth) dark.push_back(p);
            EXPECT_EQ(frame.luminanceAt(p) < 0.75 * lit, truth)
                << what << ": ground at " << p.x << ", " << p.z << " (luminance " << frame.luminanceAt(p) << ", lit "
                << lit << ")";
        }
    EXPECT_GT(checked, 2000) << what;
    return dark;
}

size_t countNotIn(const std::vector<core::Vec3>& a, const std::vector<core::Vec3>& b) {
    return static_cast<size_t>(std::count_if(a.begin(), a.end(), [&](const core::Vec3& p) {
        return std::none_of(b.begin(), b.end(), [&](const core::Vec3& q) { return glm::distance(p, q) < 1e-9; });
    }));
}

} // namespace

TEST_F(DynamicsTest, AMoversShadowMovesWithIt) {
    scene::Scene s = groundAndMover();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(45.0, 90.0).value(); // shadows fall west
    const Frame before = renderAt(**renderer, s, 0.0, sun);
    const std::vector<core::Vec3> darkBefore = expectShadowsAsTruth(before, s, sun, "t = 0 s");
    const Frame after = renderAt(**renderer, s, 2.0, sun); // 10 m round the circle
    const std::vector<core::Vec3> darkAfter = expectShadowsAsTruth(after, s, sun, "t = 2 s");
    EXPECT_GT(darkBefore.size(), 20u);
    EXPECT_GT(darkAfter.size(), 20u);
    // The points are placed round the cube where it is: the shadow came along.
    EXPECT_GT(glm::distance(darkBefore.front(), darkAfter.front()), 5.0);
    // The hierarchy followed the cube: the scene bounds hold it where it is now.
    const core::Vec3 centre = core::Vec3(s.batches[1].worldFromObject[0][3]);
    EXPECT_TRUE((*renderer)->wsSceneBounds().contains(centre));
}

TEST_F(DynamicsTest, TheSameTimeGivesTheSameImage) {
    scene::Scene s = groundAndMover();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50.0, 120.0).value();
    const Frame first = renderAt(**renderer, s, 1.25, sun);
    const Frame elsewhere = renderAt(**renderer, s, 4.0, sun);
    const Frame again = renderAt(**renderer, s, 1.25, sun);
    EXPECT_NE(first.image.rgba, elsewhere.image.rgba);
    EXPECT_EQ(first.image.rgba, again.image.rgba);
}

TEST_F(DynamicsTest, ASunMovingTenDegreesMovesTheShadows) {
    scene::Scene s = groundAndMover();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::DirectionalLight low = core::DirectionalLight::fromSunAngles(30.0, 90.0).value();
    const core::DirectionalLight high = core::DirectionalLight::fromSunAngles(40.0, 90.0).value();
    const std::vector<core::Vec3> darkLow =
        expectShadowsAsTruth(renderAt(**renderer, s, 0.0, low), s, low, "sun at 30 degrees");
    const std::vector<core::Vec3> darkHigh =
        expectShadowsAsTruth(renderAt(**renderer, s, 0.0, high), s, high, "sun at 40 degrees");
    // Both ends of the shadow moved: ground shadowed under one sun and not the other, both ways.
    EXPECT_GT(countNotIn(darkLow, darkHigh), 20u);
    EXPECT_GT(countNotIn(darkHigh, darkLow), 5u);
}

TEST_F(DynamicsTest, MovingAStaticInstanceOrAnotherScenesIsRefused) {
    scene::Scene s = groundAndMover();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const uint32_t ground = 0, outside = 7;
    EXPECT_FALSE((*renderer)->moveInstances(s, {&ground, 1}));
    EXPECT_FALSE((*renderer)->moveInstances(s, {&outside, 1}));
    scene::Scene other = s;
    other.batches[0].worldFromObject.push_back(glm::mat4(1.0f));
    const uint32_t mover = 1;
    EXPECT_FALSE((*renderer)->moveInstances(other, {&mover, 1}));
    EXPECT_TRUE((*renderer)->moveInstances(s, {&mover, 1}));
}
