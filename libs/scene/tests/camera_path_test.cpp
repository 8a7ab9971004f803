// Camera paths: through every key at its time, smooth between them, and clear errors for
// bad files; the standard flythrough is what EVALUATION.md §2 asks for, and frames a loaded
// model that has no ground.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/camera_path.h"
#include "shadowkit/scene/forest.h"

#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>

using namespace shadowkit;

namespace {

std::vector<scene::CameraKey> zigzag() {
    // Uneven spacing in time and space, a climb and a turn.
    return {{0.0, {0, 1.8, 0}, {0, 1.8, -10}},
            {1.0, {5, 1.8, -3}, {10, 2.0, -10}},
            {1.5, {6, 10.0, -9}, {0, 0.0, -30}},
            {4.0, {-10, 30.0, -20}, {-20, 0.0, -60}}};
}

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
    const auto path = shadowkit::test_support::scratchDir() / name;
    std::ofstream(path) << text;
    return path;
}

} // namespace

TEST(CameraPath, PassesThroughEveryKeyAtItsTime) {
    const auto keys = zigzag();
    for (const scene::CameraKey& key : keys) {
        const scene::CameraKey at = scene::cameraAt(keys, key.time);
        EXPECT_NEAR(glm::distance(at.eye, key.eye), 0.0, 1e-9) << key.time;
        EXPECT_NEAR(glm::distance(at.target, key.target), 0.0, 1e-9) << key.time;
    }
    // Outside the keys it holds the ends.
    EXPECT_EQ(scene::cameraAt(keys, -5.0).eye, keys.front().eye);
    EXPECT_EQ(scene::cameraAt(keys, 99.0).eye, keys.back().eye);
}

TEST(CameraPath, IsSmoothNoJumpBetweenFramesBeyondTheKeySpacing) {
    const auto keys = zigzag();
    const int frames = 400;
    const double dt = (keys.back().time - keys.front().time) / (frames - 1);
    // The fastest straight-line speed between neighbouring keys bounds the step a frame
    // takes, up to the cubic's swing (a monotone cubic's slope stays within 3 times the
    // segment's).
    double fastest = 0.0;
    for (size_t k = 0; k + 1 < keys.size(); ++k)
        fastest = std::max(fastest, glm::distance(keys[k + 1].eye, keys[k].eye) / (keys[k + 1].time - keys[k].time));
    core::Vec3 lastEye{}, lastStep{};
    for (int f = 0; f < frames; ++f) {
        const scene::CameraKey at = scene::cameraAt(keys, keys.front().time + f * dt);
        if (f > 0) {
            const core::Vec3 step = at.eye - lastEye;
            EXPECT_LE(glm::length(step), 3.0 * fastest * dt) << "frame " << f;
            // Velocity is continuous: consecutive steps differ by far less than a step.
            if (f > 1) {
                EXPECT_LE(glm::length(step - lastStep), 0.1 * fastest * dt) << "frame " << f;
            }
            lastStep = step;
        }
        lastEye = at.eye;
        EXPECT_GE(at.eye.y, 1.8 - 1e-12); // never below the lowest key, though two keys sit there
        EXPECT_LE(at.eye.y, 30.0 + 1e-12);
    }
}

TEST(CameraPath, TheFlythroughHas240FramesBetween1Point8And40MetresAndATenDegreeSun) {
    auto path = scene::findCameraPath("flythrough", std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "paths");
    ASSERT_TRUE(path) << path.error();
    EXPECT_EQ(path->frames, 240);
    EXPECT_EQ(path->width, 1280);
    EXPECT_EQ(path->height, 720);
    double low = INFINITY, high = -INFINITY;
    for (int f = 0; f < path->frames; ++f) {
        const scene::CameraKey at = scene::cameraAt(path->camera, path->timeOfFrame(f));
        low = std::min(low, at.eye.y), high = std::max(high, at.eye.y);
    }
    EXPECT_NEAR(low, 1.8, 1e-9);
    EXPECT_NEAR(high, 40.0, 1e-9);
    ASSERT_FALSE(path->sun.empty());
    const scene::SunKey first = scene::sunAt(path->sun, path->startTime()),
                        last = scene::sunAt(path->sun, path->endTime());
    const auto a = core::DirectionalLight::fromSunAngles(first.elevationDegrees, first.azimuthDegrees).value();
    const auto b = core::DirectionalLight::fromSunAngles(last.elevationDegrees, last.azimuthDegrees).value();
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(a.wsDirection, b.wsDirection))), 10.0, 1e-6);
    // Every frame resolves over the forest into a valid camera.
    scene::ForestOptions o;
    o.trees = 0;
    const scene::Scene forest = scene::makeForest(o);
    for (int f = 0; f < path->frames; f += 7) EXPECT_TRUE(scene::viewAt(*path, forest, path->timeOfFrame(f))) << f;
}

TEST(CameraPath, BadFilesGiveErrorsNamingTheFileAndTheKey) {
    const auto backwards = writeFile("sk_path_backwards.json", R"({"camera": [
        {"time": 1, "eye_xz": [0, 0], "target_xz": [0, -5]},
        {"time": 0.5, "eye_xz": [1, 0], "target_xz": [0, -5]}]})");
    auto p = scene::loadCameraPath(backwards);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().find("sk_path_backwards.json"), std::string::npos) << p.error();
    EXPECT_NE(p.error().find("camera key 1"), std::string::npos) << p.error();
    const auto noTarget = writeFile("sk_path_no_target.json", R"({"camera": [{"time": 0, "eye_xz": [0, 0]}]})");
    p = scene::loadCameraPath(noTarget);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().find("target_xz"), std::string::npos) << p.error();
    const auto badSun =
        writeFile("sk_path_bad_sun.json", R"({"camera": [{"time": 0, "eye_xz": [0, 0], "target_xz": [0, -5]}],
        "sun": [{"time": 0, "elevation": 95, "azimuth": 0}]})");
    p = scene::loadCameraPath(badSun);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().find("sun key 0"), std::string::npos) << p.error();
    const auto wrongType =
        writeFile("sk_path_wrong_type.json", R"({"camera": [{"time": 0, "eye_xz": "here", "target_xz": [0, -5]}]})");
    p = scene::loadCameraPath(wrongType);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().find("wrong type"), std::string::npos) << p.error();
    p = scene::findCameraPath("no-such-path", std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "paths");
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().find("flythrough"), std::string::npos) << p.error(); // lists the known ones
}

// Keys no frame could use are refused when the file is read, naming the file and the key, rather
// than frames into a run (an eye 1e49 m up; times 1e308 s apart gave "meet at t = -nan s").
TEST(CameraPath, KeysNoFrameCouldUseAreRefusedWhenTheFileIsRead) {
    const std::string key1 = R"({"time": 1, "eye_xz": [5, 0], "target_xz": [10, 10]})";
    const std::vector<std::pair<std::string, std::string>> files = {
        {"eye-far", R"({"camera": [{"time": 0, "eye_xz": [0, 0], "eye_height": 1e49, "target_xz": [10, 10]}]})"},
        {"target-far", R"({"camera": [{"time": 0, "eye_xz": [0, 0], "target_xz": [-6e12, 10]}]})"},
        {"times-far", R"({"camera": [{"time": -1e308, "eye_xz": [0, 0], "target_xz": [10, 10]},)" + key1 + "]}"},
        {"times-close",
         R"({"camera": [{"time": 0.9999999999, "eye_xz": [0, 0], "target_xz": [10, 10]},)" + key1 + "]}"},
        {"meet",
         R"({"camera": [{"time": 0, "eye_xz": [3, 4], "eye_height": 2, "target_xz": [3, 4], "target_height": 2}]})"},
        {"sun-spins", R"({"camera": [)" + key1 + R"(], "sun": [{"time": 0, "elevation": 30, "azimuth": 1e300}]})"},
        {"sun-times-close", R"({"camera": [)" + key1 + R"(], "sun": [{"time": 0, "elevation": 30, "azimuth": 0},
            {"time": 1e-320, "elevation": 40, "azimuth": 0}]})"},
    };
    for (const auto& [name, text] : files) {
        const auto file = writeFile("sk_path_" + name + ".json", text);
        const auto p = scene::loadCameraPath(file);
        ASSERT_FALSE(p) << name;
        EXPECT_NE(p.error().find(file.string()), std::string::npos) << p.error();
        EXPECT_NE(p.error().find(name.starts_with("sun") ? "sun key " : "camera key "), std::string::npos) << p.error();
        EXPECT_EQ(p.error().find('\n'), std::string::npos) << p.error();
    }
}

// A path at those bounds — eyes and targets 5e12 m out, keys microseconds apart, the sun turned
// 1e6 degrees — is read, and every frame of it is a usable camera under a finite sun: the bounds
// are enough for the interpolation to stay finite.
TEST(CameraPath, APathAtTheBoundsGivesAUsableCameraAtEveryFrame) {
    const auto file = writeFile("sk_path_at_bounds.json", R"({"frames": 50, "camera": [
        {"time": -1e9, "eye_xz": [-5e12, 5e12], "eye_height": 5e12, "target_xz": [5e12, -5e12]},
        {"time": -999999999.999998, "eye_xz": [5e12, -5e12], "eye_height": 0, "target_xz": [-5e12, 5e12]},
        {"time": 1e9, "eye_xz": [0, 0], "target_xz": [0, -10]}],
        "sun": [{"time": -1e9, "elevation": -90, "azimuth": -1e6}, {"time": 1e9, "elevation": 90, "azimuth": 1e6}]})");
    const auto path = scene::loadCameraPath(file);
    ASSERT_TRUE(path) << path.error();
    scene::ForestOptions o;
    o.trees = 0;
    const scene::Scene forest = scene::makeForest(o);
    for (int frame = 0; frame < path->frames; ++frame) {
        const double t = path->timeOfFrame(frame);
        ASSERT_TRUE(std::isfinite(t));
        const auto view = scene::viewAt(*path, forest, t);
        ASSERT_TRUE(view) << "frame " << frame << ": " << view.error();
        EXPECT_TRUE(view->camera.validate()) << "frame " << frame;
        EXPECT_TRUE(core::isFinite(view->light.wsDirection)) << "frame " << frame;
    }
    // Between its first two keys, two microseconds apart, the eye moves 1.5e13 m and stays finite.
    for (const double t : {-1e9 + 5e-7, -1e9 + 1e-6, -1e9 + 1.5e-6}) {
        const scene::CameraKey key = scene::cameraAt(path->camera, t);
        EXPECT_TRUE(core::isFinite(key.eye) && core::isFinite(key.target)) << t;
    }
}

// A path may pass under its target (found by fuzz_paths): where the camera looks straight up,
// the sky's up is no direction in the image; north is (a usable camera, not "up parallel").
TEST(CameraPath, ACameraPassingUnderItsTargetLooksStraightUpWithNorthAtTheTop) {
    scene::CameraPath path;
    path.name = "under";
    path.camera = {{0.0, {0, 2, 0}, {10, 5, 0}}, {2.0, {20, 2, 0}, {10, 5, 0}}};
    scene::ForestOptions o;
    o.trees = 0;
    o.terrainSize = 100;
    const scene::Scene forest = scene::makeForest(o);
    const auto straightUp = scene::viewAt(path, forest, 1.0); // the eye at (10, 2, 0), under the target
    ASSERT_TRUE(straightUp) << straightUp.error();
    EXPECT_NEAR(straightUp->camera.wsDirection.y, 1.0, 1e-9);
    EXPECT_EQ(straightUp->camera.wsUp, core::Vec3(0, 0, -1));
    EXPECT_TRUE(straightUp->camera.validate());
    const auto before = scene::viewAt(path, forest, 0.5); // looking up and east: the sky's up
    ASSERT_TRUE(before) << before.error();
    EXPECT_EQ(before->camera.wsUp, core::Vec3(0, 1, 0));
}

TEST(CameraPath, EyeMeetingTargetIsAnErrorNotANanCamera) {
    scene::CameraPath path;
    path.name = "meet";
    path.camera = {{0.0, {0, 2, 0}, {0, 2, 0}}};
    scene::ForestOptions o;
    o.trees = 0;
    const scene::Scene forest = scene::makeForest(o);
    auto view = scene::viewAt(path, forest, 0.0);
    ASSERT_FALSE(view);
    EXPECT_NE(view.error().find("eye and target meet"), std::string::npos);
}

TEST(CameraPath, TheSunsSizeFollowsItsKeysMonotoneAndReachesTheView) {
    // A sunset through haze: the sun's disk grows from 0.53° to 1.2°, then holds.
    const auto file = writeFile("sk_path_sun_angle.json", R"({"camera": [
        {"time": 0, "eye_xz": [0, 0], "target_xz": [0, -5]}, {"time": 4, "eye_xz": [1, 0], "target_xz": [1, -5]}],
        "sun": [{"time": 0, "elevation": 30, "azimuth": 90, "angle": 0.53},
                {"time": 2, "elevation": 10, "azimuth": 100, "angle": 1.2},
                {"time": 4, "elevation": 5, "azimuth": 110, "angle": 1.2}]})");
    auto path = scene::loadCameraPath(file);
    ASSERT_TRUE(path) << path.error();
    double last = 0.0;
    for (double t = -1.0; t <= 5.0; t += 0.125) {
        const scene::SunKey key = scene::sunAt(path->sun, t);
        ASSERT_TRUE(key.angleDegrees) << t;
        // Never outside its neighbouring keys: no size below the smallest, never shrinking on the way up.
        EXPECT_GE(*key.angleDegrees, 0.53 - 1e-12) << t;
        EXPECT_LE(*key.angleDegrees, 1.2 + 1e-12) << t;
        EXPECT_GE(*key.angleDegrees, last - 1e-12) << t;
        last = *key.angleDegrees;
    }
    EXPECT_NEAR(*scene::sunAt(path->sun, 0.0).angleDegrees, 0.53, 1e-12);
    EXPECT_NEAR(*scene::sunAt(path->sun, 3.0).angleDegrees, 1.2, 1e-12); // held between equal keys

    scene::ForestOptions o;
    o.trees = 0;
    o.terrainResolution = 16;
    const scene::Scene forest = scene::makeForest(o);
    auto view = scene::viewAt(*path, forest, 2.0);
    ASSERT_TRUE(view) << view.error();
    ASSERT_TRUE(view->sunAngleDegrees);
    EXPECT_NEAR(*view->sunAngleDegrees, 1.2, 1e-12);
    // Keys without a size leave the view's unset (--sun-angle decides).
    path->sun = {{0.0, 30.0, 90.0, std::nullopt}};
    EXPECT_FALSE(scene::viewAt(*path, forest, 0.0).value().sunAngleDegrees);
}

TEST(CameraPath, ASunSizeOnSomeKeysOnlyOrOutOfRangeIsAnErrorNamingTheKey) {
    const std::string camera = R"("camera": [{"time": 0, "eye_xz": [0, 0], "target_xz": [0, -5]}])";
    const std::pair<const char*, const char*> cases[] = {
        {R"("sun": [{"time": 0, "elevation": 30, "azimuth": 0, "angle": 0.5}, {"time": 1, "elevation": 30, "azimuth": 0}])",
         "sun key 1: \"angle\" on some sun keys but not on others"},
        {R"("sun": [{"time": 0, "elevation": 30, "azimuth": 0}, {"time": 1, "elevation": 30, "azimuth": 0, "angle": 0.5}])",
         "sun key 1: \"angle\" on some sun keys but not on others"},
        {R"("sun": [{"time": 0, "elevation": 30, "azimuth": 0, "angle": 21}])",
         "sun key 0: angle must be a number in [0, 20]"},
        {R"("sun": [{"time": 0, "elevation": 30, "azimuth": 0, "angle": -1}])",
         "sun key 0: angle must be a number in [0, 20]"},
        {R"("sun": [{"time": 0, "elevation": 30, "azimuth": 0, "angle": "wide"}])",
         "sun key 0: angle must be a number"},
    };
    for (const auto& [sun, expected] : cases) {
        const auto file = writeFile("sk_path_bad_angle.json", "{" + camera + ", " + sun + "}");
        auto p = scene::loadCameraPath(file);
        ASSERT_FALSE(p) << sun;
        EXPECT_NE(p.error().find(expected), std::string::npos) << p.error();
        EXPECT_NE(p.error().find("sk_path_bad_angle.json"), std::string::npos) << p.error();
    }
}

namespace {

// A loaded model has no ground: a 40 × 6 × 10 m block far from the forest paths' keys.
scene::Scene blockModel() {
    scene::Scene model;
    scene::Mesh block;
    for (int corner = 0; corner < 8; ++corner)
        block.vertices.push_back(
            {.position = {corner & 1 ? 20.0f : -20.0f, corner & 2 ? 6.0f : 0.0f, corner & 4 ? 5.0f : -5.0f},
             .normal = {0, 1, 0},
             .albedo = {0.5f, 0.5f, 0.5f}});
    block.indices = {0, 1, 3, 0, 3, 2}; // the bounds are what framing reads
    block.computeBounds();
    model.meshes.push_back(block);
    model.batches.push_back({.mesh = 0, .worldFromObject = {glm::translate(glm::mat4(1.0f), {300, 20, -700})}});
    return model;
}

double compassOf(const core::Vec3& d) { return std::atan2(d.x, -d.z); }
double pitchOf(const core::Vec3& d) { return std::atan2(d.y, std::hypot(d.x, d.z)); }

} // namespace

// The standard paths are written for the forest's kilometre: over a loaded model they would face
// nothing. Each frame frames the model instead, looking the way the path looks at that moment.
TEST(CameraPath, APathWrittenForTheForestFramesALoadedModelInEveryFrameLookingTheWayItsKeysLook) {
    auto path = scene::findCameraPath("flythrough", std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "paths");
    ASSERT_TRUE(path) << path.error();
    ASSERT_TRUE(path->frameLoadedScene);
    const scene::Scene model = blockModel();
    const core::Aabb bounds = model.wsBounds();
    for (int f = 0; f < path->frames; f += 7) {
        const double t = path->timeOfFrame(f);
        const auto view = scene::viewAt(*path, model, t);
        ASSERT_TRUE(view) << f << ": " << view.error();
        EXPECT_TRUE(view->framed);
        // Every corner in the picture and between the planes; one near its edge (tight framing).
        const core::Mat4 clipFromWorld = view->camera.clipFromWorld();
        double outermost = 0.0;
        for (const core::Vec3& corner : bounds.corners()) {
            const glm::dvec4 clip = clipFromWorld * glm::dvec4(corner, 1.0);
            EXPECT_LE(std::abs(clip.x / clip.w), 1.0) << f;
            EXPECT_LE(std::abs(clip.y / clip.w), 1.0) << f;
            EXPECT_GE(clip.w, view->camera.zNear) << f;
            EXPECT_LE(clip.w, view->camera.zFar) << f;
            outermost = std::max({outermost, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
        }
        EXPECT_GT(outermost, 0.9) << f;
        // The keys' compass direction, and their pitch or 30° down where that is steeper.
        const scene::CameraKey key = scene::cameraAt(path->camera, t);
        const core::Vec3 along = key.target - key.eye;
        EXPECT_NEAR(compassOf(view->camera.wsDirection), compassOf(along), 1e-9) << f;
        EXPECT_NEAR(pitchOf(view->camera.wsDirection), std::min(pitchOf(along), glm::radians(-30.0)), 1e-9) << f;
    }
    // Frame to frame the framed camera moves smoothly (the flicker measured along it is the
    // shadows', not a jump of the camera): no step longer than 2 % of its distance to the model.
    for (int f = 1; f < path->frames; ++f) {
        const auto before = scene::viewAt(*path, model, path->timeOfFrame(f - 1)),
                   after = scene::viewAt(*path, model, path->timeOfFrame(f));
        ASSERT_TRUE(before && after) << f;
        const double reach = glm::distance(after->camera.wsEye, bounds.center());
        EXPECT_LE(glm::distance(before->camera.wsEye, after->camera.wsEye), 0.02 * reach) << f;
    }
    // A path whose keys are the model's own positions ("keys", the default) is followed as written.
    path->frameLoadedScene = false;
    const auto asWritten = scene::viewAt(*path, model, 0.0);
    ASSERT_TRUE(asWritten) << asWritten.error();
    EXPECT_FALSE(asWritten->framed);
    EXPECT_EQ(asWritten->camera.wsEye.x, path->camera.front().eye.x);
    EXPECT_EQ(asWritten->camera.wsEye.z, path->camera.front().eye.z);
    // Over the forest's ground the keys are followed either way.
    scene::ForestOptions o;
    o.trees = 0;
    o.terrainResolution = 16;
    const scene::Scene forest = scene::makeForest(o);
    const auto followed = scene::viewAt(*path, forest, 3.0);
    path->frameLoadedScene = true;
    const auto alsoFollowed = scene::viewAt(*path, forest, 3.0);
    ASSERT_TRUE(followed && alsoFollowed);
    EXPECT_EQ(followed->camera.wsEye, alsoFollowed->camera.wsEye);
    EXPECT_FALSE(alsoFollowed->framed);
}

// Looking straight down, the framing's compass is north's, as the image's up is: still framed.
TEST(CameraPath, AFramingPathLookingStraightDownKeepsTheModelInThePictureWithNorthAtTheTop) {
    scene::CameraPath path;
    path.name = "down";
    path.frameLoadedScene = true;
    path.camera = {{0.0, {7, 50, 3}, {7, 0, 3}}};
    const scene::Scene model = blockModel();
    const auto view = scene::viewAt(path, model, 0.0);
    ASSERT_TRUE(view) << view.error();
    EXPECT_NEAR(view->camera.wsDirection.y, -1.0, 1e-9);
    EXPECT_EQ(view->camera.wsUp, core::Vec3(0, 0, -1));
    ASSERT_TRUE(view->camera.validate());
    for (const core::Vec3& corner : model.wsBounds().corners()) {
        const glm::dvec4 clip = view->camera.clipFromWorld() * glm::dvec4(corner, 1.0);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0);
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0);
    }
}

TEST(CameraPath, AnUnknownOnLoadedSceneIsAnErrorNamingTheField) {
    const auto file = writeFile("sk_path_on_loaded.json", R"({"on_loaded_scene": "zoom", "camera": [
        {"time": 0, "eye_xz": [0, 0], "target_xz": [0, -5]}]})");
    const auto path = scene::loadCameraPath(file);
    ASSERT_FALSE(path);
    EXPECT_NE(path.error().find("on_loaded_scene must be \"frame\""), std::string::npos) << path.error();
    EXPECT_NE(path.error().find("sk_path_on_loaded.json"), std::string::npos) << path.error();
}

// `orbit`: a turntable. Over a loaded model every frame is framed and the camera's compass turns
// once round, so the sun stands ahead, beside and behind it in turn; the loop closes.
TEST(CameraPath, TheOrbitFramesAModelFromEveryCompassDirectionAndClosesItsLoop) {
    auto path = scene::findCameraPath("orbit", std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "paths");
    ASSERT_TRUE(path) << path.error();
    ASSERT_TRUE(path->frameLoadedScene);
    const scene::Scene model = blockModel();
    std::array<bool, 8> sectors{}; // 45° sectors of the view's compass
    for (int f = 0; f < path->frames; ++f) {
        const auto view = scene::viewAt(*path, model, path->timeOfFrame(f));
        ASSERT_TRUE(view) << f << ": " << view.error();
        ASSERT_TRUE(view->framed) << f;
        const double compass = std::fmod(glm::degrees(compassOf(view->camera.wsDirection)) + 360.0, 360.0);
        sectors[size_t(compass / 45.0) % 8] = true;
        // Round the clearing at its radius (the keys' circle, 60 m), looking at its centre.
        const scene::CameraKey key = scene::cameraAt(path->camera, path->timeOfFrame(f));
        EXPECT_NEAR(std::hypot(key.eye.x, key.eye.z), 60.0, 3.0) << f;
    }
    for (size_t s = 0; s < sectors.size(); ++s) EXPECT_TRUE(sectors[s]) << "no frame looks towards " << 45 * s << "°";
    const auto first = scene::viewAt(*path, model, path->startTime()),
               last = scene::viewAt(*path, model, path->endTime());
    ASSERT_TRUE(first && last);
    EXPECT_LT(glm::distance(first->camera.wsEye, last->camera.wsEye), 1e-6);
}

// Over a scene whose movers move, a framing path frames one box for the whole path: the box of
// the scene at the path's frames. The camera holds its distance (it zoomed in and out with a
// mover before), the mover stays in the picture, and a frame drawn alone is framed as in the
// sequence, whatever time the scene stood at before.
TEST(CameraPath, AFramingPathHoldsItsCameraWhileAMoverTravelsAndKeepsTheMoverInThePicture) {
    scene::Scene model = blockModel();
    // A 2 × 0.3 × 0.5 m mover once round a circle 80 m out from the block's centre.
    scene::MeshBatch movers{.mesh = 0, .worldFromObject = {glm::mat4(1.0f)}, .dynamic = true};
    model.batches.push_back(movers);
    scene::CameraPath path;
    path.name = "held";
    path.frameLoadedScene = true;
    path.frames = 48;
    path.camera = {{0.0, {0, 40, 60}, {0, 0, 0}}, {12.0, {0, 40, 60}, {0, 0, 0}}};
    constexpr double kRadius = 80.0;
    model.tracks.push_back({.batch = 1,
                            .instance = 0,
                            .centreX = 300.0,
                            .centreZ = -700.0,
                            .radius = kRadius,
                            .speed = 2.0 * std::numbers::pi * kRadius / path.endTime(),
                            .lift = 0.0,
                            .scale = 0.05f});
    ASSERT_TRUE(model.animated());

    const double now = path.timeOfFrame(17);
    const core::Aabb box = scene::framedOverPath(path, model, now);
    ASSERT_FALSE(box.isEmpty());
    // The scene is left where `now` puts it, and the box does not depend on `now`.
    const glm::mat4 placed = model.batches[1].worldFromObject[0];
    scene::animate(model, now);
    EXPECT_EQ(model.batches[1].worldFromObject[0], placed);
    const core::Aabb fromStart = scene::framedOverPath(path, model, 0.0);
    EXPECT_EQ(fromStart.min, box.min);
    EXPECT_EQ(fromStart.max, box.max);
    // The box spans the mover's circle, not the block alone.
    EXPECT_GT(box.diagonal(), 2.0 * kRadius);

    std::optional<core::Vec3> firstEye;
    for (int f = 0; f < path.frames; ++f) {
        const double t = path.timeOfFrame(f);
        scene::animate(model, t);
        const auto view = scene::viewAt(path, model, t, {}, box);
        ASSERT_TRUE(view) << f << ": " << view.error();
        ASSERT_TRUE(view->framed) << f;
        if (!firstEye) firstEye = view->camera.wsEye;
        EXPECT_EQ(view->camera.wsEye, *firstEye) << f; // a held camera holds
        // The whole scene as it stands at t — the mover included — inside the picture.
        const core::Mat4 clipFromWorld = view->camera.clipFromWorld();
        for (const core::Vec3& corner : model.wsBounds().corners()) {
            const glm::dvec4 clip = clipFromWorld * glm::dvec4(corner, 1.0);
            EXPECT_LE(std::abs(clip.x / clip.w), 1.0) << f;
            EXPECT_LE(std::abs(clip.y / clip.w), 1.0) << f;
            EXPECT_GE(clip.w, view->camera.zNear) << f;
            EXPECT_LE(clip.w, view->camera.zFar) << f;
        }
    }
    // Without the path's box each frame frames the scene as it stands: the camera follows the mover.
    scene::animate(model, path.timeOfFrame(0));
    const auto early = scene::viewAt(path, model, path.timeOfFrame(0));
    scene::animate(model, path.timeOfFrame(path.frames / 4));
    const auto later = scene::viewAt(path, model, path.timeOfFrame(path.frames / 4));
    ASSERT_TRUE(early && later);
    EXPECT_GT(glm::distance(early->camera.wsEye, later->camera.wsEye), 1.0);

    // A path that follows its keys frames nothing.
    path.frameLoadedScene = false;
    EXPECT_TRUE(scene::framedOverPath(path, model, now).isEmpty());
}
