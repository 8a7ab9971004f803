// Headless rendering tests (CTest label `gl`): a box floating over a plane under an
// overhead sun must shadow the plane below it, for every technique.
#include "headless_gl_test.h"
#include "program.h"
#include "test_scenes.h"

#include "shadowkit/core/visible_depth.h"
#include "shadowkit/gl/context.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/leafy_trees.h"
#include "shadowkit/scene/mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <optional>
#include <vector>

using namespace shadowkit;

namespace {

class RendererTest : public gl::testing::HeadlessGlTest {};

scene::Scene boxOverPlane() {
    scene::Scene s;
    scene::Mesh ground, box;
    ground.name = "ground";
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {20, 0.05f, 20}, glm::vec3(0.8f));
    box.name = "box";
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1}, glm::vec3(0.8f));
    ground.computeBounds();
    box.computeBounds();
    s.meshes = {ground, box};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 2.5f, 0})}, false}};
    return s;
}

} // namespace

TEST_F(RendererTest, ContextIsOpenGL45Core) {
    EXPECT_NE(context().description().find("4.5"), std::string::npos) << context().description();
}

TEST_F(RendererTest, BoxOverPlaneShadowsThePlaneBelowItForEveryTechnique) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.fogDensity = 0.0f;

    for (const core::TechniqueInfo& technique : core::allTechniques()) {
        const auto setup = core::computeShadowSetup({.camera = cam,
                                                     .light = sun,
                                                     .wsSceneBounds = s.wsBounds(),
                                                     .technique = technique.technique,
                                                     .mapSize = 256});
        ASSERT_TRUE(setup) << setup.error();
        const auto stats = (*renderer)->render(cam, sun, *setup, settings);
        ASSERT_TRUE(stats) << stats.error();
        if (!setup->clipmap) { // two batches per map, or for all maps where drawn together (virtual maps: per page)
            const bool together = setup->views.size() > 1 && setup->depthLayout == core::DepthLayout::Hyperbolic &&
                                  gl::vertexStagesReadDrawParameters() &&
                                  epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array");
            EXPECT_EQ(stats->shadow.drawCalls, 2u * (together ? 1 : setup->views.size())) << technique.name;
        }
        const scene::Image image = (*renderer)->readColor();
        const double under = gl::testing::luminanceAt(image, cam, {0.3, 0, 0.3});
        const double away = gl::testing::luminanceAt(image, cam, {6, 0, 2});
        // Shadowed: ambient only; lit: ambient + sun. The ratio is ~0.45 with our radiances.
        EXPECT_LT(under, 0.7 * away) << technique.name << ": under " << under << ", away " << away;
        EXPECT_GT(away, 100.0) << technique.name << ": the lit plane must not be dark (acne or a wrong matrix)";
    }
}

// An evaluation that wants the shaded frame too (renderWithEvalBuffers) draws the camera's view
// once, the eval pass's buffers and the colour from one pass, or, with the eye-space blur, the
// eval pass inside the frame: the same buffers as renderEvalBuffers() and the same picture as
// render(), each on a renderer of its own that has drawn the same frames, to the bit — though
// the shadow passes and the culling are drawn once, not twice. CHC++'s pre-pass, GPU culling,
// the eye-space blur, virtual pages and the aliasing overlay each take a case; so do the leafy
// forest's alpha-tested textures with the cascades' colours and a lamp.
TEST_F(RendererTest, AFrameWithItsEvalBuffersEqualsTheFrameAndTheEvalPassDrawnApart) {
    const scene::Scene forest = gl::testing::smallForest(400, 300, 32);
    // The forest with a row of leafy trees (every card, alpha-tested in the leaf atlas) 15–45 m
    // in front of the camera: textures in both passes.
    const scene::Scene leafy = [&] {
        scene::Scene s = forest;
        const scene::ResolvedView view = gl::testing::standardView(forest, "perpendicular");
        scene::LeafyTree tree = scene::makeLeafyTree(scene::TreeSpecies::Broadleaf, 1);
        tree.leaves.authoredLods.clear();
        tree.leaves.material = static_cast<int32_t>(s.materials.size());
        s.materials.push_back(scene::leafMaterial(static_cast<int32_t>(s.textures.size())));
        s.textures.push_back(scene::makeLeafAtlas());
        tree.leaves.computeBounds();
        std::vector<glm::mat4> placed;
        const core::Vec3 wsForward =
            glm::normalize(core::Vec3(view.camera.wsDirection.x, 0, view.camera.wsDirection.z));
        const core::Vec3 wsSide = glm::cross(wsForward, core::Vec3(0, 1, 0));
        for (int i = 0; i < 6; ++i) {
            const core::Vec3 at = view.camera.wsEye + (15.0 + 6.0 * i) * wsForward + (i % 2 ? 4.0 : -4.0) * wsSide;
            placed.push_back(
                glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(at.x, forest.groundHeightAt(at.x, at.z), at.z)),
                           glm::vec3(8.0f)));
        }
        s.batches.push_back({static_cast<uint32_t>(s.meshes.size()), std::move(placed), false});
        s.meshes.push_back(std::move(tree.leaves));
        return s;
    }();
    constexpr int kWidth = 160, kHeight = 90;
    struct Case {
        const char* name;
        const scene::Scene* scene;
        core::Technique technique;
        gl::Culling culling;
        int blurIterations = 0;
        bool cascadeColors = false, aliasingOverlay = false, lamp = false;
    };
    // Three renderers per scene, each drawing every case of it in turn (the lamp, once set, stays).
    struct Renderers {
        const scene::Scene* scene = nullptr;
        core::Result<std::unique_ptr<gl::Renderer>> together, shaded, evaluated;
    };
    std::optional<Renderers> renderers;
    for (const Case& c :
         {Case{"tsm, chc", &forest, core::Technique::Tsm, gl::Culling::Occlusion},
          Case{"lispsm, gpu culling, blurred", &forest, core::Technique::Lispsm, gl::Culling::Gpu, 2},
          Case{"virtual, frustum", &forest, core::Technique::Virtual, gl::Culling::Frustum},
          Case{"tsm, aliasing overlay", &forest, core::Technique::Tsm, gl::Culling::Frustum, 0, false, true},
          Case{"leafy, coloured cascades, a lamp", &leafy, core::Technique::Csm, gl::Culling::Occlusion, 0, true, false,
               true}}) {
        if (!renderers || renderers->scene != c.scene)
            renderers.emplace(Renderers{c.scene, gl::Renderer::create(*c.scene), gl::Renderer::create(*c.scene),
                                        gl::Renderer::create(*c.scene)});
        auto& [scene, together, shaded, evaluated] = *renderers;
        ASSERT_TRUE(together && shaded && evaluated);
        scene::ResolvedView view = gl::testing::standardView(*c.scene, "perpendicular");
        view.camera.aspect = double(kWidth) / kHeight;
        core::ShadowSetupInputs in{.camera = view.camera,
                                   .light = view.light,
                                   .wsSceneBounds = c.scene->wsBounds(),
                                   .technique = c.technique,
                                   .mapSize = 512};
        in.virtualMaps.imageHeight = kHeight;
        const auto setup = core::computeShadowSetup(in);
        ASSERT_TRUE(setup) << c.name << ": " << setup.error();
        gl::RenderSettings settings = gl::testing::smallFrame(kWidth, kHeight, c.culling);
        settings.blur.iterations = c.blurIterations;
        settings.cascadeColors = c.cascadeColors;
        settings.aliasingOverlay = c.aliasingOverlay;
        if (c.lamp) { // 4 m above the ground 20 m ahead of the camera
            const core::Vec3 wsAhead = view.camera.wsEye + 20.0 * glm::normalize(view.camera.wsDirection);
            const core::PointLight lamp{
                .wsPosition = {wsAhead.x, c.scene->groundHeightAt(wsAhead.x, wsAhead.z) + 4.0, wsAhead.z},
                .range = 30.0};
            auto lighting = core::computeLocalLighting(
                {.camera = view.camera, .wsSceneBounds = c.scene->wsBounds(), .mapSize = 128}, std::span(&lamp, 1), {});
            ASSERT_TRUE(lighting) << lighting.error();
            for (auto* r : {&*together, &*shaded, &*evaluated}) ASSERT_TRUE((*r)->setLocalLights(*lighting));
        }

        const int viewsBefore = (*together)->cameraViewsDrawn();
        const auto both = (*together)->renderWithEvalBuffers(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(both) << c.name << ": " << both.error();
        EXPECT_EQ((*together)->cameraViewsDrawn() - viewsBefore, c.blurIterations > 0 ? 2 : 1)
            << c.name << ": the camera's view drawn once, or the eval pass and the main pass around the blur";
        const scene::Image image = (*together)->readColor();
        const auto rendered = (*shaded)->render(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(rendered) << c.name << ": " << rendered.error();
        const auto buffers = (*evaluated)->renderEvalBuffers(view.camera, view.light, *setup, settings);
        ASSERT_TRUE(buffers) << c.name << ": " << buffers.error();

        const core::RasterBuffers& inFrame = both->second;
        EXPECT_GT(std::ranges::count_if(inFrame.surfaceId, [](uint32_t id) { return id != 0; }), kWidth * kHeight / 2)
            << c.name << ": the forest fills most of the frame";
        EXPECT_GT(std::ranges::count(inFrame.shadowTerm, 0.0f), 0) << c.name << ": some of it in shadow";
        if (c.scene == &leafy) {
            const auto leaves = std::ranges::count_if(
                inFrame.surfaceId, [&](uint32_t id) { return id > forest.instanceCount(); }); // the trees' instances
            EXPECT_GT(leaves, kWidth * kHeight / 20) << c.name << ": the leafy trees in the picture";
            EXPECT_LT(leaves, kWidth * kHeight / 2) << c.name << ": with gaps between their leaves";
        }
        EXPECT_EQ(inFrame.surfaceId, buffers->surfaceId) << c.name;
        EXPECT_EQ(inFrame.shadowTerm, buffers->shadowTerm) << c.name;
        EXPECT_EQ(inFrame.viewDepth, buffers->viewDepth) << c.name;
        EXPECT_EQ(inFrame.wsNormal, buffers->wsNormal) << c.name;
        EXPECT_EQ(inFrame.tsTexel, buffers->tsTexel) << c.name;
        EXPECT_EQ(inFrame.texelFromPixel, buffers->texelFromPixel) << c.name;
        EXPECT_EQ(inFrame.mapSize, buffers->mapSize) << c.name;
        EXPECT_EQ(image.rgba, (*shaded)->readColor().rgba) << c.name;
        EXPECT_EQ(both->first.shadow.triangles, (*together)->lastShadowPass().triangles) << c.name;
        EXPECT_EQ(both->first.main.triangles, rendered->main.triangles) << c.name << ": the camera pass's work";
        EXPECT_GT(both->first.main.triangles, 0) << c.name;
    }
}

TEST_F(RendererTest, ShadowMapImageShowsTheCaster) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    const auto setup = core::computeShadowSetup({.camera = cam,
                                                 .light = sun,
                                                 .wsSceneBounds = s.wsBounds(),
                                                 .technique = core::Technique::Standard,
                                                 .mapSize = 64});
    gl::RenderSettings settings;
    settings.width = settings.height = 32;
    ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
    const scene::Image map = (*renderer)->readShadowMap();
    ASSERT_EQ(map.width, 64);
    // The box (nearer the light) is brighter than the plane around it at the map's centre.
    EXPECT_GT(map.pixel(32, 32)[0], map.pixel(2, 2)[0]);
}

TEST_F(RendererTest, OutOfRangeSettingsAreErrorsNotGlErrors) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    auto setup = core::computeShadowSetup(
        {.camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = core::Technique::Focused});
    ASSERT_TRUE(setup);
    // A set-up edited past any driver's GL_MAX_TEXTURE_SIZE: the renderer checks again.
    setup->mapSize = 1 << 20;
    const auto r = (*renderer)->render(cam, sun, *setup, gl::RenderSettings{});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.errorInfo().field, "map_size") << r.error();
    EXPECT_EQ(r.errorInfo().kind, core::ErrorKind::Environment) << "a driver's limit is the machine's, not the input's";
    setup->mapSize = 64;
    gl::RenderSettings settings;
    settings.blur.radiusPixels = 0.0f;
    const auto blur = (*renderer)->render(cam, sun, *setup, settings);
    ASSERT_FALSE(blur);
    EXPECT_EQ(blur.errorInfo().field, "blur.radius") << blur.error();
    EXPECT_EQ(blur.errorInfo().kind, core::ErrorKind::BadInput);
}

TEST_F(RendererTest, CasterAboveTheFrustumStillShadowsItsCascade) {
    // The caster floats 40 m up, far above the view frustum (which reaches 19 m at that
    // depth), but between the ground it shadows and the overhead sun: every cascade
    // configuration must keep it in the split that serves that ground.
    scene::Scene s;
    scene::Mesh ground, box;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, -50}), {60, 0.5f, 60}, glm::vec3(0.8f));
    scene::addBox(box, glm::mat4(1.0f), {3, 0.5f, 3}, glm::vec3(0.8f));
    ground.computeBounds();
    box.computeBounds();
    s.meshes = {ground, box};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 40, -30})}, false}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 2, 0};
    cam.wsDirection = {0, -0.05, -1};
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 100;
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.fogDensity = 0.0f;
    for (int variant = 0; variant < 3; ++variant) {
        core::ShadowSetupInputs in{.camera = cam,
                                   .light = sun,
                                   .wsSceneBounds = s.wsBounds(),
                                   .technique = core::Technique::Csm,
                                   .mapSize = 512};
        in.cascades.count = 2;
        in.cascades.splits = {0.5, 20, 100};
        in.cascades.warp = variant == 1 ? core::CascadeWarp::Lispsm : core::CascadeWarp::None;
        in.cascades.stabilize = variant == 2;
        const auto setup = core::computeShadowSetup(in);
        ASSERT_TRUE(setup) << setup.error();
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
        const scene::Image image = (*renderer)->readColor();
        const double under = gl::testing::luminanceAt(image, cam, {0, 0, -30}),
                     away = gl::testing::luminanceAt(image, cam, {9, 0, -30});
        EXPECT_LT(under, 0.7 * away) << "variant " << variant << ": under " << under << ", away " << away;
    }
}

TEST_F(RendererTest, EveryBiasModeAndFilterWorksWithEveryTechnique) {
    // No mode may turn the image all-lit or all-shadowed: the plane under the box stays
    // darker than the plane beside it, for every technique.
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    std::vector<std::pair<std::string, gl::RenderSettings>> modes;
    gl::RenderSettings base;
    base.width = base.height = 96;
    base.fogDensity = 0.0f;
    base.bias = core::BiasSettings{}; // every mode below changes one thing from the same bias
    for (core::CasterCull cull :
         {core::CasterCull::None, core::CasterCull::Back, core::CasterCull::Front, core::CasterCull::BackOfClosed}) {
        gl::RenderSettings m = base;
        m.bias->cull = cull;
        modes.emplace_back("cull " + std::to_string(int(cull)), m);
    }
    gl::RenderSettings m = base;
    m.bias->normalOffset = 1.0;
    modes.emplace_back("normal offset", m);
    m = base;
    m.bias->receiverPlane = true;
    m.bias->slope = 0.0;
    modes.emplace_back("receiver plane", m);
    for (auto [kind, taps] : {std::pair{core::ShadowFilter::Pcf2, 1},
                              {core::ShadowFilter::PcfGrid, 3},
                              {core::ShadowFilter::Poisson, 16}}) {
        m = base;
        m.filter = {kind, taps};
        modes.emplace_back("filter " + std::to_string(int(kind)), m);
    }
    m = base;
    m.blur.iterations = 4;
    modes.emplace_back("blur", m);

    for (const core::TechniqueInfo& technique : core::allTechniques())
        for (core::DepthLayout layout : {core::DepthLayout::Hyperbolic, core::DepthLayout::Linear})
            for (const auto& [name, settings] : modes) {
                const auto setup = core::computeShadowSetup({.camera = cam,
                                                             .light = sun,
                                                             .wsSceneBounds = s.wsBounds(),
                                                             .technique = technique.technique,
                                                             .mapSize = 256,
                                                             .virtualMaps = {.imageHeight = 96}, // the frame's rows
                                                             .depthLayout = layout});
                ASSERT_TRUE(setup);
                ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings)) << name;
                const scene::Image image = (*renderer)->readColor();
                const double under = gl::testing::luminanceAt(image, cam, {0.3, 0, 0.3}),
                             away = gl::testing::luminanceAt(image, cam, {6, 0, 2});
                EXPECT_LT(under, 0.7 * away) << technique.name << ", " << name << ", layout " << int(layout);
                EXPECT_GT(away, 100.0) << technique.name << ", " << name << ", layout " << int(layout);
            }
}

// The offset guard (BiasSettings::offsetGuard) looks only where the light grazes a receiver's
// triangle (|f·ℓ| < 0.15): under a sun at 35° to every face of a box over a plane, no face
// grazes, and every technique's frame with the guard is the frame without it, pixel for pixel,
// though the offsets move the lookups there. (Where the light grazes, the guard's own test is
// the corpus's spheres in walled cells, tests/corpus_defaults_test.cpp.)
TEST_F(RendererTest, TheOffsetGuardChangesNothingWhereTheLightGrazesNoFace) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer) << renderer.error();
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{glm::normalize(core::Vec3{1, -1, 1})};
    for (const core::TechniqueInfo& technique : core::allTechniques()) {
        const auto setup = core::computeShadowSetup({.camera = cam,
                                                     .light = sun,
                                                     .wsSceneBounds = s.wsBounds(),
                                                     .technique = technique.technique,
                                                     .mapSize = 256,
                                                     .virtualMaps = {.imageHeight = 96}});
        ASSERT_TRUE(setup) << setup.error();
        gl::RenderSettings settings;
        settings.width = settings.height = 96;
        settings.fogDensity = 0.0f;
        settings.bias = gl::biasFor(*setup, settings);
        settings.bias->normalOffset = 0.5, settings.bias->normalOffsetFootprint = 0.5; // both offsets, everywhere
        settings.bias->offsetGuard = false; // the warped maps' recommended bias has it on
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
        const scene::Image unguarded = (*renderer)->readColor();
        settings.bias->offsetGuard = true;
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
        const scene::Image guarded = (*renderer)->readColor();
        EXPECT_EQ(guarded.rgba, unguarded.rgba) << technique.name;
    }
}

TEST_F(RendererTest, TheReceiverPlaneAloneKeepsALitPlaneLitWithNoDepthOffsetAtAll) {
    // With the reference depth on the receiver's exact plane, a texel's stored depth differs from
    // it only by the rasteriser's own rounding of that plane — which the shader's margin
    // (SK_RECEIVER_PLANE_MARGIN) must cover, since no polygon offset does here. Without it,
    // 44–83 % of the ground acned on llvmpipe under the warped maps and 95 % on an NVIDIA H200.
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    gl::RenderSettings settings;
    settings.width = settings.height = 96;
    settings.fogDensity = 0.0f;
    settings.bias = core::BiasSettings{.slope = 0.0, .constant = 0.0, .receiverPlane = true};
    for (core::Technique technique : {core::Technique::Psm, core::Technique::Lispsm, core::Technique::Tsm}) {
        const auto setup = core::computeShadowSetup({.camera = cam,
                                                     .light = sun,
                                                     .wsSceneBounds = s.wsBounds(),
                                                     .technique = technique,
                                                     .mapSize = 256,
                                                     .depthLayout = core::DepthLayout::Hyperbolic});
        ASSERT_TRUE(setup);
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, settings));
        const scene::Image image = (*renderer)->readColor();
        // Ground points on half rings round the box's shadow (the sun is overhead: the shadow is
        // the box's 2 × 2 m footprint), every one in full sun and, on the camera's side (z ≥ 0),
        // none behind the box.
        std::vector<double> lit;
        for (int i = 0; i < 64; ++i) {
            const double angle = 3.14159265358979 * i / 63.0, radius = 2.5 + (i % 4);
            lit.push_back(
                gl::testing::luminanceAt(image, cam, {radius * std::cos(angle), 0.0, radius * std::sin(angle)}));
        }
        const double brightest = *std::max_element(lit.begin(), lit.end());
        const auto dark = std::count_if(lit.begin(), lit.end(), [&](double l) { return l < 0.8 * brightest; });
        EXPECT_LE(dark, 1) << core::techniqueName(technique) << ": " << dark << " of 64 sunlit ground points dark";
        EXPECT_LT(gl::testing::luminanceAt(image, cam, {0.3, 0, 0.3}), 0.7 * brightest)
            << core::techniqueName(technique);
    }
}

TEST_F(RendererTest, PcfTermsLieInZeroOneAndFallMonotonicallyAcrossAShadowEdge) {
    // A plate 10 m up casts a square shadow 6 m to its +x side (sun tilted); the camera
    // looks straight down on that shadow's left edge.
    scene::Scene s;
    scene::Mesh ground, plate;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, 0}), {20, 0.5f, 20}, glm::vec3(0.8f));
    scene::addBox(plate, glm::mat4(1.0f), {3, 0.1f, 3}, glm::vec3(0.8f));
    ground.computeBounds();
    plate.computeBounds();
    s.meshes = {ground, plate};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {0, 10, 0})}, false}};
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    core::PerspectiveCamera cam;
    cam.wsEye = {6, 30, 0};
    cam.wsDirection = {0, -1, 0};
    cam.wsUp = {0, 0, -1};
    cam.aspect = 1.0;
    cam.zNear = 1;
    cam.zFar = 40;
    const core::DirectionalLight sun = core::DirectionalLight::fromDirection({0.6, -1, 0}).value();
    gl::RenderSettings settings;
    settings.width = settings.height = 128;
    settings.bias = core::BiasSettings{};
    for (auto [kind, taps] : {std::pair{core::ShadowFilter::Pcf2, 1}, {core::ShadowFilter::PcfGrid, 5}}) {
        settings.filter = {kind, taps};
        // Wide kernels need the receiver-plane bias: without it the outer taps of a 5x5 grid
        // compare the centre's depth with texels 2 away on the sloped ground and a fifth of
        // them fail (0.8 on lit ground), which is why `--receiver-plane-bias auto` turns it on.
        settings.bias->receiverPlane = kind == core::ShadowFilter::PcfGrid;
        const auto setup = core::computeShadowSetup({.camera = cam,
                                                     .light = sun,
                                                     .wsSceneBounds = s.wsBounds(),
                                                     .technique = core::Technique::Standard,
                                                     .mapSize = 256});
        const auto raster = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
        ASSERT_TRUE(raster);
        // Along +x on the ground: lit, the edge at x = 3, shadow.

        std::vector<float> terms;
        for (double x = 1.6; x <= 6.0; x += 0.05) {
            const core::Vec4 c = cam.clipFromWorld() * core::Vec4(x, 0, 0, 1);
            const int px = static_cast<int>((c.x / c.w * 0.5 + 0.5) * raster->width);
            const int py = static_cast<int>((0.5 - c.y / c.w * 0.5) * raster->height);
            const size_t i = raster->index(px, py);
            ASSERT_EQ(raster->surfaceId[i], 1u) << "x " << x; // the ground, not the plate
            terms.push_back(raster->shadowTerm[i]);
        }
        EXPECT_GT(terms.front(), 0.99f);
        EXPECT_LT(terms.back(), 0.01f);
        bool partial = false;
        for (size_t i = 0; i < terms.size(); ++i) {
            EXPECT_GE(terms[i], 0.0f);
            EXPECT_LE(terms[i], 1.0f);
            if (i > 0) {
                EXPECT_LE(terms[i], terms[i - 1] + 1e-5f) << "filter " << int(kind) << " at " << i;
            }
            partial |= terms[i] > 0.05f && terms[i] < 0.95f;
        }
        EXPECT_TRUE(partial) << "filter " << int(kind) << ": no intermediate values at the edge";
    }
}

namespace {
// A lit wall 9 m ahead with ground behind it shadowed by a low plate: a depth step
// between a lit and a shadowed surface along the wall's sides.
scene::Scene wallBeforeShadowedGround() {
    scene::Scene s;
    scene::Mesh ground, plate, wall;
    scene::addBox(ground, glm::translate(glm::mat4(1.0f), {0, -0.5f, -30}), {40, 0.5f, 40}, glm::vec3(0.8f));
    scene::addBox(plate, glm::mat4(1.0f), {20, 0.1f, 15}, glm::vec3(0.8f));
    // Thin enough that its side faces (which self-shadow, at the wall's own depth) stay
    // under a pixel: the test is about the step to the ground behind, not those.
    scene::addBox(wall, glm::mat4(1.0f), {1.5f, 2.0f, 0.002f}, glm::vec3(0.8f));
    for (scene::Mesh* m : {&ground, &plate, &wall}) m->computeBounds();
    s.meshes = {ground, plate, wall};
    s.batches = {{0, {glm::mat4(1.0f)}, false},
                 {1, {glm::translate(glm::mat4(1.0f), {0, 3, -25})}, false},
                 {2, {glm::translate(glm::mat4(1.0f), {0, 2.0f, -9})}, false}};
    return s;
}
} // namespace

TEST_F(RendererTest, BlurKeepsAUniformMaskAndStopsAtDepthSteps) {
    const scene::Scene s = wallBeforeShadowedGround();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 2, 0};
    cam.wsDirection = {0, -0.05, -1};
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 90;
    const core::DirectionalLight sun =
        core::DirectionalLight::fromDirection({0, -1, -0.1}).value(); // grazes the wall's front
    const auto setup = core::computeShadowSetup({.camera = cam,
                                                 .light = sun,
                                                 .wsSceneBounds = s.wsBounds(),
                                                 .technique = core::Technique::Focused,
                                                 .mapSize = 512});
    gl::RenderSettings settings;
    settings.width = settings.height = 96;
    const auto sharp = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
    settings.blur = {16, 3.0f, 0.0f, 0.02f}; // strong, uniform in depth
    const auto blurred = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
    settings.blur.depthThreshold = 1.0f; // the control: depths within 2x mix (ground at 11-18 m)
    const auto bleeding = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
    ASSERT_TRUE(sharp && blurred && bleeding);

    int wallEdge = 0, keptLit = 0, bledInto = 0;
    for (int y = 1; y < sharp->height - 1; ++y)
        for (int x = 1; x < sharp->width - 1; ++x) {
            const size_t i = sharp->index(x, y);
            if (sharp->surfaceId[i] != 3) continue; // the wall
            bool nearGround = false;                // within 2 pixels of the shadowed ground
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const int xx = std::clamp(x + dx, 0, sharp->width - 1),
                              yy = std::clamp(y + dy, 0, sharp->height - 1);
                    const size_t j = sharp->index(xx, yy);
                    nearGround |= sharp->surfaceId[j] == 1 && sharp->shadowTerm[j] < 0.5f;
                }
            if (!nearGround || sharp->shadowTerm[i] < 0.99f) continue;
            ++wallEdge;
            keptLit += blurred->shadowTerm[i] > 0.99f;
            bledInto += bleeding->shadowTerm[i] < 0.9f;
        }
    ASSERT_GT(wallEdge, 10);
    EXPECT_EQ(keptLit, wallEdge);      // the depth test stops the blur at the silhouette
    EXPECT_GT(bledInto, wallEdge / 2); // and without it, shadow bleeds onto the wall
    // A uniform region stays uniform: the middle of the shadowed ground stays 0.
    for (size_t i = 0; i < sharp->shadowTerm.size(); ++i)
        if (sharp->surfaceId[i] == 1 && sharp->shadowTerm[i] == 0.0f && blurred->shadowTerm[i] > 0.0f) {
            // only allowed next to a lit region; check the 13x13 neighbourhood had light
            const int x = int(i % size_t(sharp->width)), y = int(i / size_t(sharp->width));
            bool litNearby = false;
            for (int dy = -6; dy <= 6; ++dy)
                for (int dx = -6; dx <= 6; ++dx) {
                    const int xx = std::clamp(x + dx, 0, sharp->width - 1),
                              yy = std::clamp(y + dy, 0, sharp->height - 1);
                    litNearby |=
                        sharp->shadowTerm[sharp->index(xx, yy)] > 0.0f && sharp->surfaceId[sharp->index(xx, yy)] == 1;
                }
            EXPECT_TRUE(litNearby) << x << "," << y;
        }
}

TEST_F(RendererTest, VisibleDepthIsTheDepthRangeOfWhatTheCameraSees) {
    const scene::Scene s = boxOverPlane();
    auto renderer = gl::Renderer::create(s);
    ASSERT_TRUE(renderer);
    const core::PerspectiveCamera cam = gl::testing::obliqueCamera();
    const core::DirectionalLight sun{{0, -1, 0}};
    core::ShadowSetupInputs in{
        .camera = cam, .light = sun, .wsSceneBounds = s.wsBounds(), .technique = core::Technique::Lispsm};
    gl::RenderSettings settings;
    settings.width = settings.height = 64;
    const auto setup = core::computeShadowSetup(in);
    ASSERT_TRUE(setup);
    const auto range = (*renderer)->visibleDepth(cam, sun, *setup, settings);
    ASSERT_TRUE(range);
    ASSERT_TRUE(*range);
    // Every drawn point lies within the scene box: its view depth between the box's nearest
    // and farthest corners, and well past the camera's 0.5 m near plane.
    const core::Vec3 forward = glm::normalize(cam.wsDirection);
    double lo = INFINITY, hi = -INFINITY;
    for (const core::Vec3& c : s.wsBounds().corners()) {
        lo = std::min(lo, glm::dot(c - cam.wsEye, forward));
        hi = std::max(hi, glm::dot(c - cam.wsEye, forward));
    }
    EXPECT_GE((*range)->x, lo - 1e-3);
    EXPECT_LE((*range)->y, hi + 1e-3);
    EXPECT_GT((*range)->x, 5.0 * cam.zNear);
    // The GPU reduction is exact: the min / max of the camera pass's own view depths, for
    // every culling mode (each makes or reuses a depth pre-pass).
    const auto buffers = (*renderer)->renderEvalBuffers(cam, sun, *setup, settings);
    ASSERT_TRUE(buffers);
    const auto cpu = core::visibleDepthRange(buffers->viewDepth);
    ASSERT_TRUE(cpu);
    for (const gl::Culling culling : {gl::Culling::Off, gl::Culling::Frustum, gl::Culling::Occlusion}) {
        gl::RenderSettings s2 = settings;
        s2.culling = culling;
        const auto reduced = (*renderer)->visibleDepth(cam, sun, *setup, s2);
        ASSERT_TRUE(reduced && *reduced) << gl::cullingName(culling);
        EXPECT_EQ(**reduced, *cpu) << gl::cullingName(culling);
        // A frame drawn with a pre-pass leaves the same range for the next frame's set-up.
        s2.receiverMask = culling == gl::Culling::Frustum;
        ASSERT_TRUE((*renderer)->render(cam, sun, *setup, s2));
        const auto last = (*renderer)->lastVisibleDepth();
        if (culling == gl::Culling::Off) { // no pre-pass: nothing measured, not an older frame's range
            EXPECT_FALSE(last);
            continue;
        }
        ASSERT_TRUE(last) << gl::cullingName(culling);
        EXPECT_EQ(*last, *cpu) << gl::cullingName(culling);
    }
    // Looking at the sky: nothing drawn, no range, inputs unchanged.
    core::PerspectiveCamera up = cam;
    up.wsDirection = {0, 1, 0};
    up.wsUp = {0, 0, -1};
    in.camera = up;
    const auto sky = core::computeShadowSetup(in);
    ASSERT_TRUE(sky);
    const auto none = (*renderer)->visibleDepth(up, sun, *sky, settings);
    ASSERT_TRUE(none);
    EXPECT_FALSE(*none);
}
