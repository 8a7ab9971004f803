// Where a receiver drawn at a coarser level of detail looks itself up in the shadow map
// (shadow_lookup.glsl, receiverLookup; gpu_scene.cpp, rangesOf): a simplified surface moves its
// lookup its error towards the light, so that it does not shadow itself against the true surface
// the map holds; a level that keeps coverage (cards, billboard clouds: leaves moved within their
// slabs, as many above the plane as below) looks itself up where it lies, so the leaves above it
// still shade it. CTest label `gl`.
#include "headless_gl_test.h"

#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class ReceiverLookupTest : public gl::testing::HeadlessGlTest {};

// A horizontal quad of half-size `half` at height `y`.
scene::Mesh quad(float y, float half) {
    scene::Mesh m;
    m.vertices = {{{-half, y, -half}}, {{half, y, -half}}, {{half, y, half}}, {{-half, y, half}}};
    for (scene::Vertex& v : m.vertices) v.normal = {0, 1, 0}, v.albedo = glm::vec3(0.8f);
    m.indices = {0, 2, 1, 0, 3, 2};
    m.computeBounds();
    return m;
}

// The shadow term of the ground 3.25 m from its middle, in the shadow of a roof 0.5 m above the
// ground that ends at 3 m (the sun 45° up: the shadow reaches 3.5 m; the roof lies 0.71 m away
// along the ray), where the camera draws the ground at its one coarser level: the same two
// triangles, erring 1 m, keeping coverage or not.
float shadowBesideTheRoof(bool keepsCoverage) {
    scene::Scene s;
    scene::Mesh ground = quad(0.0f, 10.0f);
    ground.authoredLods.push_back({ground.indices, 1.0f, keepsCoverage});
    s.meshes = {ground, quad(0.5f, 3.0f)};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    auto renderer = gl::Renderer::create(s);
    EXPECT_TRUE(renderer) << renderer.error();
    if (!renderer) return -1.0f;
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 30, 0.01};
    camera.wsDirection = {0, -1, 0};
    camera.wsUp = {0, 0, -1};
    camera.fovYDegrees = 40; // 7 cm a pixel on the ground
    camera.zNear = 1, camera.zFar = 100;
    const core::DirectionalLight sun{glm::normalize(core::Vec3(1.0, -1.0, 0.0))};
    gl::RenderSettings settings;
    settings.width = settings.height = 320;
    // The coarser level wherever the ground is seen: its 1 m projects to 15 pixels here.
    settings.lodPixelError = 16.0f;
    settings.lodFoliageScale = 16.0f;
    const auto setup = core::computeShadowSetup({.camera = camera,
                                                 .light = sun,
                                                 .wsSceneBounds = s.wsBounds(),
                                                 .technique = core::Technique::Focused,
                                                 .mapSize = 2048});
    EXPECT_TRUE(setup);
    if (!setup) return -1.0f;
    const auto buffers = (*renderer)->renderEvalBuffers(camera, sun, *setup, settings);
    EXPECT_TRUE(buffers) << buffers.error();
    if (!buffers) return -1.0f;
    EXPECT_EQ((*renderer)->levelsDrawn().camera.at(0), 1u) << "the ground drawn at its coarser level";
    const core::Vec4 clip = camera.clipFromWorld() * core::Vec4(3.25, 0.0, 0.0, 1.0);
    const int x = int((clip.x / clip.w * 0.5 + 0.5) * settings.width);
    const int y = int((0.5 - clip.y / clip.w * 0.5) * settings.height); // the top row first
    const size_t pixel = buffers->index(x, y);
    EXPECT_EQ(buffers->surfaceId[pixel], 1u) << "the ground, beside the roof";
    return buffers->shadowTerm[pixel];
}

} // namespace

TEST_F(ReceiverLookupTest, ASimplifiedReceiverMovesItsLookupByItsErrorALevelKeepingCoverageDoesNot) {
    EXPECT_EQ(shadowBesideTheRoof(true), 0.0f) << "leaves moved within their slabs: shaded by the roof";
    EXPECT_EQ(shadowBesideTheRoof(false), 1.0f) << "a surface that may lie 1 m low: looked up past the roof";
}
