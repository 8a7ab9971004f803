// Caster face culling in the sun's depth pass (core::CasterCull, core/caster_facing.h): the
// faces turned towards the light are the ones kept under every technique's projection, warped
// and inverted ones included, and BackOfClosed culls only what bounds a solid. Without bias a
// culled map must equal the two-sided one texel for texel, for fewer samples written.
// CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <utility>

using namespace shadowkit;

namespace {

class CasterCullingTest : public gl::testing::HeadlessGlTest {};

// Closed casters stacked over one another (a tower of boxes, a ball over it) above an open,
// single-sided ground quad whose counter-clockwise side faces `groundUp` ((0, ±1, 0)).
scene::Scene stackOverOpenGround(float groundUp) {
    scene::Scene s;
    scene::Mesh ground, tower, ball;
    ground.name = "ground";
    const glm::vec3 albedo(0.8f);
    for (const glm::vec2 xz : {glm::vec2(-30, -30), glm::vec2(30, -30), glm::vec2(30, 30), glm::vec2(-30, 30)})
        ground.vertices.push_back({{xz.x, 0.0f, xz.y}, {0.0f, groundUp, 0.0f}, albedo});
    // (0, 3, 2) and (0, 2, 1) have their counter-clockwise side up (+y); reversed, down.
    ground.indices = groundUp > 0 ? std::vector<uint32_t>{0, 3, 2, 0, 2, 1} : std::vector<uint32_t>{0, 2, 3, 0, 1, 2};
    tower.name = "tower";
    for (int level = 0; level < 4; ++level)
        scene::addBox(tower, glm::translate(glm::mat4(1.0f), {0.3f * float(level), 1.0f + 2.0f * float(level), 0.0f}),
                      {2.0f - 0.3f * float(level), 0.5f, 2.0f}, albedo);
    ball.name = "ball";
    scene::addIcosphere(ball, glm::mat4(1.0f), 2, 1.5f, albedo);
    for (scene::Mesh* m : {&ground, &tower, &ball}) m->computeBounds();
    s.meshes = {ground, tower, ball};
    s.batches = {{0, {glm::mat4(1.0f)}, false},
                 {1, {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), {-6.0f, 0.0f, -4.0f})}, false},
                 {2, {glm::translate(glm::mat4(1.0f), {1.0f, 11.0f, 0.5f})}, false}};
    return s;
}

struct Drawn {
    scene::Image map;
    uint64_t samples = 0;
};

Drawn drawMap(gl::Renderer& renderer, const core::PerspectiveCamera& cam, const core::DirectionalLight& sun,
              const core::ShadowSetup& setup, core::CasterCull cull) {
    gl::RenderSettings settings;
    settings.width = settings.height = 64;
    settings.fogDensity = 0.0f;
    // No offset: the claim "the same map" is about depth; slope-scaled offset breaks it
    // on purpose (bias.h).
    settings.bias = core::BiasSettings{.slope = 0.0, .constant = 0.0, .cull = cull};
    const auto stats = renderer.render(cam, sun, setup, settings);
    EXPECT_TRUE(stats) << stats.error();
    return {renderer.readShadowMap(), stats ? stats->shadow.samplesPassed : 0};
}

} // namespace

TEST_F(CasterCullingTest, CulledMapsEqualTwoSidedOnesUnderEveryTechniqueForFewerSamples) {
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 8, 24};
    cam.wsDirection = glm::normalize(core::Vec3(0, -0.3, -1));
    cam.fovYDegrees = 50;
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 80;
    // A sun ahead of the viewer, one behind it (PSM's inverted projection) and one from the side.
    const core::Vec3 suns[3] = {{0.2, -1.0, 0.6}, {0.2, -1.0, -0.7}, {1.0, -0.8, 0.1}};
    for (const float groundUp : {1.0f, -1.0f}) {
        const scene::Scene s = stackOverOpenGround(groundUp);
        auto renderer = gl::Renderer::create(s);
        ASSERT_TRUE(renderer) << renderer.error();
        for (const core::Vec3& travel : suns) {
            const core::DirectionalLight sun{glm::normalize(travel)};
            for (const core::TechniqueInfo& technique : core::allTechniques()) {
                if (technique.technique == core::Technique::Virtual) continue; // pages: virtual_pages_test
                const auto setup = core::computeShadowSetup({.camera = cam,
                                                             .light = sun,
                                                             .wsSceneBounds = s.wsBounds(),
                                                             .technique = technique.technique,
                                                             .mapSize = 256});
                ASSERT_TRUE(setup) << setup.error();
                const std::string where = std::string(technique.name) + ", sun " + std::to_string(travel.z) +
                                          ", ground up " + std::to_string(groundUp);
                const Drawn both = drawMap(**renderer, cam, sun, *setup, core::CasterCull::None);
                const Drawn closed = drawMap(**renderer, cam, sun, *setup, core::CasterCull::BackOfClosed);
                EXPECT_TRUE(closed.map.rgba == both.map.rgba) << where << ": BackOfClosed changed the map";
                EXPECT_LT(closed.samples, both.samples) << where;
                // Back culls every single-sided face turned away from the sun: the same map as long
                // as the open ground faces the sun; a ground facing away is gone from the map.
                const Drawn back = drawMap(**renderer, cam, sun, *setup, core::CasterCull::Back);
                EXPECT_EQ(back.map.rgba == both.map.rgba, groundUp > 0) << where << ": Back";
            }
        }
    }
}
