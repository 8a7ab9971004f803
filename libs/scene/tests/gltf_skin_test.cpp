// Skinned meshes and morph targets as glTF files bring them (gltf_pose.cpp): placed by their
// joints at the rest pose, far out without losing millimetres, mirrored with their faces kept
// outward, refused in one line where they cannot be posed; morph targets at their weights.
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace shadowkit;
using scene::testing::append;
using scene::testing::base64;
using scene::testing::expectEveryTriangleFacesOutward;
using scene::testing::loadWritten;

namespace {

// A skinned triangle: its node scaled 100 times (ignored: joints alone place a skinned mesh),
// joint A at (0, 0, 5), joint B at (10, 0, 0) turned 90° about y with an inverse bind matrix
// moving 2 along -z; corner 0 bound to A, corner 1 to B (`joint`), corner 2 half to each. `ibmCount`
// and `joint` break it on purpose; `weights` false drops WEIGHTS_0; `at` moves both joints.
core::Result<scene::Scene> loadSkinned(const std::string& name, int ibmCount = 2, uint8_t joint = 1,
                                       bool weights = true, const glm::dvec3& at = glm::dvec3(0.0)) {
    std::vector<unsigned char> b;
    append<float>(b, {1, 0, 0, 0, 0, 0, 0, 0, -1});                      // POSITION: 36 at 0
    append<uint8_t>(b, {0, 1, 0, 0, 0, joint, 0, 0, 0, 1, 0, 0});        // JOINTS_0: 12 at 36
    append<float>(b, {1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0.5f, 0, 0});        // WEIGHTS_0: 48 at 48
    append<float>(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,  1,   // IBM A: identity
                      1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -2, 1}); // IBM B: 128 at 96
    const float s45 = std::sqrt(0.5f);
    return loadWritten(name, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],
        "nodes":[{"mesh":0,"skin":0,"scale":[100,100,100]},{"translation":[)" +
                                 std::to_string(at.x) + "," + std::to_string(at.y) + "," + std::to_string(at.z + 5) +
                                 R"(]},
                 {"translation":[)" +
                                 std::to_string(at.x + 10) + "," + std::to_string(at.y) + "," + std::to_string(at.z) +
                                 R"(],"rotation":[0,)" + std::to_string(s45) + ",0," + std::to_string(s45) + R"(]}],
        "skins":[{"joints":[1,2],"inverseBindMatrices":3}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1)" +
                                 (weights ? R"(,"WEIGHTS_0":2)" : "") + R"(}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                     {"bufferView":1,"componentType":5121,"count":3,"type":"VEC4"},
                     {"bufferView":2,"componentType":5126,"count":3,"type":"VEC4"},
                     {"bufferView":3,"componentType":5126,"count":)" +
                                 std::to_string(ibmCount) + R"(,"type":"MAT4"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},
                       {"buffer":0,"byteOffset":48,"byteLength":48},{"buffer":0,"byteOffset":96,"byteLength":128}],
        "buffers":[{"byteLength":224,"uri":"data:application/octet-stream;base64,)" +
                                 base64(b) + "\"}]}");
}

} // namespace

TEST(GltfReadTest, ASkinnedMeshIsPlacedByItsJointsAtTheRestPose) {
    const auto s = loadSkinned("sk_skinned.gltf");
    ASSERT_TRUE(s) << s.error();
    ASSERT_EQ(s->batches.size(), 1u);
    ASSERT_EQ(s->batches[0].worldFromObject.size(), 1u);
    const scene::Mesh& mesh = s->meshes[s->batches[0].mesh];
    const glm::mat4& placed = s->batches[0].worldFromObject[0];
    // Worked by hand: (1, 0, 0) by A alone, (1, 0, 5); (0, 0, 0) by B alone: -2 along z, turned
    // to (-2, 0, 0), moved to (8, 0, 0); (0, 0, -1) half by each: (0, 0, 4) and (7, 0, 0), so
    // (3.5, 0, 2). With the node's scale of 100 they would be metres away.
    const glm::vec3 expected[3] = {{1, 0, 5}, {8, 0, 0}, {3.5f, 0, 2}};
    ASSERT_EQ(mesh.vertices.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        const glm::vec3 world = glm::vec3(placed * glm::vec4(mesh.vertices[i].position, 1.0f));
        EXPECT_LT(glm::distance(world, expected[i]), 1e-5f) << i << ": " << world.x << "," << world.y << "," << world.z;
    }
}

// Posed far out (joints in survey metres), the skin keeps its millimetres: posed in double and
// kept relative to its anchor, where before it was posed into float world coordinates (a 0.5 m
// step at 5.4e6 m).
TEST(GltfReadTest, ASkinPosedFarOutKeepsItsMillimetres) {
    const glm::dvec3 at(512345.678, 20.25, 5412345.321);
    const auto s = loadSkinned("sk_skinned_far.gltf", 2, 1, true, at);
    ASSERT_TRUE(s) << s.error();
    ASSERT_EQ(s->batches.size(), 1u);
    ASSERT_EQ(s->batches[0].worldFromObject.size(), 1u);
    const scene::Mesh& mesh = s->meshes[s->batches[0].mesh];
    const glm::dmat4 placed(s->batches[0].worldFromObject[0]);
    const glm::dvec3 expected[3] = {{1, 0, 5}, {8, 0, 0}, {3.5, 0, 2}}; // as above, then moved by `at`
    ASSERT_EQ(mesh.vertices.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        const glm::dvec3 world =
            s->wsOrigin + glm::dvec3(placed * glm::dvec4(glm::dvec3(mesh.vertices[i].position), 1.0));
        EXPECT_LT(glm::distance(world, at + expected[i]), 1e-5) << i;
    }
}

TEST(GltfReadTest, MirroringSkinsKeepTheirFacesOutward) {
    // As MirroredNodesKeepTheirFacesOutward, for a skinned triangle: its one joint mirrored in x,
    // or mirrored twice (no mirror), every corner bound to it alone. The pose turns the winding
    // where it mirrors while the normals (the inverse transpose) keep pointing out: in the world
    // every triangle must wind counter-clockwise about its own normal.
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1});           // POSITION: 36 at 0
    append<uint8_t>(b, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}); // JOINTS_0: 12 at 36
    append<float>(b, {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});   // WEIGHTS_0: 48 at 48
    const auto s = loadWritten("sk_mirrored_skin.gltf", R"({"asset":{"version":"2.0"},"scene":0,
        "scenes":[{"nodes":[0,1,2,3]}],
        "nodes":[{"mesh":0,"skin":0},{"mesh":0,"skin":1},{"scale":[-1,1,1],"translation":[5,0,0]},
                 {"scale":[-1,-1,1],"translation":[9,0,0]}],
        "skins":[{"joints":[2]},{"joints":[3]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":2}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                     {"bufferView":1,"componentType":5121,"count":3,"type":"VEC4"},
                     {"bufferView":2,"componentType":5126,"count":3,"type":"VEC4"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12},
                       {"buffer":0,"byteOffset":48,"byteLength":48}],
        "buffers":[{"byteLength":96,"uri":"data:application/octet-stream;base64,)" +
                                                            base64(b) + "\"}]}");
    ASSERT_TRUE(s) << s.error();
    EXPECT_EQ(expectEveryTriangleFacesOutward(*s), 2u) << "one triangle per skinned node";
}

TEST(GltfReadTest, ASkinThatCannotBePosedIsRefusedInOneLine) {
    for (const auto& [what, s, expected] :
         {std::tuple{"one inverse bind matrix for two joints", loadSkinned("sk_skin.gltf", 1),
                     "sk_skin.gltf: skin 0: its inverseBindMatrices must be a MAT4 accessor of one per joint (2)"},
          std::tuple{"a joint the skin does not have", loadSkinned("sk_skin.gltf", 2, 5),
                     "sk_skin.gltf: mesh 0 primitive 0: vertex 1 names joint 5 of a skin of 2"},
          std::tuple{"joints without weights", loadSkinned("sk_skin.gltf", 2, 1, false),
                     "JOINTS_0 and WEIGHTS_0 come in pairs"}}) {
        SCOPED_TRACE(what);
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().find(expected), std::string::npos) << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    }
}

TEST(GltfReadTest, MorphTargetsTakeTheirDefaultWeightsOrTheirNodesOwn) {
    // A triangle whose one target lifts its third corner 2 m; the mesh's default weight is 0.5,
    // and a second node, 5 m along x, sets its own weight of 1.
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1}); // POSITION: 36 at 0
    append<float>(b, {0, 0, 0, 0, 0, 0, 0, 2, 0});  // the target's POSITION: 36 at 36
    const auto s = loadWritten("sk_morph.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
        "nodes":[{"mesh":0},{"mesh":0,"translation":[5,0,0],"weights":[1]}],
        "meshes":[{"weights":[0.5],"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                     {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36}],
        "buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
                                                    base64(b) + "\"}]}");
    ASSERT_TRUE(s) << s.error();
    ASSERT_EQ(s->batches.size(), 2u) << "the node with weights of its own has its own shape";
    std::vector<float> lifted; // the third corner's height, per instance
    for (const scene::MeshBatch& batch : s->batches)
        for (const glm::mat4& m : batch.worldFromObject) {
            const scene::Mesh& mesh = s->meshes[batch.mesh];
            lifted.push_back((m * glm::vec4(mesh.vertices[2].position, 1.0f)).y);
            // The face's normal follows the moved corner: no longer straight up.
            EXPECT_LT(mesh.vertices[0].normal.y, 0.9f);
        }
    std::sort(lifted.begin(), lifted.end());
    ASSERT_EQ(lifted.size(), 2u);
    EXPECT_FLOAT_EQ(lifted[0], 1.0f); // 0.5 × 2 m
    EXPECT_FLOAT_EQ(lifted[1], 2.0f); // 1 × 2 m
}
