// A glTF's skins and morph weights stand as its animations pose them: loaded at
// LoadOptions::poseSeconds (gltf_animation.cpp's poseNodes, then gltf_pose.cpp), and played to any
// time after by scene::animate (deformation.h). Every expected position is worked by hand from
// the file's keys, not read back from the loader; each is checked both ways, so a frame played
// from another pose must equal a fresh load.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

template <typename T>
void appendValues(std::vector<unsigned char>& bytes, const std::vector<T>& values) {
    const auto* first = reinterpret_cast<const unsigned char*>(values.data());
    bytes.insert(bytes.end(), first, first + values.size() * sizeof(T));
}

// A skinned triangle: joint A (node 1) at (0, 0, 5); joint B (node 2) at (10, 0, 0), turned 90°
// about +y at rest, with an inverse bind matrix moving 2 along −z; corner 0 (1, 0, 0) bound to A,
// corner 1 (0, 0, 0) to B, corner 2 (0, 0, −1) half to each. Node 3, a child of B, holds an
// unskinned triangle with a corner at (1, 0, 0). Animation 0 'Wave' turns B from 90° to 180°
// about +y over a second, LINEAR. `armature`: both joints below node 4, which the animation
// moves from 0 to 10 m along +z over the second too.
std::string wavingFile(bool armature = false) {
    std::vector<unsigned char> b;
    appendValues<float>(b, {1, 0, 0, 0, 0, 0, 0, 0, -1});               // POSITION: 36 at 0
    appendValues<uint8_t>(b, {0, 1, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0});     // JOINTS_0: 12 at 36
    appendValues<float>(b, {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0}); // WEIGHTS_0: 48 at 48
    appendValues<float>(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,  1,
                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -2, 1}); // IBMs: 128 at 96
    appendValues<float>(b, {0, 1});                                            // times: 8 at 224
    const float s45 = std::sqrt(0.5f);
    appendValues<float>(b, {0, s45, 0, s45, 0, 1, 0, 0}); // 90° then 180° about +y: 32 at 232
    appendValues<float>(b, {0, 0, 0, 0, 0, 10});          // the armature's moves: 24 at 264
    const std::string moveArmature = armature ? R"(,{"sampler":1,"target":{"node":4,"path":"translation"}})" : "";
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + std::string(armature ? "[0,4]" : "[0,1,2]") +
           R"(}],
        "nodes":[{"mesh":0,"skin":0},{"translation":[0,0,5]},
                 {"translation":[10,0,0],"rotation":[0,)" +
           std::to_string(s45) + ",0," + std::to_string(s45) + R"(],"children":[3]},{"mesh":1},
                 {"name":"armature")" +
           std::string(armature ? R"(,"children":[1,2])" : "") + R"(}],
        "skins":[{"joints":[1,2],"inverseBindMatrices":3}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":2}}]},
                  {"primitives":[{"attributes":{"POSITION":0}}]}],
        "animations":[{"name":"Wave","samplers":[{"input":4,"output":5},{"input":4,"output":6}],
                       "channels":[{"sampler":0,"target":{"node":2,"path":"rotation"}})" +
           moveArmature + R"(]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]},
                     {"bufferView":1,"componentType":5121,"count":3,"type":"VEC4"},
                     {"bufferView":2,"componentType":5126,"count":3,"type":"VEC4"},
                     {"bufferView":3,"componentType":5126,"count":2,"type":"MAT4"},
                     {"bufferView":4,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},
                     {"bufferView":5,"componentType":5126,"count":2,"type":"VEC4"},
                     {"bufferView":6,"componentType":5126,"count":2,"type":"VEC3"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},
                       {"buffer":0,"byteOffset":48,"byteLength":48},{"buffer":0,"byteOffset":96,"byteLength":128},
                       {"buffer":0,"byteOffset":224,"byteLength":8},{"buffer":0,"byteOffset":232,"byteLength":32},
                       {"buffer":0,"byteOffset":264,"byteLength":24}],
        "buffers":[{"byteLength":288,"uri":"data:application/octet-stream;base64,)" +
           scene::testing::base64(b) + "\"}]}";
}

// A triangle in y = 0 with one morph target lifting every corner 2 m; animation 0 'Rise' keys its
// weight 0 at t = 0 and 1 at t = 2, with `interpolation` (CUBICSPLINE: zero tangents).
std::string risingFile(const std::string& interpolation) {
    const bool cubic = interpolation == "CUBICSPLINE";
    std::vector<unsigned char> b;
    appendValues<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1}); // POSITION: 36 at 0
    appendValues<float>(b, {0, 2, 0, 0, 2, 0, 0, 2, 0});  // the target's POSITION: 36 at 36
    appendValues<float>(b, {0, 2});                       // times: 8 at 72
    if (cubic)
        appendValues<float>(b, {0, 0, 0, 0, 1, 0}); // per key: in-tangent, value, out-tangent: 24 at 80
    else
        appendValues<float>(b, {0, 1}); // 8 at 80
    const size_t weightBytes = cubic ? 24 : 8;
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}],"weights":[0]}],
        "animations":[{"name":"Rise","samplers":[{"input":2,"output":3,"interpolation":")" +
           interpolation + R"("}],"channels":[{"sampler":0,"target":{"node":0,"path":"weights"}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]},
                     {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3","min":[0,2,0],"max":[0,2,0]},
                     {"bufferView":2,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[2]},
                     {"bufferView":3,"componentType":5126,"count":)" +
           std::to_string(cubic ? 6 : 2) + R"(,"type":"SCALAR"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36},
                       {"buffer":0,"byteOffset":72,"byteLength":8},{"buffer":0,"byteOffset":80,"byteLength":)" +
           std::to_string(weightBytes) + R"(}],
        "buffers":[{"byteLength":)" +
           std::to_string(80 + weightBytes) + R"(,"uri":"data:application/octet-stream;base64,)" +
           scene::testing::base64(b) + "\"}]}";
}

// Every vertex of the scene's batch `batch`, in the world.
std::vector<glm::dvec3> cornersOf(const Scene& s, size_t batch) {
    std::vector<glm::dvec3> out;
    const MeshBatch& b = s.batches.at(batch);
    for (const glm::mat4& placed : b.worldFromObject)
        for (const Vertex& v : s.meshes[b.mesh].vertices)
            out.push_back(s.wsOrigin + glm::dvec3(placed * glm::vec4(v.position, 1.0f)));
    return out;
}

void expectCorners(const std::vector<glm::dvec3>& got, const std::vector<glm::dvec3>& want, const std::string& what) {
    ASSERT_EQ(got.size(), want.size()) << what;
    for (size_t i = 0; i < got.size(); ++i)
        EXPECT_LT(glm::distance(got[i], want[i]), 1e-5)
            << what << ", corner " << i << ": got (" << got[i].x << ", " << got[i].y << ", " << got[i].z << "), want ("
            << want[i].x << ", " << want[i].y << ", " << want[i].z << ")";
}

// Joint B turned θ about +y: a point p of its frame stands at (10, 0, 0) + (x cos θ + z sin θ, y,
// z cos θ − x sin θ).
glm::dvec3 byJointB(const glm::dvec3& p, double degrees) {
    const double a = glm::radians(degrees);
    return glm::dvec3(10, 0, 0) +
           glm::dvec3(p.x * std::cos(a) + p.z * std::sin(a), p.y, p.z * std::cos(a) - p.x * std::sin(a));
}

// The scene as it stands at t, two ways: loaded posed at t, and loaded at 0 then played to t.
// `moved` receives what animate() says it moved or reshaped.
std::vector<Scene> bothWays(const std::string& name, const std::string& text, double t,
                            std::vector<uint32_t>* moved = nullptr) {
    std::vector<Scene> out;
    auto loaded = scene::testing::loadWritten(name, text, {.poseSeconds = t});
    EXPECT_TRUE(loaded) << loaded.error();
    auto played = scene::testing::loadWritten(name, text, {.poseSeconds = 0.0});
    EXPECT_TRUE(played) << played.error();
    if (!loaded || !played) return out;
    scene::animate(*played, t, moved);
    out.push_back(std::move(*loaded));
    out.push_back(std::move(*played));
    return out;
}

const char* const kWay[2] = {"loaded posed", "played from t = 0"};

} // namespace

// The skin and the triangle hanging from its joint stand in the pose the animation gives at the
// time asked — halfway, B turned 135° — and the animation loops over its second; played, the skin
// is reshaped and the triangle moved, and animate() says so.
TEST(GltfPosedAnimationTest, ASkinAndWhatHangsFromItsJointsStandInThePoseOfTheTimeAsked) {
    for (double t : {0.0, 0.5, 1.5, -0.5}) {
        const double turn = 90.0 + 90.0 * (t - std::floor(t));
        std::vector<uint32_t> moved;
        const std::vector<Scene> scenes = bothWays("sk_waving.gltf", wavingFile(), t, &moved);
        ASSERT_EQ(scenes.size(), 2u);
        for (int way = 0; way < 2; ++way) {
            const Scene& s = scenes[size_t(way)];
            ASSERT_EQ(s.batches.size(), 2u) << "the skin, and the triangle below joint B";
            ASSERT_EQ(s.deformations.size(), 1u) << "the skin; the triangle below the joint is moved, not deformed";
            EXPECT_EQ(s.deformations[0].batch, 0u);
            ASSERT_EQ(s.tracks.size(), 1u) << "the triangle below joint B follows it";
            EXPECT_TRUE(s.batches[0].dynamic && s.batches[1].dynamic);
            // Corner 2 is half A's (0, 0, −1) + (0, 0, 5), half B's (0, 0, −1 − 2) turned.
            const glm::dvec3 half = 0.5 * glm::dvec3(0, 0, 4) + 0.5 * byJointB({0, 0, -3}, turn);
            const std::string at = std::string(kWay[way]) + " at t = " + std::to_string(t);
            expectCorners(cornersOf(s, 0), {{1, 0, 5}, byJointB({0, 0, -2}, turn), half}, "the skin " + at);
            expectCorners(cornersOf(s, 1),
                          {byJointB({1, 0, 0}, turn), byJointB({0, 0, 0}, turn), byJointB({0, 0, -1}, turn)},
                          "the triangle below joint B " + at);
            EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
        }
        EXPECT_EQ(moved, (std::vector<uint32_t>{1, 0})) << "the triangle placed, then the skin reshaped";
    }
}

// Morph weights are posed as their keys say: LINEAR halfway between 0 and 1 lifts the triangle
// 1 m of the target's 2 at t = 1; CUBICSPLINE with zero tangents follows 3s² − 2s³ (s = t / 2).
TEST(GltfPosedAnimationTest, MorphWeightsArePosedAsTheirKeysInterpolate) {
    for (const std::string interpolation : {"LINEAR", "STEP", "CUBICSPLINE"})
        for (double t : {0.0, 0.5, 1.0, 3.0}) {
            const std::vector<Scene> scenes = bothWays("sk_rising.gltf", risingFile(interpolation), t);
            ASSERT_EQ(scenes.size(), 2u);
            const double u = std::fmod(t, 2.0) / 2.0; // the loop is the last key's 2 s
            const double weight = interpolation == "LINEAR" ? u
                                  : interpolation == "STEP" ? 0.0
                                                            : 3 * u * u - 2 * u * u * u;
            const double y = 2.0 * weight;
            for (int way = 0; way < 2; ++way) {
                EXPECT_EQ(scenes[size_t(way)].deformations.size(), 1u);
                expectCorners(cornersOf(scenes[size_t(way)], 0), {{0, y, 0}, {1, y, 0}, {0, y, -1}},
                              interpolation + " " + kWay[way] + " at t = " + std::to_string(t));
            }
        }
}

// A weights channel keyed for more targets than the mesh has cannot pose it: the scene loads at
// rest with one line saying so, and stays there when played.
TEST(GltfPosedAnimationTest, AWeightsChannelOfTheWrongLengthLeavesTheMeshAtRest) {
    std::string text = risingFile("LINEAR");
    const std::string one = R"("targets":[{"POSITION":1}]}],"weights":[0])";
    const size_t at = text.find(one);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, one.size(), R"("targets":[{"POSITION":1},{"POSITION":1}]}],"weights":[0,0])");
    const std::vector<Scene> scenes = bothWays("sk_rising_two.gltf", text, 1.0);
    ASSERT_EQ(scenes.size(), 2u);
    for (int way = 0; way < 2; ++way) {
        const Scene& s = scenes[size_t(way)];
        expectCorners(cornersOf(s, 0), {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}}, std::string("at rest, ") + kWay[way]);
        EXPECT_TRUE(s.deformations.empty());
        ASSERT_EQ(s.warnings.size(), 1u);
        EXPECT_NE(
            s.warnings[0].find("animation 0 'Rise': channel 0 (sampler 0): 2 values for 2 keys of 2 morph target(s); "
                               "left at rest"),
            std::string::npos)
            << s.warnings[0];
    }
}

// A node above the joints (an armature object) moved by the animation moves the skin too: the
// skin follows its joints, which follow the armature (a played armature that left the skin
// behind would move it twice, or not at all), and the triangle below joint B goes with it.
TEST(GltfPosedAnimationTest, AMovingNodeAboveTheJointsPosesTheSkinWithThem) {
    for (double t : {0.0, 0.5}) {
        const std::vector<Scene> scenes = bothWays("sk_waving_armature.gltf", wavingFile(true), t);
        ASSERT_EQ(scenes.size(), 2u);
        for (int way = 0; way < 2; ++way) {
            const Scene& s = scenes[size_t(way)];
            EXPECT_EQ(s.deformations.size(), 1u);
            EXPECT_EQ(s.tracks.size(), 1u) << "the triangle below joint B";
            const double turn = 90.0 + 90.0 * t;
            const glm::dvec3 moved(0, 0, 10.0 * t);
            const glm::dvec3 half = 0.5 * glm::dvec3(0, 0, 4) + 0.5 * byJointB({0, 0, -3}, turn);
            const std::string at = std::string(kWay[way]) + " at t = " + std::to_string(t);
            expectCorners(cornersOf(s, 0),
                          {moved + glm::dvec3(1, 0, 5), moved + byJointB({0, 0, -2}, turn), moved + half},
                          "the skin " + at);
            expectCorners(cornersOf(s, 1),
                          {moved + byJointB({1, 0, 0}, turn), moved + byJointB({0, 0, 0}, turn),
                           moved + byJointB({0, 0, -1}, turn)},
                          "the triangle below joint B " + at);
            EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
        }
    }
}

// Exported to .glb and read back, a skinned or morphed mesh plays as it did: its bind vertices,
// targets, joints (with their chains of keyed nodes) and weights' keys are written, not the
// pose of the moment. Loaded turned z-up too (the mesh's move from posed coordinates), and
// compared at times across the loop; what hangs from a joint comes back playing with it.
TEST(GltfPosedAnimationTest, ExportedAndLoadedBackADeformedMeshPlaysTheSame) {
    const auto everyCorner = [](const Scene& s) {
        std::vector<glm::dvec3> all;
        for (size_t b = 0; b < s.batches.size(); ++b)
            for (const glm::dvec3& p : cornersOf(s, b)) all.push_back(p);
        std::sort(all.begin(), all.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
            return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
        });
        return all;
    };
    struct Case {
        const char* name;
        std::string text;
        UpAxis up;
    };
    for (const Case& c : {Case{"sk_waving_x.gltf", wavingFile(), UpAxis::Y},
                          Case{"sk_waving_armature_x.gltf", wavingFile(true), UpAxis::Z},
                          Case{"sk_rising_x.gltf", risingFile("CUBICSPLINE"), UpAxis::Y},
                          Case{"sk_rising_step_x.gltf", risingFile("STEP"), UpAxis::Z}}) {
        SCOPED_TRACE(c.name);
        auto original = scene::testing::loadWritten(c.name, c.text, {.up = c.up});
        ASSERT_TRUE(original) << original.error();
        const auto file = shadowkit::test_support::scratchDir() / (std::string(c.name) + ".glb");
        ASSERT_TRUE(exportScene(*original, file));
        auto back = loadScene(file);
        ASSERT_TRUE(back) << back.error();
        EXPECT_EQ(back->deformations.size(), original->deformations.size());
        EXPECT_EQ(back->tracks.size(), original->tracks.size());
        EXPECT_TRUE(back->warnings.empty()) << back->warnings.front();
        for (double t : {0.0, 0.3, 0.5, 1.7}) {
            animate(*original, t);
            animate(*back, t);
            const std::vector<glm::dvec3> want = everyCorner(*original), got = everyCorner(*back);
            ASSERT_EQ(got.size(), want.size());
            for (size_t k = 0; k < got.size(); ++k)
                EXPECT_LT(glm::distance(got[k], want[k]), 1e-3) << "t = " << t << ", corner " << k;
        }
    }
}
