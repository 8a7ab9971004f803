// The sun's depth programs (sun_pass.h, depth.frag): opaque and alpha-tested casters in the
// hyperbolic layout are drawn by programs that never write gl_FragDepth, so early and
// hierarchical depth tests stay on for every caster fragment; only the linear layout, whose
// depth is computed per fragment, writes it. Checked by program introspection (a written
// gl_FragDepth is an active program output), so a write slipped back in — even
// `gl_FragDepth = gl_FragCoord.z` on a path no uniform takes — fails here on any GL.
// CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "program.h"
#include "sun_pass.h"
#include "uniforms.h"

#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/leafy_trees.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
    // The fixed maps drawn together (hyperbolic alone), where the GL can.
    const gl::PassPrograms together = (*pass)->mapsTogetherPrograms();
    for (const GLuint program : {together.plain, together.material})
        if (program) {
            EXPECT_FALSE(writesFragmentDepth(program)) << "the maps drawn together";
        }
}

namespace {

// A ground quad under a roof over part of it, the roof in the later batch: drawn in batch
// order, every texel under the roof is written twice.
scene::Scene groundAndRoof(const core::Vec2& groundHalfXZ, const core::Vec4& roofXZ, float roofY) {
    scene::Scene s;
    scene::Mesh ground, roof;
    const auto quad = [](scene::Mesh& m, float y, float x0, float x1, float z0, float z1) {
        m.vertices = {{{x0, y, z0}}, {{x1, y, z0}}, {{x1, y, z1}}, {{x0, y, z1}}};
        for (scene::Vertex& v : m.vertices) v.normal = {0, 1, 0}, v.albedo = glm::vec3(0.8f);
        m.indices = {0, 2, 1, 0, 3, 2};
        m.computeBounds();
    };
    const auto gx = float(groundHalfXZ.x), gz = float(groundHalfXZ.y);
    quad(ground, 0.0f, -gx, gx, -gz, gz);
    quad(roof, roofY, float(roofXZ.x), float(roofXZ.y), float(roofXZ.z), float(roofXZ.w));
    s.meshes = {ground, roof};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}};
    return s;
}

// The shadow pass's samples and texels for one frame of `s`.
gl::PassStats shadowPassOf(const scene::Scene& s, const core::PerspectiveCamera& camera,
                           const core::DirectionalLight& sun, const core::Aabb& bounds, core::Technique technique) {
    auto renderer = gl::Renderer::create(s);
    EXPECT_TRUE(renderer) << renderer.error();
    if (!renderer) return {};
    gl::RenderSettings settings;
    settings.width = settings.height = 32;
    settings.bias = core::BiasSettings{.cull = core::CasterCull::None};
    const auto setup = core::computeShadowSetup(
        {.camera = camera, .light = sun, .wsSceneBounds = bounds, .technique = technique, .mapSize = 64});
    EXPECT_TRUE(setup) << setup.error();
    if (!setup) return {};
    auto stats = (*renderer)->render(camera, sun, *setup, settings);
    EXPECT_TRUE(stats) << stats.error();
    return stats ? stats->shadow : gl::PassStats{};
}

} // namespace

TEST_F(DepthProgramsTest, StackedCastersDrawnNearestFirstWriteEachTexelOnce) {
    // The counter against a count known without it: a ground quad wider than the focus body
    // covers every texel of the focused map; a roof over half of it, in a later batch, is
    // nearer the light and drawn first (PassLists::nearestFirst), so the ground under it is
    // rejected: every texel written exactly once. In batch order it would be 1.5 per texel. The
    // same when the roof is an alpha-tested card (its texture wholly covered), drawn by the other
    // program: in the order, not after every opaque batch as a camera pass draws them.
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 30, 0.01};
    camera.wsDirection = {0, -1, 0};
    camera.wsUp = {0, 0, -1};
    camera.fovYDegrees = 90;
    camera.zNear = 1, camera.zFar = 100;
    // The box reaches a metre below the ground: a caster on the box's far face would store the
    // cleared depth (1) and fail GL_LESS.
    const core::Aabb bounds = core::Aabb::fromMinMax(core::Vec3(-10, -1, -10), core::Vec3(10, 3, 10));
    for (const bool alphaTested : {false, true}) {
        scene::Scene s = groundAndRoof({10, 10}, {-10, 0, -10, 10}, 2.0f);
        if (alphaTested) {
            scene::Image covered;
            covered.width = covered.height = 1;
            covered.rgba = {200, 200, 200, 255};
            s.textures = {scene::Texture{.image = std::move(covered)}};
            s.materials = {scene::Material{.name = "card",
                                           .baseColorTexture = 0,
                                           .alphaMode = scene::AlphaMode::Mask,
                                           .alphaCutoff = 0.5f,
                                           .doubleSided = true}};
            s.meshes[1].material = 0;
        }
        const gl::PassStats pass =
            shadowPassOf(s, camera, core::DirectionalLight{{0, -1, 0}}, bounds, core::Technique::Focused);
        ASSERT_EQ(pass.mapTexels, 64u * 64u);
        EXPECT_EQ(pass.samplesPassed, 64u * 64u) << (alphaTested ? "an alpha-tested roof" : "an opaque roof");
    }
}

TEST_F(DepthProgramsTest, ARoofOverPartOfAWideGroundIsDrawnBeforeIt) {
    // Nearest first means nearer the sun on each ray, and a batch's centre says little of that
    // when batches differ in extent. Seen level with the sun 25 degrees up behind the viewer
    // (LiSPSM's duelling frusta), a roof 3 m up over the far part of a wide ground: the ground's
    // centre lies nearer the sun than the roof's, both along the light and in the warped map's
    // depth (the two orders tried before), so the ground was drawn first and every texel under
    // the roof written twice. By height, the order every ray of a sun above the horizon keeps,
    // the roof goes first. One quad over another: no texel needs two writes.
    // The ground spans LiSPSM's w = 0 plane (its far corners lie behind the warp's projection
    // centre): on NVIDIA's driver (580, an H200) glPolygonOffset's constant units pushed it out
    // of the map under depth clamping, 710 samples (the roof alone) against llvmpipe's 3,982,
    // which is why the constant term moved into depth.vert (not yet re-run on that driver).
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 1.8, 0};
    camera.wsDirection = {0, 0, -1};
    camera.wsUp = {0, 1, 0};
    camera.fovYDegrees = 60;
    camera.zNear = 0.5, camera.zFar = 150;
    const double elevation = glm::radians(25.0);
    const core::DirectionalLight sun{-core::Vec3(0, std::sin(elevation), std::cos(elevation))};
    const core::Aabb bounds = core::Aabb::fromMinMax(core::Vec3(-50, -1, -100), core::Vec3(50, 4, 20));
    // The virtual clipmap's pages take the same order: its first frame draws every page it needs,
    // each page's texels (guard bands and all) counted.
    for (const core::Technique technique : {core::Technique::Lispsm, core::Technique::Tsm, core::Technique::Virtual}) {
        const gl::PassStats pass =
            shadowPassOf(groundAndRoof({400, 400}, {-50, 50, -100, -40}, 3.0f), camera, sun, bounds, technique);
        if (technique != core::Technique::Virtual) {
            ASSERT_EQ(pass.mapTexels, 64u * 64u);
        }
        ASSERT_GT(pass.mapTexels, 0u) << core::techniqueName(technique);
        EXPECT_GT(pass.samplesPassed, pass.mapTexels / 4)
            << core::techniqueName(technique) << ": the roof and ground must fill much of the map";
        EXPECT_LE(pass.samplesPassed, pass.mapTexels) << core::techniqueName(technique);
    }
}

namespace {

// One leafy broadleaf tree, 10 m high, its leaves alone (every card: no levels), in the order
// the tree brings them or with its cards reversed.
scene::Scene oneCanopy(bool reversed) {
    scene::LeafyTree tree = scene::makeLeafyTree(scene::TreeSpecies::Broadleaf, 1);
    tree.leaves.authoredLods.clear();
    tree.leaves.material = 0;
    if (reversed) { // a card is two triangles, six indices, that stay together
        std::vector<uint32_t>& indices = tree.leaves.indices;
        std::vector<uint32_t> back;
        for (size_t card = indices.size() / 6; card-- > 0;)
            back.insert(back.end(), indices.begin() + std::ptrdiff_t(6 * card),
                        indices.begin() + std::ptrdiff_t(6 * card + 6));
        indices = std::move(back);
    }
    scene::Scene s;
    s.textures.push_back(scene::makeLeafAtlas());
    s.materials.push_back(scene::leafMaterial(0));
    s.meshes = {tree.leaves};
    s.batches = {{0, {glm::scale(glm::mat4(1.0f), glm::vec3(10.0f))}, false}};
    return s;
}

// Samples the canopy's shadow pass wrote per map texel it covers, the sun `elevation` degrees
// up; the map, as greys, in `map`.
double samplesPerCoveredTexel(const scene::Scene& s, double elevation, scene::Image& map) {
    auto renderer = gl::Renderer::create(s);
    EXPECT_TRUE(renderer) << renderer.error();
    if (!renderer) return 0.0;
    core::PerspectiveCamera camera;
    camera.wsEye = {0, 8, 25};
    camera.wsDirection = glm::normalize(core::Vec3(0, -0.1, -1));
    camera.wsUp = {0, 1, 0};
    camera.zNear = 0.5, camera.zFar = 100;
    const double e = glm::radians(elevation);
    const core::DirectionalLight sun{glm::normalize(core::Vec3(std::cos(e), -std::sin(e), 0.3))};
    gl::RenderSettings settings;
    settings.width = settings.height = 64;
    settings.lod = false;
    const auto setup = core::computeShadowSetup({.camera = camera,
                                                 .light = sun,
                                                 .wsSceneBounds = s.wsBounds(),
                                                 .technique = core::Technique::Focused,
                                                 .mapSize = 512});
    EXPECT_TRUE(setup);
    if (!setup) return 0.0;
    auto stats = (*renderer)->render(camera, sun, *setup, settings);
    EXPECT_TRUE(stats) << stats.error();
    if (!stats) return 0.0;
    map = (*renderer)->readShadowMap(); // empty texels black
    size_t covered = 0;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) covered += map.pixel(x, y)[0] != 0;
    EXPECT_GT(covered, 1000u);
    return covered > 0 ? double(stats->shadow.samplesPassed) / double(covered) : 0.0;
}

} // namespace

// A leafy tree's cards come highest first (leafy_trees.cpp), so a shadow pass under a sun above
// the horizon meets the upper leaves before those they hide and rejects these. The same cards
// reversed (lowest first: each leaf written, then overwritten) draw the same map with three
// times the samples — the counter sees the order. Measured when written, highest first 1.12,
// 1.17 and 1.26 samples per covered texel with the sun 80°, 45° and 25° up; reversed 3.5–4.1;
// in the order the cards grew (before they were sorted) 1.92–2.16.
TEST_F(DepthProgramsTest, ALeafyCanopysCardsHighestFirstWriteItsTexelsNearlyOnce) {
    const scene::Scene highestFirst = oneCanopy(false), lowestFirst = oneCanopy(true);
    for (const double elevation : {80.0, 45.0, 25.0}) {
        scene::Image map, reversedMap;
        EXPECT_LT(samplesPerCoveredTexel(highestFirst, elevation, map), 1.4) << elevation << " degrees";
        EXPECT_GT(samplesPerCoveredTexel(lowestFirst, elevation, reversedMap), 2.5) << elevation << " degrees";
        EXPECT_EQ(map.rgba, reversedMap.rgba) << elevation << " degrees: the order changes no texel";
    }
}

// The linear layout writes its depth per fragment and promises the GL it is never less than the
// rasterised one (depth.frag's layout(depth_greater)), the rasterised depth built as a bound from
// the longest edge of each vertex's triangles and the warp's change of w along it (depth_pass.glsl's
// skConservativeClipZ): a GPU's early depth test then rejects covered fragments before they are
// shaded. A broken promise would be holes in a GPU's map, not in llvmpipe's, so the programs count
// it (CheckingConservativeDepth): on TSM's maps of both forests (instanced trees of two and three
// species at their own scales, their levels down to billboard clouds, rocks, buildings, movers, a
// terrain of the default's 4 m cells drawn by clusters) from four views, no fragment's written
// depth lies in front of its rasterised one. And the bound is of use: most fragments' lies within
// 5 m of the written depth, so a fragment more than that behind a stored caster (a terrain under
// a canopy) is rejected early — a bound of 0 everywhere would keep the promise and reject nothing.
// Measured when written: 0 broken; within 5 m 35–37 % of the fragments on `paper` (TSM's texels
// crowd near its apex, where w changes fastest across a triangle), 97–99.6 % on the other views,
// 87 % of all; within a metre 8–10 % and 44–75 %.
TEST_F(DepthProgramsTest, TheLinearLayoutsRasterisedDepthIsABoundOfTheDepthItWrites) {
    const gl::CheckingConservativeDepth checking; // programs built from here count
    GLuint counters = 0;
    glCreateBuffers(1, &counters);
    const GLuint zeros[4] = {0, 0, 0, 0};
    glNamedBufferStorage(counters, sizeof zeros, zeros, GL_DYNAMIC_STORAGE_BIT);
    double fragments = 0.0, withinFiveMetres = 0.0;
    for (const bool leafy : {false, true}) {
        // Both with the default forest's 4 m terrain cells (1,024 m in 256), over 200 m.
        scene::ForestOptions options;
        options.kind = leafy ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
        options.trees = leafy ? 200 : 400, options.terrainSize = 200, options.terrainResolution = 50;
        options.rocks = 4, options.buildings = 2, options.movers = 2;
        const scene::Scene forest = scene::makeForest(options);
        auto renderer = gl::Renderer::create(forest);
        ASSERT_TRUE(renderer) << renderer.error();
        for (const char* name : {"paper", "perpendicular", "sun-behind", "aerial"}) {
            scene::ResolvedView view = gl::testing::standardView(forest, name);
            view.setSize(96, 54);
            const auto setup = core::computeShadowSetup({.camera = view.camera,
                                                         .light = view.light,
                                                         .wsSceneBounds = forest.wsBounds(),
                                                         .technique = core::Technique::Tsm,
                                                         .mapSize = 256});
            ASSERT_TRUE(setup) << setup.error();
            ASSERT_EQ(setup->depthLayout, core::DepthLayout::Linear);
            glNamedBufferSubData(counters, 0, sizeof zeros, zeros);
            glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, gl::kConservativeDepthCheckBinding, counters);
            gl::RenderSettings settings;
            settings.width = 96, settings.height = 54;
            ASSERT_TRUE((*renderer)->render(view.camera, view.light, *setup, settings));
            GLuint counted[4] = {}; // fragments, promises broken, bounds within 1 m, within 5 m
            glGetNamedBufferSubData(counters, 0, sizeof counted, counted);
            const std::string where = std::string(leafy ? "leafy forest, " : "forest, ") + name;
            EXPECT_GT(counted[0], 10000u) << where << ": the depth pass drew";
            EXPECT_EQ(counted[1], 0u) << where << ": fragments whose written depth lies in front of the rasterised";
            EXPECT_GT(double(counted[3]), 0.25 * double(counted[0])) << where << ": bounds within 5 m";
            fragments += counted[0], withinFiveMetres += counted[3];
        }
    }
    EXPECT_GT(withinFiveMetres, 0.8 * fragments) << "bounds within 5 m, every view";
    glDeleteBuffers(1, &counters);
}

// The local lights' maps store the distance to the light per fragment (local_depth.frag) and make
// the same promise, the vertex stages rasterising each vertex at its distance less the longest edge
// of its triangles, or the geometry stage each triangle at the larger of its farthest vertex's
// distance less its longest edge and its plane's distance (local_depth.glsl's
// skLocalConservativeClipZ). On the leafy forest at night, a point light's six faces and a spot
// light among the trees, written each way the renderer can (one layered pass from the vertex stage,
// from a geometry stage, a pass a face): no fragment's written distance lies in front of its
// rasterised one (without the margin 88 % would), and most bounds lie within 5 m of it. Measured
// when written: 0 broken; within 5 m 88 % of the fragments from the vertex stage and 99 % from the
// geometry stage, which bounds each triangle whole; within a metre 33–35 % and 61 %.
TEST_F(DepthProgramsTest, TheLocalLightsRasterisedDepthIsABoundOfTheDistanceTheyWrite) {
    const gl::CheckingConservativeDepth checking;
    GLuint counters = 0;
    glCreateBuffers(1, &counters);
    const GLuint zeros[4] = {0, 0, 0, 0};
    glNamedBufferStorage(counters, sizeof zeros, zeros, GL_DYNAMIC_STORAGE_BIT);
    scene::ForestOptions options;
    options.kind = scene::ForestKind::Leafy;
    options.trees = 200, options.terrainSize = 200, options.terrainResolution = 50;
    options.rocks = 4, options.buildings = 2, options.movers = 0;
    const scene::Scene forest = scene::makeForest(options);
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    scene::ResolvedView view = gl::testing::standardView(forest, "perpendicular");
    view.setSize(96, 54);
    const core::Vec3 wsAhead = view.camera.wsEye + 25.0 * glm::normalize(view.camera.wsDirection);
    const core::PointLight point{.wsPosition = wsAhead + core::Vec3(0, 6, 0), .range = 40};
    const core::SpotLight spot{
        .wsPosition = wsAhead + core::Vec3(8, 14, 0), .wsDirection = {-0.3, -1, 0.2}, .range = 50};
    auto lighting =
        core::computeLocalLighting({.camera = view.camera, .wsSceneBounds = forest.wsBounds(), .mapSize = 256},
                                   std::vector{point}, std::vector{spot});
    ASSERT_TRUE(lighting) << lighting.error();
    ASSERT_TRUE((*renderer)->setLocalLights(*lighting));
    const auto sun = core::computeShadowSetup(
        {.camera = view.camera, .light = view.light, .wsSceneBounds = forest.wsBounds(), .mapSize = 64});
    ASSERT_TRUE(sun) << sun.error();
    for (const gl::LocalPass pass : {gl::LocalPass::VertexLayer, gl::LocalPass::Geometry, gl::LocalPass::PerFace}) {
        glNamedBufferSubData(counters, 0, sizeof zeros, zeros);
        glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, gl::kConservativeDepthCheckBinding, counters);
        gl::RenderSettings settings;
        settings.width = 96, settings.height = 54;
        settings.sun = false; // night: the sun's linear maps would count too
        settings.localPass = pass;
        ASSERT_TRUE((*renderer)->render(view.camera, view.light, *sun, settings));
        GLuint counted[4] = {}; // fragments, promises broken, bounds within 1 m, within 5 m
        glGetNamedBufferSubData(counters, 0, sizeof counted, counted);
        const std::string where = gl::localPassName(pass);
        EXPECT_GT(counted[0], 10000u) << where << ": the lights' depth passes drew";
        EXPECT_EQ(counted[1], 0u) << where << ": fragments whose written distance lies in front of the rasterised";
        EXPECT_GT(double(counted[3]), 0.5 * double(counted[0])) << where << ": bounds within 5 m";
    }
    glDeleteBuffers(1, &counters);
}
