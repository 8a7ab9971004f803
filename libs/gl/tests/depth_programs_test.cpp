// The sun's depth programs (sun_pass.h, depth.frag): opaque and alpha-tested casters in the
// hyperbolic layout are drawn by programs that never write gl_FragDepth, so early and
// hierarchical depth tests stay on for every caster fragment; only the linear layout, whose
// depth is computed per fragment, writes it. Checked by program introspection (a written
// gl_FragDepth is an active program output), so a write slipped back in — even
// `gl_FragDepth = gl_FragCoord.z` on a path no uniform takes — fails here on any GL.
// CTest label `gl`.
#include "headless_gl_test.h"

#include "sun_pass.h"

#include "shadowkit/gl/renderer.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class DepthProgramsTest : public gl::testing::HeadlessGlTest {};

bool writesFragmentDepth(GLuint program) {
    return glGetProgramResourceIndex(program, GL_PROGRAM_OUTPUT, "gl_FragDepth") != GL_INVALID_INDEX;
}

} // namespace

TEST_F(DepthProgramsTest, OnlyTheLinearLayoutsDepthProgramsWriteFragmentDepth) {
    auto pass = gl::SunPass::create();
    ASSERT_TRUE(pass) << pass.error();
    for (const core::DepthLayout layout : {core::DepthLayout::Hyperbolic, core::DepthLayout::Linear}) {
        const gl::PassPrograms programs = (*pass)->programsFor(layout);
        const bool linear = layout == core::DepthLayout::Linear;
        ASSERT_NE(programs.plain, 0u);
        ASSERT_NE(programs.material, 0u);
        EXPECT_EQ(writesFragmentDepth(programs.plain), linear) << "opaque casters, layout " << int(layout);
        EXPECT_EQ(writesFragmentDepth(programs.material), linear) << "alpha-tested casters, layout " << int(layout);
    }
}

TEST_F(DepthProgramsTest, StackedCastersDrawnNearestFirstWriteEachTexelOnce) {
    // The counter against a count known without it: a ground quad wider than the focus body
    // covers every texel of the focused map; a roof over half of it, in a later batch, is
    // nearer the light and drawn first (PassLists::nearestFirst), so the ground under it is
    // rejected: every texel written exactly once. In batch order it would be 1.5 per texel.
    scene::Scene s;
    scene::Mesh ground, roof;
    const auto quad = [](scene::Mesh& m, float y, float x0, float x1) {
        m.vertices = {{{x0, y, -10}}, {{x1, y, -10}}, {{x1, y, 10}}, {{x0, y, 10}}};
        for (scene::Vertex& v : m.vertices) v.normal = {0, 1, 0}, v.albedo = glm::vec3(0.8f);
        m.indices = {0, 2, 1, 0, 3, 2};
        m.computeBounds();
    };
    quad(ground, 0.0f, -10, 10);
    quad(roof, 2.0f, -10, 0);
    s.meshes = {ground, roof};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 30, 0.01};
    camera.wsDirection = {0, -1, 0};
    camera.wsUp = {0, 0, -1};
    camera.fovYDegrees = 90;
    camera.zNear = 1, camera.zFar = 100;
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 32;
    settings.bias = core::BiasSettings{.cull = core::CasterCull::None};
    // The box reaches a metre below the ground: a caster on the box's far face would store the
    // cleared depth (1) and fail GL_LESS.
    const core::Aabb bounds = core::Aabb::fromMinMax(core::Vec3(-10, -1, -10), core::Vec3(10, 3, 10));
    const auto setup = core::computeShadowSetup({.camera = camera,
                                                 .light = sun,
                                                 .wsSceneBounds = bounds,
                                                 .technique = core::Technique::Focused,
                                                 .mapSize = 64});
    ASSERT_TRUE(setup);
    auto stats = (*renderer)->render(camera, sun, *setup, settings);
    ASSERT_TRUE(stats) << stats.error();
    ASSERT_EQ(stats->shadow.mapTexels, 64u * 64u);
    EXPECT_EQ(stats->shadow.samplesPassed, 64u * 64u);
}
