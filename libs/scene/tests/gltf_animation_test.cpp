// A glTF's animations (gltf_animation.cpp) move the instances below the nodes they target, as
// scene::animate plays them; what cannot be played is a warning and stays at rest; exported,
// they play again, and a forest's circling movers with them. Expected
// positions are worked by hand from the file's turn about +y, not read back from the loader.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// Bytes of the test file's one buffer, each block at a known offset.
struct SpinnerBuffer {
    std::vector<unsigned char> bytes;
    size_t add(const std::vector<float>& floats) {
        const size_t at = bytes.size();
        const auto* first = reinterpret_cast<const unsigned char*>(floats.data());
        bytes.insert(bytes.end(), first, first + floats.size() * sizeof(float));
        return at;
    }
};

// Node 0 "spinner" at `rootAt` turns +90° about +y over a second (animation 0 'Spin'); its child
// node 1 holds the triangle 2 m along its +x. Node 2 holds the same triangle at rest 20 m to
// the spinner's −x. Also: 'Spin' animates node 1's morph weights (its mesh has none: left at rest), animation 1
// 'Again' turns the spinner too (the first animation plays it), and animation 2 'Broken' moves
// node 2 with times that run backwards (left at rest).
// `instanced`: node 1 places its triangle twice (EXT_mesh_gpu_instancing), 0 and 3 m along its +z.
std::string spinnerFile(const std::string& rootAt, const std::string& staticAt, bool instanced = false) {
    SpinnerBuffer b;
    const size_t triangle = b.add({0, 0, 0, 0, 0, 1, 1, 0, 0});
    const size_t times = b.add({0, 1});
    const double half = glm::radians(45.0);
    const size_t turns = b.add({0, 0, 0, 1, 0, float(std::sin(half)), 0, float(std::cos(half))});
    const size_t backwards = b.add({1, 0});
    const size_t moves = b.add({0, 0, 0, 0, 5, 0});
    const size_t weights = b.add({0, 1});
    const size_t instances = b.add({0, 0, 0, 0, 0, 3});
    const auto view = [](size_t offset, size_t length) {
        return R"({"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" + std::to_string(length) +
               "}";
    };
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,2]}],
        "nodes":[{"name":"spinner","translation":)" +
           rootAt + R"(,"children":[1]},{"mesh":0,"translation":[2,0,0])" +
           (instanced ? R"(,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":6}}})" : "") +
           R"(},{"mesh":0,"translation":)" + staticAt + R"(}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "animations":[
          {"name":"Spin","samplers":[{"input":1,"output":2},{"input":1,"output":5}],
           "channels":[{"sampler":0,"target":{"node":0,"path":"rotation"}},{"sampler":1,"target":{"node":1,"path":"weights"}}]},
          {"name":"Again","samplers":[{"input":1,"output":2,"interpolation":"STEP"}],
           "channels":[{"sampler":0,"target":{"node":0,"path":"rotation"}}]},
          {"name":"Broken","samplers":[{"input":3,"output":4}],
           "channels":[{"sampler":0,"target":{"node":2,"path":"translation"}}]}],
        "accessors":[
          {"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,0,1]},
          {"bufferView":1,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},
          {"bufferView":2,"componentType":5126,"count":2,"type":"VEC4"},
          {"bufferView":3,"componentType":5126,"count":2,"type":"SCALAR"},
          {"bufferView":4,"componentType":5126,"count":2,"type":"VEC3"},
          {"bufferView":5,"componentType":5126,"count":2,"type":"SCALAR"},
          {"bufferView":6,"componentType":5126,"count":2,"type":"VEC3"}],
        "bufferViews":[)" +
           view(triangle, 36) + "," + view(times, 8) + "," + view(turns, 32) + "," + view(backwards, 8) + "," +
           view(moves, 24) + "," + view(weights, 8) + "," + view(instances, 24) + R"(],
        "buffers":[{"byteLength":)" +
           std::to_string(b.bytes.size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
           scene::testing::base64(b.bytes) + "\"}]}";
}

// Where the object origin of every instance of the scene's dynamic or static batch stands in
// the world.
std::vector<glm::dvec3> originsOf(const Scene& s, bool dynamic) {
    std::vector<glm::dvec3> out;
    for (const MeshBatch& batch : s.batches)
        if (batch.dynamic == dynamic)
            for (const glm::mat4& m : batch.worldFromObject) out.push_back(s.wsOrigin + glm::dvec3(m[3]));
    return out;
}

// The child's origin at time t: the spinner's place plus (2, 0, 0) turned 90°·t about +y
// (+x turns towards −z), the turn looping each second.
glm::dvec3 spunAt(const glm::dvec3& root, double t) {
    const double angle = glm::radians(90.0 * std::fmod(t, 1.0));
    return root + glm::dvec3(2.0 * std::cos(angle), 0.0, -2.0 * std::sin(angle));
}

void expectNear(const glm::dvec3& got, const glm::dvec3& want, double tolerance, const std::string& what) {
    EXPECT_LT(glm::distance(got, want), tolerance) << what << ": got (" << got.x << ", " << got.y << ", " << got.z
                                                   << "), want (" << want.x << ", " << want.y << ", " << want.z << ")";
}

} // namespace

TEST(GltfAnimationTest, AnInstanceBelowAnAnimatedNodeMovesAsItsKeysSayAndLoops) {
    auto scene = scene::testing::loadWritten("sk_spinner.gltf", spinnerFile("[10,0,0]", "[-10,0,0]"));
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_EQ(scene->tracks.size(), 1u) << "the spinner's child, and only it, moves";
    EXPECT_TRUE(scene->batches[scene->tracks[0].batch].dynamic);
    const glm::dvec3 root(10, 0, 0);
    expectNear(originsOf(*scene, true).at(0), spunAt(root, 0.0), 1e-5, "as loaded: t = 0");
    for (double t : {0.25, 0.5, 1.0 - 1e-9, 1.5, 2.75}) {
        animate(*scene, t);
        expectNear(originsOf(*scene, true).at(0), spunAt(root, t), 1e-5, "t = " + std::to_string(t));
        expectNear(originsOf(*scene, false).at(0), {-10, 0, 0}, 1e-6, "the static instance");
    }
}

TEST(GltfAnimationTest, WhatCannotBePlayedIsOneWarningAnAnimationAndStaysAtRest) {
    const auto scene = scene::testing::loadWritten("sk_spinner.gltf", spinnerFile("[10,0,0]", "[-10,0,0]"));
    ASSERT_TRUE(scene) << scene.error();
    std::string all;
    for (const std::string& w : scene->warnings) all += w + "\n";
    EXPECT_EQ(scene->warnings.size(), 3u) << all;
    const auto says = [&](const std::string& text) { return all.find(text) != std::string::npos; };
    EXPECT_TRUE(
        says("animation 0 'Spin': channel 1 moves the morph weights of node 1, whose mesh has no morph targets"))
        << all;
    EXPECT_TRUE(says("animation 1 'Again': channel 0 moves what animation 0 moves")) << all;
    EXPECT_TRUE(says("animation 2 'Broken': channel 0 (sampler 0): key 1's time comes before the key before it"))
        << all;
    for (const std::string& w : scene->warnings) EXPECT_EQ(w.find('\n'), std::string::npos) << w;
}

// A character's many clips each moving what the first moves: three lines say what happens and
// one counts the rest, not a line a clip.
TEST(GltfAnimationTest, ManyClipsMovingTheSameNodesAreCountedNotListed) {
    std::string text = spinnerFile("[10,0,0]", "[-10,0,0]");
    const std::string again =
        R"({"name":"Again","samplers":[{"input":1,"output":2,"interpolation":"STEP"}],
           "channels":[{"sampler":0,"target":{"node":0,"path":"rotation"}}]},)";
    const size_t at = text.find(again);
    ASSERT_NE(at, std::string::npos);
    for (int copy = 0; copy < 3; ++copy) text.insert(at, again); // 'Again' four times over: six lines to say
    const auto scene = scene::testing::loadWritten("sk_clips.gltf", text);
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_EQ(scene->warnings.size(), 4u);
    EXPECT_NE(scene->warnings[0].find("animation 0 'Spin'"), std::string::npos) << scene->warnings[0];
    EXPECT_NE(scene->warnings[1].find("animation 1 'Again': channel 0 moves what animation 0 moves"), std::string::npos)
        << scene->warnings[1];
    EXPECT_NE(scene->warnings[3].find("sk_clips.gltf: and 3 more animations with channels left at rest"),
              std::string::npos)
        << scene->warnings[3];
    ASSERT_EQ(scene->tracks.size(), 1u) << "the first animation still plays";
}

// Far from the origin and turned z-up, the motion stands where the loader stood the rest of
// the scene: the world point is the file's, turned (x, y, z) → (x, z, −y).
TEST(GltfAnimationTest, FarOutAndZUpTheMotionStaysWithItsScene) {
    const glm::dvec3 farRoot(2.0e6, 0.0, -3.0e6);
    auto far =
        scene::testing::loadWritten("sk_spinner_far.gltf", spinnerFile("[2000000,0,-3000000]", "[1999980,0,-3000000]"));
    ASSERT_TRUE(far) << far.error();
    EXPECT_GT(glm::length(far->wsOrigin), 1e6) << "the scene stands far out, its floats near zero";
    animate(*far, 0.5);
    expectNear(originsOf(*far, true).at(0), spunAt(farRoot, 0.5), 1e-3, "far out");

    auto turned =
        scene::testing::loadWritten("sk_spinner_z.gltf", spinnerFile("[10,0,0]", "[-10,0,0]"), {.up = UpAxis::Z});
    ASSERT_TRUE(turned) << turned.error();
    animate(*turned, 0.5);
    const glm::dvec3 file = spunAt({10, 0, 0}, 0.5);
    expectNear(originsOf(*turned, true).at(0), {file.x, file.z, -file.y}, 1e-5, "z-up");
}

// Instances below a moving node (EXT_mesh_gpu_instancing) move with it, each keeping its own
// place in the node's frame: (2, 0, 3k) turned 90°·t about +y, (x, z) → (x cos + z sin, z cos − x sin).
TEST(GltfAnimationTest, InstancesBelowAMovingNodeKeepTheirPlacesInItsFrame) {
    auto scene = scene::testing::loadWritten("sk_spinner_instanced.gltf", spinnerFile("[10,0,0]", "[-10,0,0]", true));
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_EQ(scene->tracks.size(), 2u);
    animate(*scene, 0.5);
    const double angle = glm::radians(45.0);
    std::vector<glm::dvec3> want;
    for (double k : {0.0, 1.0}) {
        const double x = 2.0, z = 3.0 * k;
        want.push_back(
            {10.0 + x * std::cos(angle) + z * std::sin(angle), 0.0, z * std::cos(angle) - x * std::sin(angle)});
    }
    const std::vector<glm::dvec3> got = originsOf(*scene, true);
    ASSERT_EQ(got.size(), 2u);
    for (size_t k = 0; k < 2; ++k) expectNear(got[k], want[k], 1e-5, "instance " + std::to_string(k));
}

// Exported to .glb and read back, a file's animations move the same instances the same way:
// far out, turned z-up and instanced below the moving node, at times across the loop.
TEST(GltfAnimationTest, ExportedAndLoadedBackTheAnimationsPlayTheSame) {
    auto original = scene::testing::loadWritten(
        "sk_spinner_export.gltf", spinnerFile("[2000000,0,-3000000]", "[1999980,0,-3000000]", true), {.up = UpAxis::Z});
    ASSERT_TRUE(original) << original.error();
    const auto file = shadowkit::test_support::scratchDir() / "sk_spinner_export.glb";
    ASSERT_TRUE(exportScene(*original, file));
    auto back = loadScene(file);
    ASSERT_TRUE(back) << back.error();
    ASSERT_EQ(back->tracks.size(), original->tracks.size());
    EXPECT_TRUE(back->warnings.empty()) << back->warnings.front(); // nothing left at rest: all was written
    const auto sorted = [](std::vector<glm::dvec3> points) {
        std::sort(points.begin(), points.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
            return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
        });
        return points;
    };
    for (double t : {0.0, 0.3, 0.5, 1.7}) {
        animate(*original, t);
        animate(*back, t);
        const std::vector<glm::dvec3> want = sorted(originsOf(*original, true)), got = sorted(originsOf(*back, true));
        ASSERT_EQ(got.size(), want.size());
        for (size_t k = 0; k < got.size(); ++k) expectNear(got[k], want[k], 1e-3, "t = " + std::to_string(t));
        expectNear(originsOf(*back, false).at(0), originsOf(*original, false).at(0), 1e-3, "the static instance");
    }
}

// A forest's movers circle by a rule, not by keys: exported, they go as keys round their circles
// (scene::circleAsKeys), and loaded back they circle as they did — on a hill, at times across and
// past each loop, turned as they turn (a point 2 m along each mover's +x).
TEST(GltfAnimationTest, AForestsCirclingMoversGoToAGlbAsKeysAndCircleOnLoadedBack) {
    ForestOptions options;
    options.trees = 0;
    options.terrainSize = 200.0;
    options.terrainResolution = 32;
    options.rocks = 0;
    options.buildings = 0;
    options.movers = 5;
    Scene forest = makeForest(options);
    ASSERT_EQ(forest.tracks.size(), 5u);
    const auto file = shadowkit::test_support::scratchDir() / "sk_forest_movers.glb";
    ASSERT_TRUE(exportScene(forest, file));
    auto back = loadScene(file);
    ASSERT_TRUE(back) << back.error();
    ASSERT_EQ(back->tracks.size(), forest.tracks.size());
    EXPECT_TRUE(back->warnings.empty()) << back->warnings.front();
    // Each mover's origin and the point 2 m along its +x, ordered by origin.
    const auto placements = [](const Scene& s) {
        std::vector<std::pair<glm::dvec3, glm::dvec3>> out;
        for (const Track& track : s.tracks) {
            const glm::dmat4 m(s.batches[track.batch].worldFromObject[track.instance]);
            out.emplace_back(s.wsOrigin + glm::dvec3(m[3]), s.wsOrigin + glm::dvec3(m * glm::dvec4(2, 0, 0, 1)));
        }
        std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
            return std::tie(a.first.x, a.first.z) < std::tie(b.first.x, b.first.z);
        });
        return out;
    };
    for (double t : {0.0, 0.8, 7.3, 41.0, 400.0}) {
        animate(forest, t);
        animate(*back, t);
        const auto want = placements(forest), got = placements(*back);
        for (size_t k = 0; k < got.size(); ++k) {
            // 1 cm from the arc (circleAsKeys's default), 2 cm from the ground where it bends between keys.
            expectNear(got[k].first, want[k].first, 0.03, "t = " + std::to_string(t));
            expectNear(got[k].second, want[k].second, 0.03, "turned, t = " + std::to_string(t));
        }
    }
}
