// Spot and point lights on the GPU (local_shadows.h): a caster's shadow lands where it must on
// every cube face, a spot light lights nothing outside its cone, the three ways of writing a
// cube give the same maps, and faces that see nothing of the view are not drawn. CTest label `gl`.
#include "headless_gl_test.h"
#include "test_scenes.h"

#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace shadowkit;

namespace {

class LocalLightsTest : public gl::testing::HeadlessGlTest {};

constexpr int kImage = 160;

// A scene of boxes (centre, half extents), each its own static mesh.
scene::Scene boxes(const std::vector<std::pair<core::Vec3, core::Vec3>>& list) {
    scene::Scene s;
    for (const auto& [centre, half] : list) {
        scene::Mesh mesh;
        scene::addBox(mesh, glm::translate(glm::mat4(1.0f), glm::vec3(centre)), glm::vec3(half), glm::vec3(0.8f));
        mesh.computeBounds();
        s.batches.push_back({static_cast<uint32_t>(s.meshes.size()), {glm::mat4(1.0f)}, false});
        s.meshes.push_back(std::move(mesh));
    }
    return s;
}

core::PerspectiveCamera looking(const core::Vec3& eye, const core::Vec3& at, const core::Vec3& up) {
    core::PerspectiveCamera cam;
    cam.wsEye = eye;
    cam.wsDirection = glm::normalize(at - eye);
    cam.wsUp = up;
    cam.aspect = 1.0;
    cam.zNear = 0.1;
    cam.zFar = 100.0;
    return cam;
}

// The pixel (top row first) showing world point ws.
std::pair<int, int> pixelOf(const core::PerspectiveCamera& cam, const core::Vec3& ws) {
    const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(ws, 1.0);
    return {static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * kImage), static_cast<int>((0.5 - cs.y / cs.w * 0.5) * kImage)};
}

gl::RenderSettings nightSettings(gl::LocalPass pass = gl::LocalPass::Layered) {
    gl::RenderSettings settings;
    settings.width = settings.height = kImage;
    settings.fogDensity = 0.0f;
    settings.sun = false;
    settings.localPass = pass;
    return settings;
}

// The sun's set-up is still required by the renderer's interface; at night it is not drawn.
core::ShadowSetup sunSetup(const core::PerspectiveCamera& cam, const core::Aabb& bounds) {
    return core::computeShadowSetup({.camera = cam, .light = {}, .wsSceneBounds = bounds, .mapSize = 64}).value();
}

core::LocalLighting lighting(const core::PerspectiveCamera& cam, const core::Aabb& bounds,
                             std::vector<core::PointLight> points, std::vector<core::SpotLight> spots,
                             int mapSize = 256) {
    auto l = core::computeLocalLighting({.camera = cam, .wsSceneBounds = bounds, .mapSize = mapSize}, points, spots);
    EXPECT_TRUE(l) << l.error();
    return *l;
}

} // namespace

TEST_F(LocalLightsTest, ABoxBesideAPointLightShadowsTheWallBehindItOnEveryCubeFace) {
    // Light at the origin; for each axis a, a wall across a at 8 m and a 1 m cube at 3 m along
    // a, 0.8 m off the axis along v: its shadow's centre lies on the wall 8/3 × 0.8 m off the
    // axis on the same side. Off-axis, so a face mirrored or turned would put it elsewhere.
    const core::Vec3 light(0.0);
    for (int face = 0; face < 6; ++face) {
        const core::Vec3 a = core::cubeFaces()[static_cast<size_t>(face)].wsAxis;
        const core::Vec3 u = std::abs(a.y) > 0.5 ? core::Vec3(1, 0, 0) : core::Vec3(0, 1, 0);
        const core::Vec3 v = glm::cross(a, u);
        const core::Vec3 wallHalf = 10.0 * (core::Vec3(1.0) - glm::abs(a)) + 0.1 * glm::abs(a);
        scene::Scene s = boxes({{8.1 * a, wallHalf}, {3.0 * a + 0.8 * v, core::Vec3(0.5)}});
        auto renderer = gl::Renderer::create(s);
        ASSERT_TRUE(renderer) << renderer.error();
        const core::Vec3 shadowCentre = 8.0 * a + (8.0 / 3.0) * 0.8 * v, mirrored = 8.0 * a - (8.0 / 3.0) * 0.8 * v;
        // Seen from beside the light, clear of the cube.
        const core::PerspectiveCamera cam =
            looking(6.0 * u + 1.0 * a, 8.0 * a, std::abs(a.y) > 0.5 ? core::Vec3(0, 0, 1) : core::Vec3(0, 1, 0));
        ASSERT_TRUE((*renderer)->setLocalLights(
            lighting(cam, (*renderer)->wsSceneBounds(), {{.wsPosition = light, .range = 30.0}}, {})));
        const gl::RenderSettings settings = nightSettings();
        auto raster = (*renderer)->renderEvalBuffers(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), settings, 0);
        ASSERT_TRUE(raster) << raster.error();
        auto termAt = [&](const core::Vec3& ws) {
            const auto [x, y] = pixelOf(cam, ws);
            const size_t i = static_cast<size_t>(y) * kImage + static_cast<size_t>(x);
            EXPECT_EQ(raster->surfaceId[i], 1u) << "face " << face << ": the wall must be seen there";
            return raster->shadowTerm[i];
        };
        EXPECT_LT(termAt(shadowCentre), 0.5f) << "face " << face << ": the cube's shadow is missing";
        EXPECT_GT(termAt(mirrored), 0.5f) << "face " << face << ": shadow on the mirrored side";
        EXPECT_GT(termAt(8.0 * a + 3.0 * u), 0.5f) << "face " << face << ": shadow beside it";
    }
}

TEST_F(LocalLightsTest, ASpotLightsNothingOutsideItsConeAndShadowsInsideIt) {
    // A 40° spot 5 m above the ground pointing down lights a disc of radius 5 tan 20° = 1.82 m;
    // a cube at 2.5 m, 0.8 m off the axis, shadows the ground 1.6 m off it.
    scene::Scene s =
        boxes({{core::Vec3(0, -0.1, 0), core::Vec3(20, 0.1, 20)}, {core::Vec3(0.8, 2.5, 0), core::Vec3(0.3)}});
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = looking({0, 12, 9}, {0, 0, 0}, {0, 1, 0});
    const core::SpotLight spot{.wsPosition = {0, 5, 0}, .wsDirection = {0, -1, 0}, .coneDegrees = 40.0, .range = 30.0};
    ASSERT_TRUE((*renderer)->setLocalLights(lighting(cam, (*renderer)->wsSceneBounds(), {}, {spot})));
    ASSERT_TRUE((*renderer)->render(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), nightSettings()));
    const scene::Image image = (*renderer)->readColor();
    auto luminance = [&](const core::Vec3& ws) {
        const auto [x, y] = pixelOf(cam, ws);
        const uint8_t* p = image.pixel(x, y);
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    };
    const double dark = luminance({8, 0, 0}); // far outside: ambient alone
    EXPECT_GT(luminance({-1.2, 0, 0}), dark + 40.0) << "inside the cone, in the open: lit";
    EXPECT_NEAR(luminance({1.6, 0, 0}), dark, 3.0) << "inside the cone, behind the cube: shadowed";
    for (const core::Vec3& outside : {core::Vec3(2.3, 0, 0), core::Vec3(0, 0, -2.3), core::Vec3(-1.7, 0, 1.7)})
        EXPECT_NEAR(luminance(outside), dark, 3.0) << "outside the cone: not lit at " << outside.x << ", " << outside.z;
}

TEST_F(LocalLightsTest, VertexLayerGeometryShaderAndSixPassesWriteTheSameCube) {
    scene::Scene s = boxes({{core::Vec3(0, -0.1, 0), core::Vec3(20, 0.1, 20)},
                            {core::Vec3(2, 1, 0), core::Vec3(0.5)},
                            {core::Vec3(-1, 2, 2), core::Vec3(0.4)},
                            {core::Vec3(0, 5, -2), core::Vec3(0.6)}});
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = looking({0, 6, 10}, {0, 1, 0}, {0, 1, 0});
    ASSERT_TRUE((*renderer)->setLocalLights(
        lighting(cam, (*renderer)->wsSceneBounds(), {{.wsPosition = {0, 3, 0}, .range = 20.0}}, {})));
    const core::ShadowSetup sun = sunSetup(cam, (*renderer)->wsSceneBounds());
    std::vector<scene::Image> maps;
    for (const gl::LocalPass pass : {gl::LocalPass::VertexLayer, gl::LocalPass::Geometry, gl::LocalPass::PerFace}) {
        auto stats = (*renderer)->render(cam, {}, sun, nightSettings(pass));
        ASSERT_TRUE(stats) << stats.error();
        EXPECT_GT(stats->local.triangles, 0u) << gl::localPassName(pass);
        maps.push_back((*renderer)->readLocalShadowMaps());
    }
    ASSERT_GT(maps[0].width, 0);
    EXPECT_TRUE(maps[0].rgba == maps[1].rgba) << "geometry shader differs from the vertex layer";
    EXPECT_TRUE(maps[0].rgba == maps[2].rgba) << "six passes differ from one layered pass";
}

TEST_F(LocalLightsTest, FacesThatSeeNothingOfTheViewAreNotDrawnAndLightsOutOfRangeDrawNothing) {
    scene::Scene s = boxes({{core::Vec3(0, -0.1, 0), core::Vec3(50, 0.1, 50)}, {core::Vec3(0, 1, -10), core::Vec3(1)}});
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    // Looking along −Z from z = 0: a lamp 3 m behind the eye sees the view only through its
    // −Z side (and down, up and sideways into the frustum); +Z looks away from everything.
    const core::PerspectiveCamera cam = looking({0, 1.8, 0}, {0, 1.8, -10}, {0, 1, 0});
    const core::PointLight behind{.wsPosition = {0, 3, 3}, .range = 30.0},
        far{.wsPosition = {0, 3, 200}, .range = 10.0};
    ASSERT_TRUE((*renderer)->setLocalLights(lighting(cam, (*renderer)->wsSceneBounds(), {behind, far}, {})));
    auto stats = (*renderer)->render(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), nightSettings());
    ASSERT_TRUE(stats) << stats.error();
    const core::LocalLighting& lights = (*renderer)->localLights();
    EXPECT_GE(lights.pointSetups[0].skippedFaces, 1);
    for (const core::ShadowView& view : lights.pointSetups[0].views)
        EXPECT_NE(view.face, 4) << "+Z sees nothing of the view";
    EXPECT_EQ(lights.pointSetups[1].skippedFaces, 6) << "a light whose range misses the view draws no face";
    EXPECT_EQ(stats->localMaps, static_cast<int>(lights.pointSetups[0].views.size()));
    EXPECT_EQ(stats->skippedFaces, lights.pointSetups[0].skippedFaces + 6);
}

TEST_F(LocalLightsTest, TooManyLightsOrAMissingSetUpIsAnError) {
    scene::Scene s = boxes({{core::Vec3(0), core::Vec3(1)}});
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    core::LocalLighting many;
    many.points.assign(gl::kMaxLocalLightsPerKind + 1, core::PointLight{});
    many.pointSetups.assign(many.points.size(), core::ShadowSetup{});
    auto tooMany = (*renderer)->setLocalLights(many);
    ASSERT_FALSE(tooMany);
    EXPECT_NE(tooMany.error().find("at most"), std::string::npos) << tooMany.error();
    core::LocalLighting missing;
    missing.spots.push_back({});
    EXPECT_FALSE((*renderer)->setLocalLights(missing));
    const core::PerspectiveCamera cam = looking({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    auto bad = (*renderer)->renderEvalBuffers(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), nightSettings(), 3);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().find("local light 3"), std::string::npos) << bad.error();
}

TEST_F(LocalLightsTest, EightPointAndEightSpotLightsEachShadowInOneFrame) {
    // Sixteen lights along a row of posts, each 1 m up and 1.5 m in front of its own post:
    // every light's own post must shadow the ground behind it, in the same frame as all the
    // others (range 4 m: a light reaches no other post's shadow spot).
    constexpr double kSpacing = 2.2;
    std::vector<std::pair<core::Vec3, core::Vec3>> parts = {{core::Vec3(0, -0.1, 0), core::Vec3(30, 0.1, 20)}};
    std::vector<core::PointLight> points;
    std::vector<core::SpotLight> spots;
    for (int i = 0; i < 16; ++i) {
        const double x = kSpacing * (i - 7.5);
        parts.push_back({core::Vec3(x, 0.75, 0), core::Vec3(0.3, 0.75, 0.3)}); // 1.5 m: taller than the light
        const core::Vec3 light(x, 1.0, 1.5);
        if (i % 2 == 0)
            points.push_back({.wsPosition = light, .range = 4.0});
        else
            spots.push_back({.wsPosition = light, .wsDirection = {0, -0.4, -1}, .coneDegrees = 90.0, .range = 4.0});
    }
    const scene::Scene s = boxes(parts);
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam =
        looking({0, 30, 10}, {0, 0, 0}, {0, 1, 0}); // steep: the ground behind each post shows
    ASSERT_TRUE((*renderer)->setLocalLights(lighting(cam, (*renderer)->wsSceneBounds(), points, spots, 128)));
    const core::ShadowSetup sun = sunSetup(cam, (*renderer)->wsSceneBounds());
    auto stats = (*renderer)->render(cam, {}, sun, nightSettings());
    ASSERT_TRUE(stats) << stats.error();
    EXPECT_GE(stats->localMaps, 8 + 8) << "every light drew its map";
    for (int light = 0; light < 16; ++light) {
        const int post = light < 8 ? 2 * light : 2 * (light - 8) + 1; // points first, then spots
        const double x = kSpacing * (post - 7.5);
        auto raster = (*renderer)->renderEvalBuffers(cam, {}, sun, nightSettings(), light);
        ASSERT_TRUE(raster) << raster.error();
        auto termAt = [&](const core::Vec3& ws) {
            const auto [px, py] = pixelOf(cam, ws);
            EXPECT_TRUE(px >= 0 && px < kImage && py >= 0 && py < kImage) << "light " << light << ": out of the image";
            return raster->shadowTerm[static_cast<size_t>(std::clamp(py, 0, kImage - 1)) * kImage +
                                      static_cast<size_t>(std::clamp(px, 0, kImage - 1))];
        };
        EXPECT_LT(termAt({x, 0, -1.6}), 0.5f) << "light " << light << ": no shadow behind its post";
        EXPECT_GT(termAt({x + 1.2, 0, -0.3}), 0.5f) << "light " << light << ": shadow beside its post";
    }
}

TEST_F(LocalLightsTest, GpuCulledListsWriteTheMapsTheCpuListsWrite) {
    // Every local pass, its lists culled on the GPU (the default on a GPU) or on the CPU: the
    // same maps texel for texel and the same instances and triangles written (the GPU's read
    // from its commands). Read late, the local lights' counts come with the GPU's figures: the
    // lists were culled there, not on the CPU.
    std::vector<std::pair<core::Vec3, core::Vec3>> parts = {{core::Vec3(0, -0.1, 0), core::Vec3(30, 0.1, 20)}};
    for (int i = 0; i < 12; ++i) parts.push_back({core::Vec3(2.2 * (i - 5.5), 0.75, 0), core::Vec3(0.3, 0.75, 0.3)});
    const scene::Scene s = boxes(parts);
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = looking({0, 30, 10}, {0, 0, 0}, {0, 1, 0});
    ASSERT_TRUE((*renderer)->setLocalLights(lighting(
        cam, (*renderer)->wsSceneBounds(),
        {{.wsPosition = {-6.6, 1.0, 1.5}, .range = 4.0}, {.wsPosition = {2.2, 1.0, 1.5}, .range = 4.0}},
        {{.wsPosition = {6.6, 1.0, 1.5}, .wsDirection = {0, -0.4, -1}, .coneDegrees = 90.0, .range = 4.0}}, 128)));
    const core::ShadowSetup sun = sunSetup(cam, (*renderer)->wsSceneBounds());
    for (const gl::LocalPass pass : {gl::LocalPass::VertexLayer, gl::LocalPass::Geometry, gl::LocalPass::PerFace}) {
        gl::RenderSettings settings = nightSettings(pass);
        settings.culling = gl::Culling::Frustum;
        auto cpu = (*renderer)->render(cam, {}, sun, settings);
        ASSERT_TRUE(cpu) << cpu.error();
        const scene::Image cpuMaps = (*renderer)->readLocalShadowMaps();
        settings.culling = gl::Culling::Gpu;
        auto gpu = (*renderer)->render(cam, {}, sun, settings);
        ASSERT_TRUE(gpu) << gpu.error();
        const std::string name(gl::localPassName(pass));
        EXPECT_TRUE(cpuMaps.rgba == (*renderer)->readLocalShadowMaps().rgba) << name;
        EXPECT_GT(cpu->local.instances, 0u) << name;
        EXPECT_LT(cpu->local.instances, 3u * 6u * parts.size()) << name << ": the lights' ranges cull";
        EXPECT_EQ(gpu->local.instances, cpu->local.instances) << name;
        EXPECT_EQ(gpu->local.triangles, cpu->local.triangles) << name;

        (*renderer)->readGpuFiguresLate(true);
        auto late = (*renderer)->render(cam, {}, sun, settings);
        ASSERT_TRUE(late);
        const std::vector<gl::GpuFigures> figures = (*renderer)->finishGpuFigures();
        ASSERT_FALSE(figures.empty());
        ASSERT_TRUE(figures.back().localInstances) << name << ": culled on the CPU";
        EXPECT_EQ(*figures.back().localInstances, cpu->local.instances) << name;
        (*renderer)->readGpuFiguresLate(false);
    }
}

TEST_F(LocalLightsTest, ALampDrawsOnlyTheTerrainClustersWithinItsReach) {
    // A large mesh — the ground, 96² quads (18,432 triangles) in clusters of 2,048 — drawn into
    // a lamp's maps by the clusters meeting each list's volume (a spot's or a cube face's clip
    // volume, a layered cube's range box), on the CPU's lists and on the GPU-driven path, which
    // leaves the clustered meshes to the CPU. Every local pass: the same maps texel for texel
    // and the same instances and triangles on both paths, and fewer triangles than the ground
    // alone drawn whole in every map written (a cluster left out lies wholly outside the
    // light's reach; one wrongly left out leaves its texels far).
    const scene::Scene forest = gl::testing::smallForest(300, 200, 96);
    constexpr size_t kGroundTriangles = 2 * 96 * 96;
    auto renderer = gl::Renderer::create(forest);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::Vec3 wsGround = forest.wsOrigin + core::Vec3(0.0, forest.groundHeightAt(0.0, 0.0), 0.0);
    const core::PerspectiveCamera cam = looking(wsGround + core::Vec3(0, 20, 12), wsGround, {0, 1, 0});
    ASSERT_TRUE((*renderer)->setLocalLights(lighting(cam, (*renderer)->wsSceneBounds(),
                                                     {{.wsPosition = wsGround + core::Vec3(-4, 3, 0), .range = 10.0}},
                                                     {{.wsPosition = wsGround + core::Vec3(5, 4, 0),
                                                       .wsDirection = {0, -1, -0.3},
                                                       .coneDegrees = 70.0,
                                                       .range = 10.0}},
                                                     128)));
    const core::ShadowSetup sun = sunSetup(cam, (*renderer)->wsSceneBounds());
    for (const gl::LocalPass pass : {gl::LocalPass::VertexLayer, gl::LocalPass::Geometry, gl::LocalPass::PerFace}) {
        const std::string name(gl::localPassName(pass));
        gl::RenderSettings settings = nightSettings(pass);
        settings.culling = gl::Culling::Frustum;
        auto cpu = (*renderer)->render(cam, {}, sun, settings);
        ASSERT_TRUE(cpu) << name << ": " << cpu.error();
        const scene::Image cpuMaps = (*renderer)->readLocalShadowMaps();
        settings.culling = gl::Culling::Gpu;
        auto gpu = (*renderer)->render(cam, {}, sun, settings);
        ASSERT_TRUE(gpu) << name << ": " << gpu.error();
        EXPECT_TRUE(cpuMaps.rgba == (*renderer)->readLocalShadowMaps().rgba) << name;
        EXPECT_GT(cpu->local.instances, 0u) << name;
        EXPECT_EQ(cpu->local.instances, gpu->local.instances) << name;
        EXPECT_EQ(cpu->local.triangles, gpu->local.triangles) << name;
        ASSERT_GT(cpu->localMaps, 0) << name;
        EXPECT_LT(cpu->local.triangles, size_t(cpu->localMaps) * kGroundTriangles)
            << name << ": the ground drawn whole";
    }
}

namespace {

// The world point on the plane y = 0 that pixel (x, y)'s centre sees (top row first).
core::Vec3 groundSeenBy(const core::PerspectiveCamera& cam, int x, int y) {
    const core::Mat4 worldFromClip = glm::inverse(cam.clipFromWorld());
    const core::Vec2 ndc((x + 0.5) / kImage * 2.0 - 1.0, 1.0 - (y + 0.5) / kImage * 2.0);
    const core::Vec4 wsNear = worldFromClip * core::Vec4(ndc, 0.0, 1.0),
                     wsFar = worldFromClip * core::Vec4(ndc, 1.0, 1.0);
    const core::Vec3 a = core::Vec3(wsNear) / wsNear.w, b = core::Vec3(wsFar) / wsFar.w;
    return a + (b - a) * (a.y / (a.y - b.y));
}

// Whether the segment from p to q crosses the box of half extents `half` whose frame is boxFromWorld.
bool segmentMeetsBox(const core::Mat4& boxFromWorld, const core::Vec3& half, const core::Vec3& p, const core::Vec3& q) {
    const core::Vec3 a(boxFromWorld * core::Vec4(p, 1.0)), b(boxFromWorld * core::Vec4(q, 1.0));
    double enter = 0.0, leave = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        const double d = b[axis] - a[axis];
        if (std::abs(d) < 1e-12) {
            if (std::abs(a[axis]) > half[axis]) return false;
            continue;
        }
        const double t0 = (-half[axis] - a[axis]) / d, t1 = (half[axis] - a[axis]) / d;
        enter = std::max(enter, std::min(t0, t1));
        leave = std::min(leave, std::max(t0, t1));
    }
    return enter <= leave;
}

} // namespace

TEST_F(LocalLightsTest, ALampsShadowOnGroundItMeetsObliquelyStaysWhereItsCasterPutsIt) {
    // A plate 3 m above the ground, turned 30° about the vertical so its edges cross the map's
    // texels at every phase, under a point light 6 m up and 8 m to the side: the light meets the
    // ground under the plate's shadow about 53° from its normal. The shadow's centroid, drawn,
    // must lie where the ray-traced one does (the same pixels, tested analytically): a lookup
    // moved along the ground's normal reads the map nearer the lamp and pulls the whole shadow
    // towards it, by half a texel for half a texel's offset (0.2 m with these coarse maps), which
    // the lamps over a forest showed as false light and shadow along every tree's shadow.
    const core::Vec3 wsLamp(0, 6, 0), wsPlate(4, 3, 0), plateHalf(1.0, 0.05, 1.0);
    const core::Mat4 worldFromPlate =
        glm::rotate(glm::translate(core::Mat4(1.0), wsPlate), glm::radians(30.0), core::Vec3(0, 1, 0));
    scene::Scene s = boxes({{core::Vec3(0, -0.1, 0), core::Vec3(30, 0.1, 30)}});
    scene::Mesh plate;
    scene::addBox(plate, glm::mat4(worldFromPlate), glm::vec3(plateHalf), glm::vec3(0.8f));
    plate.computeBounds();
    s.batches.push_back({static_cast<uint32_t>(s.meshes.size()), {glm::mat4(1.0f)}, false});
    s.meshes.push_back(std::move(plate));
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = looking({8, 9, 0.5}, {8, 0, 0}, {1, 0, 0});
    ASSERT_TRUE((*renderer)->setLocalLights(
        lighting(cam, (*renderer)->wsSceneBounds(), {{.wsPosition = wsLamp, .range = 30.0}}, {}, 64)));
    auto raster =
        (*renderer)->renderEvalBuffers(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), nightSettings(), 0);
    ASSERT_TRUE(raster) << raster.error();
    const core::Mat4 plateFromWorld = glm::inverse(worldFromPlate);
    core::Vec3 drawnSum(0.0), truthSum(0.0);
    int drawn = 0, truth = 0;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const size_t i = raster->index(x, y);
            if (raster->surfaceId[i] != 1u) continue; // the ground alone
            const core::Vec3 ws = groundSeenBy(cam, x, y);
            if (raster->shadowTerm[i] < 0.5f) drawnSum += ws, ++drawn;
            if (segmentMeetsBox(plateFromWorld, plateHalf, ws, wsLamp)) truthSum += ws, ++truth;
        }
    ASSERT_GT(truth, 500) << "the plate's shadow must be in view";
    EXPECT_NEAR(double(drawn) / truth, 1.0, 0.1) << "the shadow's area";
    const core::Vec3 shift = drawnSum / double(drawn) - truthSum / double(truth);
    // 64² faces: a texel spans 2 / 64 of the 10 m from the lamp to the shadow, 0.31 m.
    EXPECT_NEAR(shift.x, 0.0, 0.06) << "the shadow moved along the light's way across the ground";
    EXPECT_NEAR(shift.z, 0.0, 0.06) << "the shadow moved across the light's way";
}

TEST_F(LocalLightsTest, GroundThroughTheLampItselfIsLitWithoutAcne) {
    // A point light 2 cm above open ground: the light grazes every receiver farther than 13 cm,
    // so a distance bias along the light (its tangent unbounded there) cannot keep the ground
    // off its own texels; the normal offset, which takes over where the light grazes, must.
    scene::Scene s = boxes({{core::Vec3(0, -0.1, 0), core::Vec3(30, 0.1, 30)}});
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = looking({0, 6, 5}, {0, 0, -1}, {0, 1, 0});
    ASSERT_TRUE((*renderer)->setLocalLights(
        lighting(cam, (*renderer)->wsSceneBounds(), {{.wsPosition = {0, 0.02, 0}, .range = 8.0}}, {})));
    auto raster =
        (*renderer)->renderEvalBuffers(cam, {}, sunSetup(cam, (*renderer)->wsSceneBounds()), nightSettings(), 0);
    ASSERT_TRUE(raster) << raster.error();
    int ground = 0, shadowed = 0;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const size_t i = raster->index(x, y);
            if (raster->surfaceId[i] != 1u || glm::length(groundSeenBy(cam, x, y)) > 7.5) continue;
            ++ground;
            shadowed += raster->shadowTerm[i] < 0.5f ? 1 : 0;
        }
    ASSERT_GT(ground, 10000);
    EXPECT_LT(shadowed, ground / 200) << shadowed << " of " << ground << " pixels of open ground drawn shadowed";
}
