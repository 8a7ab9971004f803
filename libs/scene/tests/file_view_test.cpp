// A glTF's own cameras and punctual lights (gltf_viewpoints.cpp) stand where their nodes put
// them, and `--view file` (file_view.cpp) looks through the camera lit by them. Expected values
// are worked from the file's quaternions by hand, not read back from the loader.
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include "gltf_test_files.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// A 20 × 20 m ground at y = 0 (two triangles facing +y), embedded.
std::string viewpointGroundMesh() {
    const float q[] = {-10, 0, -10, -10, 0, 10, 10, 0, 10, -10, 0, -10, 10, 0, 10, 10, 0, -10};
    std::vector<unsigned char> bytes(sizeof q);
    std::memcpy(bytes.data(), q, sizeof q);
    return R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3","min":[-10,0,-10],"max":[10,0,10]}],
        "bufferViews":[{"buffer":0,"byteLength":72}],
        "buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
           scene::testing::base64(bytes) + "\"}]";
}

// The ground under a root node at `rootTranslation`, with a rig at (0, 0, 10) holding a camera
// 5 m up turned 30° down; a sun turned 60° down about x, a point lamp, a spot pointing straight
// down, an orthographic camera; `lights` replaces the file's light list where given.
std::string viewpointFile(const std::string& rootTranslation, const std::string& lights = "") {
    const double s15 = std::sin(glm::radians(-15.0)), c15 = std::cos(glm::radians(-15.0));
    const double s30 = std::sin(glm::radians(-30.0)), c30 = std::cos(glm::radians(-30.0));
    const double s45 = std::sin(glm::radians(-45.0)), c45 = std::cos(glm::radians(-45.0));
    // Appended, not `"[" + std::to_string(s)`: GCC 12 warns falsely on that (-Wstringop-overflow).
    const auto quat = [](double s, double c) {
        std::string q = "[";
        return q.append(std::to_string(s)).append(",0,0,").append(std::to_string(c)).append("]");
    };
    const std::string lightList =
        lights.empty() ? R"([{"type":"directional","name":"Sun"},{"type":"point","range":7,"intensity":5},
                            {"type":"spot","spot":{"outerConeAngle":0.4}},{"type":"point","intensity":0}])"
                       : lights;
    return R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],
        "extensions":{"KHR_lights_punctual":{"lights":)" +
           lightList + R"(}},
        "scene":0,"scenes":[{"nodes":[0]}],
        "nodes":[{"translation":)" +
           rootTranslation + R"(,"children":[1,2,4,5,6,7,8]},
          {"mesh":0},
          {"name":"rig","translation":[0,0,10],"children":[3]},
          {"name":"Cam","camera":0,"translation":[0,5,0],"rotation":)" +
           quat(s15, c15) + R"(},
          {"extensions":{"KHR_lights_punctual":{"light":0}},"rotation":)" +
           quat(s30, c30) + R"(},
          {"extensions":{"KHR_lights_punctual":{"light":1}},"translation":[3,4,5]},
          {"extensions":{"KHR_lights_punctual":{"light":2}},"translation":[-2,6,0],"rotation":)" +
           quat(s45, c45) + R"(,"scale":[3,3,3]},
          {"camera":1},
          {"extensions":{"KHR_lights_punctual":{"light":3}}}],
        "cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"zfar":1000000,"aspectRatio":2.0}},
                   {"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":10}}],
        )" +
           viewpointGroundMesh() + "}";
}

void expectVec3Near(const core::Vec3& got, const core::Vec3& want, double tolerance, const char* what) {
    EXPECT_NEAR(got.x, want.x, tolerance) << what;
    EXPECT_NEAR(got.y, want.y, tolerance) << what;
    EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

} // namespace

TEST(FileViewTest, CamerasAndLightsStandWhereTheirNodesPutThem) {
    const auto scene = scene::testing::loadWritten("sk_viewpoints.gltf", viewpointFile("[0,0,0]"));
    ASSERT_TRUE(scene) << scene.error();
    // The orthographic camera is read as one, and said to be drawn as a telephoto; the lamp of
    // intensity 0 is left out.
    ASSERT_EQ(scene->cameras.size(), 2u);
    ASSERT_EQ(scene->lights.size(), 3u);
    EXPECT_EQ(std::count_if(scene->warnings.begin(), scene->warnings.end(),
                            [](const std::string& w) {
                                return w.find("orthographic: drawn as a telephoto") != std::string::npos;
                            }),
              1);
    const FileCamera& flat = scene->cameras[1];
    EXPECT_EQ(flat.orthographicHalfHeight, 1.0);
    EXPECT_EQ(flat.aspect, 1.0);
    EXPECT_EQ(flat.zNear, 0.1);
    EXPECT_EQ(flat.zFar, 10.0);
    EXPECT_FALSE(scene->cameras[0].orthographicHalfHeight);

    // The camera: rig (0, 0, 10) then (0, 5, 0); turned −30° about x, it looks along
    // Rx(−30°)·(0, 0, −1) = (0, −sin 30°, −cos 30°) with up Rx(−30°)·(0, 1, 0) = (0, cos 30°, −sin 30°).
    const FileCamera& camera = scene->cameras[0];
    EXPECT_EQ(camera.name, "Cam");
    expectVec3Near(camera.localEye, {0, 5, 10}, 1e-9, "eye");
    expectVec3Near(camera.localForward, {0, -0.5, -std::sqrt(0.75)}, 1e-6, "forward");
    expectVec3Near(camera.localUp, {0, std::sqrt(0.75), -0.5}, 1e-6, "up");
    EXPECT_NEAR(camera.fovYDegrees, 0.8 * 180.0 / M_PI, 1e-9);
    EXPECT_EQ(camera.aspect, 2.0);

    // The sun travels along Rx(−60°)·(0, 0, −1) = (0, −sin 60°, −cos 60°).
    EXPECT_EQ(scene->lights[0].kind, FileLight::Kind::Sun);
    EXPECT_EQ(scene->lights[0].name, "Sun");
    expectVec3Near(scene->lights[0].localDirection, {0, -std::sqrt(0.75), -0.5}, 1e-6, "sun");
    EXPECT_EQ(scene->lights[1].kind, FileLight::Kind::Point);
    expectVec3Near(scene->lights[1].localPosition, {3, 4, 5}, 1e-9, "lamp");
    EXPECT_EQ(scene->lights[1].range, 7.0);
    // The spot, scaled 3× (which scales no light), points down: Rx(−90°)·(0, 0, −1) = (0, −1, 0),
    // opening twice its outer cone angle, of unlimited range.
    EXPECT_EQ(scene->lights[2].kind, FileLight::Kind::Spot);
    expectVec3Near(scene->lights[2].localPosition, {-2, 6, 0}, 1e-9, "spot");
    expectVec3Near(scene->lights[2].localDirection, {0, -1, 0}, 1e-6, "spot axis");
    EXPECT_NEAR(scene->lights[2].coneDegrees, 2.0 * 0.4 * 180.0 / M_PI, 1e-9);
    EXPECT_FALSE(scene->lights[2].range);

    std::string said;
    const auto view = fileView(*scene, "", 16, &said);
    ASSERT_TRUE(view) << view.error();
    EXPECT_EQ(view->width, 1280);
    EXPECT_EQ(view->height, 640); // the camera's aspect 2
    EXPECT_TRUE(view->sun);
    EXPECT_FALSE(view->framed);
    expectVec3Near(view->light.wsTowardsLight(), {0, std::sqrt(0.75), 0.5}, 1e-6, "towards the sun");
    ASSERT_EQ(view->points.size(), 1u);
    ASSERT_EQ(view->spots.size(), 1u);
    EXPECT_EQ(view->points[0].range, 7.0);
    // Unlimited: it reaches the ground's farthest corner, (10, 0, ±10) from (−2, 6, 0).
    EXPECT_GE(view->spots[0].range, std::sqrt(144.0 + 36.0 + 100.0));
    // The planes hold the whole ground — its corners lie 2.5 to 2.5 + 20 cos 30° m deep along the
    // camera's axis — and not the file's million metres.
    EXPECT_LE(view->camera.zNear, 2.5);
    EXPECT_GE(view->camera.zNear, 0.1);
    EXPECT_GE(view->camera.zFar, 2.5 + 20.0 * std::sqrt(0.75));
    EXPECT_LE(view->camera.zFar, 100.0);
    EXPECT_TRUE(view->camera.validate());
    EXPECT_NE(said.find("camera 0 'Cam' of 2"), std::string::npos) << said;

    EXPECT_TRUE(fileView(*scene, "Cam", 16));
    EXPECT_TRUE(fileView(*scene, "0", 16));
    const auto missing = fileView(*scene, "2", 16);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().find("which has camera 0 'Cam'"), std::string::npos) << missing.error();
    // At most the frame's limit of each kind, the rest said.
    const auto capped = fileView(*scene, "", 0, &said);
    ASSERT_TRUE(capped);
    EXPECT_TRUE(capped->points.empty() && capped->spots.empty());
    EXPECT_NE(said.find("2 more left out"), std::string::npos) << said;
}

// glTF's orthographic camera (§5.13) drawn as a telephoto: every size in the picture within 1 % of
// the orthographic one's, whatever its depth in the scene. A block 8 × 5 × 4 m seen from 20 m
// above it, xmag 4 and ymag 2: its corners, top and bottom alike, lie on the picture's edges.
TEST(FileViewTest, AnOrthographicCameraIsDrawnAsATelephotoWhoseSizesDoNotChangeWithDepth) {
    Scene scene;
    Mesh block;
    for (int corner = 0; corner < 8; ++corner)
        block.vertices.push_back(
            {.position = {corner & 1 ? 4.0f : -4.0f, corner & 2 ? 5.0f : 0.0f, corner & 4 ? 2.0f : -2.0f},
             .normal = {0, 1, 0}});
    block.indices = {0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6};
    block.computeBounds();
    scene.meshes.push_back(block);
    scene.batches.push_back({.mesh = 0, .worldFromObject = {glm::mat4(1.0f)}});
    scene.cameras.push_back({.name = "plan",
                             .localEye = {0, 20, 0},
                             .localForward = {0, -1, 0},
                             .localUp = {0, 0, -1},
                             .aspect = 2.0,
                             .zNear = 0.0,
                             .zFar = 100.0,
                             .orthographicHalfHeight = 2.0});
    const auto view = fileView(scene, "plan", 16);
    ASSERT_TRUE(view) << view.error();
    EXPECT_TRUE(view->camera.validate());
    EXPECT_EQ(view->fogDensity, 0.0);
    const core::Mat4 clipFromWorld = view->camera.clipFromWorld();
    for (const core::Vec3& corner : scene.localBounds().corners()) {
        const glm::dvec4 clip = clipFromWorld * glm::dvec4(corner, 1.0);
        // x across the picture: the block's ±4 m on its edges; y: its ∓2 m along z (up is −z).
        EXPECT_NEAR(std::abs(clip.x / clip.w), 1.0, 0.01) << corner.x << " " << corner.y << " " << corner.z;
        EXPECT_NEAR(std::abs(clip.y / clip.w), 1.0, 0.01) << corner.x << " " << corner.y << " " << corner.z;
        EXPECT_GT(clip.w, view->camera.zNear);
        EXPECT_LT(clip.w, view->camera.zFar);
    }
    // Still straight down, from above.
    EXPECT_NEAR(glm::dot(view->camera.wsDirection, core::Vec3(0, -1, 0)), 1.0, 1e-12);
    EXPECT_GT(view->camera.wsEye.y, 20.0);
}

TEST(FileViewTest, FarOutAndZUpTheViewStaysOnItsModel) {
    // 5,400 km out the scene stands at its own origin (near_origin.cpp): the camera and lamps
    // move with it, and the view's world positions are the file's.
    const auto far = scene::testing::loadWritten("sk_viewpoints_far.gltf", viewpointFile("[512345,20,5412345]"));
    ASSERT_TRUE(far) << far.error();
    EXPECT_NE(far->wsOrigin, core::Vec3(0.0));
    expectVec3Near(far->cameras[0].localEye + far->wsOrigin, {512345, 25, 5412355}, 1e-6, "far eye");
    const auto view = fileView(*far, "", 16);
    ASSERT_TRUE(view) << view.error();
    expectVec3Near(view->camera.wsEye, {512345, 25, 5412355}, 1e-6, "far view's eye");
    expectVec3Near(view->points[0].wsPosition, {512348, 24, 5412350}, 1e-6, "far lamp");
    EXPECT_LE(view->camera.zFar, 100.0);

    // Loaded z-up, the file's (x, y, z) is the world's (x, z, −y): its camera and lights turn too.
    const auto turned =
        scene::testing::loadWritten("sk_viewpoints_zup.gltf", viewpointFile("[0,0,0]"), {.up = UpAxis::Z});
    ASSERT_TRUE(turned) << turned.error();
    expectVec3Near(turned->cameras[0].localEye, {0, 10, -5}, 1e-9, "turned eye");
    expectVec3Near(turned->cameras[0].localForward, {0, -std::sqrt(0.75), 0.5}, 1e-6, "turned forward");
    expectVec3Near(turned->lights[1].localPosition, {3, 5, -4}, 1e-9, "turned lamp");
}

TEST(FileViewTest, WithoutASunItIsNightAndWithoutLightsTheStandardSun) {
    // Lamps only: night, lit by them, as its author lit it.
    const auto lamps = scene::testing::loadWritten(
        "sk_viewpoints_lamps.gltf", viewpointFile("[0,0,0]", R"([{"type":"spot","spot":{}},{"type":"point"},
                                                {"type":"spot","spot":{}},{"type":"point"}])"));
    ASSERT_TRUE(lamps) << lamps.error();
    const auto night = fileView(*lamps, "", 16);
    ASSERT_TRUE(night) << night.error();
    EXPECT_FALSE(night->sun);
    EXPECT_EQ(night->points.size() + night->spots.size(), 4u);

    // No light at all: the standard views' sun, 45° up.
    const auto unlit = scene::testing::loadWritten("sk_viewpoints_unlit.gltf", viewpointFile("[0,0,0]", "[]"));
    ASSERT_TRUE(unlit) << unlit.error();
    const auto day = fileView(*unlit, "", 16);
    ASSERT_TRUE(day) << day.error();
    EXPECT_TRUE(day->sun);
    EXPECT_NEAR(day->light.wsTowardsLight().y, std::sqrt(0.5), 1e-9);
}

TEST(FileViewTest, NoCameraOrOneLookingAwayIsOneLine) {
    Scene none;
    const auto noCamera = fileView(none, "", 16);
    ASSERT_FALSE(noCamera);
    EXPECT_NE(noCamera.error().find("no camera of its own"), std::string::npos) << noCamera.error();

    auto scene = scene::testing::loadWritten("sk_viewpoints_away.gltf", viewpointFile("[0,0,0]"));
    ASSERT_TRUE(scene) << scene.error();
    scene->cameras[0].localForward = core::Vec3(0, 1, 0); // straight up, from 5 m above the ground
    const auto away = fileView(*scene, "", 16);
    ASSERT_FALSE(away);
    EXPECT_NE(away.error().find("looks away from the scene"), std::string::npos) << away.error();
}

TEST(FileViewTest, ExportedAndLoadedBackTheCamerasAndLightsStay) {
    // `shadowkit export` keeps what the file brought: written to a .glb and read back, each
    // camera and light stands where it stood in the world, 5,400 km out as at the origin.
    const auto scene = scene::testing::loadWritten("sk_viewpoints_export.gltf", viewpointFile("[512345,20,5412345]"));
    ASSERT_TRUE(scene) << scene.error();
    const auto file = shadowkit::test_support::scratchDir() / "sk_viewpoints_export.glb";
    ASSERT_TRUE(exportScene(*scene, file));
    const auto back = loadScene(file);
    std::filesystem::remove(file);
    ASSERT_TRUE(back) << back.error();
    ASSERT_EQ(back->cameras.size(), scene->cameras.size());
    ASSERT_EQ(back->lights.size(), scene->lights.size());
    const FileCamera &was = scene->cameras[0], &is = back->cameras[0];
    EXPECT_EQ(is.name, was.name);
    expectVec3Near(is.localEye + back->wsOrigin, was.localEye + scene->wsOrigin, 1e-6, "eye");
    expectVec3Near(is.localForward, was.localForward, 1e-6, "forward");
    expectVec3Near(is.localUp, was.localUp, 1e-6, "up");
    EXPECT_NEAR(is.fovYDegrees, was.fovYDegrees, 1e-9);
    EXPECT_EQ(is.aspect, was.aspect);
    EXPECT_EQ(is.zNear, was.zNear);
    EXPECT_EQ(is.zFar, was.zFar);
    // The orthographic camera goes back orthographic, of the same size and planes.
    const FileCamera &flatWas = scene->cameras[1], &flatIs = back->cameras[1];
    ASSERT_TRUE(flatIs.orthographicHalfHeight);
    EXPECT_EQ(flatIs.orthographicHalfHeight, flatWas.orthographicHalfHeight);
    EXPECT_EQ(flatIs.aspect, flatWas.aspect);
    EXPECT_EQ(flatIs.zNear, flatWas.zNear);
    EXPECT_EQ(flatIs.zFar, flatWas.zFar);
    for (size_t i = 0; i < scene->lights.size(); ++i) {
        const FileLight &l0 = scene->lights[i], &l1 = back->lights[i];
        EXPECT_EQ(l1.kind, l0.kind) << i;
        EXPECT_EQ(l1.name, l0.name) << i;
        EXPECT_EQ(l1.range, l0.range) << i;
        expectVec3Near(l1.localPosition + back->wsOrigin, l0.localPosition + scene->wsOrigin, 1e-6, "light position");
        if (l0.kind != FileLight::Kind::Point)
            expectVec3Near(l1.localDirection, l0.localDirection, 1e-6, "light direction");
        if (l0.kind == FileLight::Kind::Spot) {
            EXPECT_NEAR(l1.coneDegrees, l0.coneDegrees, 1e-9) << i;
        }
    }
}
