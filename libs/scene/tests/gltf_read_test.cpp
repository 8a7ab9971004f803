// glTF files as real exporters write them: strips and fans, quantized and normalized integer
// attributes, sparse accessors; and what cannot be read, named in one line.
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <tuple>
#include <vector>

using namespace shadowkit;

namespace {

using scene::testing::append;
using scene::testing::base64;
using scene::testing::expectEveryTriangleFacesOutward;
using scene::testing::loadWritten;

// A .gltf with one mesh node; `rest` holds "meshes", "accessors" and "bufferViews" (JSON text
// after the opening brace), the buffer is embedded.
core::Result<scene::Scene> loadGltfText(const std::string& name, const std::string& rest,
                                        const std::vector<unsigned char>& buffer,
                                        const std::string& asset = R"({"version":"2.0"})") {
    return loadWritten(name, R"({"asset":)" + asset + R"(,"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)" +
                                 rest + R"(,"buffers":[{"byteLength":)" + std::to_string(buffer.size()) +
                                 R"(,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + "\"}]}");
}

// Signed area of a triangle seen from +y, for winding checks.
float windingFromAbove(const scene::Mesh& mesh, size_t triangle) {
    const glm::vec3 a = mesh.vertices[mesh.indices[3 * triangle]].position,
                    b = mesh.vertices[mesh.indices[3 * triangle + 1]].position,
                    c = mesh.vertices[mesh.indices[3 * triangle + 2]].position;
    return glm::cross(b - a, c - a).y;
}

std::vector<unsigned char>
flatFan(int points) { // a disc in the xz plane: centre then the rim, counter-clockwise from above
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0});
    for (int i = 0; i < points - 1; ++i) append<float>(b, {std::cos(-0.5f * float(i)), 0, std::sin(-0.5f * float(i))});
    return b;
}

} // namespace

TEST(GltfReadTest, StripsAndFansBecomeTriangleListsWithOneWinding) {
    // Strip over a quad row: 6 vertices zig-zagging along x make 4 triangles.
    std::vector<unsigned char> strip;
    append<float>(strip, {0, 0, 0, 0, 0, -1, 1, 0, 0, 1, 0, -1, 2, 0, 0, 2, 0, -1});
    const std::string views = R"("bufferViews":[{"buffer":0,"byteLength":72}])";
    auto s = loadGltfText("sk_strip.gltf",
                          R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":5}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3","min":[0,0,-1],"max":[2,0,0]}],)" +
                              views,
                          strip);
    ASSERT_TRUE(s) << s.error();
    const scene::Mesh& stripMesh = s->meshes.at(0);
    ASSERT_EQ(stripMesh.indices.size(), 12u);
    // glTF's rule swaps every second triangle's order: unrolled, all four face the same way.
    const float first = windingFromAbove(stripMesh, 0);
    ASSERT_NE(first, 0.0f);
    for (size_t t = 1; t < 4; ++t) EXPECT_GT(windingFromAbove(stripMesh, t) * first, 0.0f) << "strip triangle " << t;

    auto f = loadGltfText("sk_fan.gltf", R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":6}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[-1,0,-1],"max":[1,0,1]}],
        "bufferViews":[{"buffer":0,"byteLength":60}])",
                          flatFan(5));
    ASSERT_TRUE(f) << f.error();
    ASSERT_EQ(f->meshes.at(0).indices.size(), 9u); // 5 fan vertices: 3 triangles
    for (size_t t = 0; t < 3; ++t) EXPECT_GT(windingFromAbove(f->meshes[0], t), 0.0f) << "fan triangle " << t;
}

TEST(GltfReadTest, QuantizedPositionsAndNormalizedSignedNormalsAreRead) {
    // KHR_mesh_quantization: positions as SHORT (not normalized), normals as normalized BYTE.
    std::vector<unsigned char> b;
    append<int16_t>(b, {0, 0, 0, 0, 0, 100, 0, 0, 0, 0, -200, 0});  // VEC3 padded to 8 bytes: stride 8
    append<int8_t>(b, {0, 127, 0, 0, 0, 0, -128, 0, 127, 0, 0, 0}); // VEC3 padded to 4 bytes: stride 4
    auto s = loadGltfText("sk_quantized.gltf",
                          R"("extensionsUsed":["KHR_mesh_quantization"],"extensionsRequired":["KHR_mesh_quantization"],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],
        "accessors":[{"bufferView":0,"componentType":5122,"count":3,"type":"VEC3","min":[0,0,-200],"max":[0,100,0]},
                     {"bufferView":1,"componentType":5120,"normalized":true,"count":3,"type":"VEC3"}],
        "bufferViews":[{"buffer":0,"byteLength":24,"byteStride":8},{"buffer":0,"byteOffset":24,"byteLength":12,"byteStride":4}])",
                          b);
    ASSERT_TRUE(s) << s.error();
    const auto& v = s->meshes.at(0).vertices;
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[1].position, glm::vec3(0, 100, 0));
    EXPECT_EQ(v[2].position, glm::vec3(0, 0, -200));
    EXPECT_NEAR(v[0].normal.y, 1.0f, 1e-6f);  // 127 -> 1 (was read as 0 before)
    EXPECT_NEAR(v[1].normal.z, -1.0f, 1e-6f); // -128 -> max(-128 / 127, -1) = -1
    EXPECT_NEAR(v[2].normal.x, 1.0f, 1e-6f);
}

TEST(GltfReadTest, SparseAccessorsSubstituteTheirValues) {
    // A triangle whose second vertex is moved by a sparse accessor, and a triangle built of
    // sparse values over zeros (no buffer view).
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1}); // base positions (36 bytes)
    append<uint16_t>(b, {1, 0});                    // sparse index 1, padded (4 bytes)
    append<float>(b, {5, 0, 0});                    // its value (12 bytes)
    append<uint16_t>(b, {1, 2});                    // second accessor: indices 1 and 2 (4 bytes)
    append<float>(b, {3, 0, 0, 0, 0, -3});          // their values (24 bytes)
    auto s = loadGltfText(
        "sk_sparse.gltf",
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]},{"primitives":[{"attributes":{"POSITION":1}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[5,0,0],
                      "sparse":{"count":1,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}}},
                     {"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-3],"max":[3,0,0],
                      "sparse":{"count":2,"indices":{"bufferView":3,"componentType":5123},"values":{"bufferView":4}}}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":2},{"buffer":0,"byteOffset":40,"byteLength":12},
                       {"buffer":0,"byteOffset":52,"byteLength":4},{"buffer":0,"byteOffset":56,"byteLength":24}])",
        b);
    ASSERT_TRUE(s) << s.error();
    EXPECT_EQ(s->meshes.at(0).vertices.at(1).position, glm::vec3(5, 0, 0));
    EXPECT_EQ(s->meshes.at(0).vertices.at(2).position, glm::vec3(0, 0, -1));
    // The second mesh is not in the scene's node tree; the first mesh is what was asked for.
    EXPECT_EQ(s->meshes.size(), 1u);
}

TEST(GltfReadTest, WhatCannotBeReadIsNamedInOneLine) {
    std::vector<unsigned char> triangle;
    append<float>(triangle, {0, 0, 0, 1, 0, 0, 0, 0, -1});
    const std::string views = R"("bufferViews":[{"buffer":0,"byteLength":36}])";
    const std::string accessor = R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)";
    auto expectError = [](const core::Result<scene::Scene>& s, const std::string& part) {
        ASSERT_FALSE(s) << "accepted; expected: " << part;
        EXPECT_NE(s.error().find(part), std::string::npos) << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    };
    expectError(loadGltfText("sk_v1.gltf",
                             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)" + accessor + views,
                             triangle, R"({"version":"1.0"})"),
                "glTF 1.0 is not supported; glTF 2.0 is");
    expectError(loadGltfText("sk_draco.gltf",
                             R"("meshes":[{"name":"packed","primitives":[{"attributes":{"POSITION":0},
                                "extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":0}}}}]}],)" +
                                 accessor + views,
                             triangle),
                "mesh 0 'packed' primitive 0 is Draco-compressed");
    std::vector<unsigned char> infinite = triangle;
    append<uint32_t>(infinite, {0x7f800000u, 0, 0}); // a fourth vertex at +inf
    expectError(loadGltfText("sk_inf.gltf",
                             R"("meshes":[{"name":"broken","primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}],"bufferViews":[{"buffer":0,"byteLength":48}])",
                             infinite),
                "sk_inf.gltf: mesh 0 'broken' primitive 0: position 3 is not finite");
    expectError(loadGltfText("sk_short.gltf",
                             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":300,"type":"VEC3"}],)" +
                                 views,
                             triangle),
                "reaches past its buffer");
    expectError(loadGltfText("sk_badindex.gltf",
                             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}])",
                             [&] {
                                 auto b = triangle;
                                 append<uint32_t>(b, {0, 1, 7});
                                 return b;
                             }()),
                "index 2 names no vertex");
    // tinygltf refuses a skin without its required `joints` and gives no reason (the glTF
    // Validator's test file skin/empty_object.gltf): the line still says what kind of fault.
    expectError(loadWritten("sk_jointless.gltf", R"({"asset":{"version":"2.0"},"skins":[{}]})"),
                "sk_jointless.gltf: not a readable glTF file (an object lacks a property glTF requires");
}

// A .gltf of one triangle mesh placed by the given nodes (a JSON array's insides), after the
// given members (a scene, skins; "" for a file with no scene at all).
core::Result<scene::Scene> loadMeshNodes(const std::string& name, const std::string& members,
                                         const std::string& nodes) {
    std::vector<unsigned char> triangle;
    append<float>(triangle, {0, 0, 0, 1, 0, 0, 0, 0, -1});
    return loadWritten(name, R"({"asset":{"version":"2.0"},)" + members + R"("nodes":[)" + nodes +
                                 R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                                 R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
                                 R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,)"
                                 R"("uri":"data:application/octet-stream;base64,)" +
                                 base64(triangle) + "\"}]}");
}

// The same, placed by scene 0 with the given roots.
core::Result<scene::Scene> loadNodes(const std::string& name, const std::string& roots, const std::string& nodes) {
    return loadMeshNodes(name, R"("scene":0,"scenes":[{"nodes":[)" + roots + "]}],", nodes);
}

// A chain of `links` nodes, each the parent of the next and one metre along x from it; the last
// places the mesh.
std::string chainOfNodes(int links) {
    std::string nodes;
    for (int i = 0; i + 1 < links; ++i)
        nodes += R"({"translation":[1,0,0],"children":[)" + std::to_string(i + 1) + "]},";
    return nodes + R"({"translation":[1,0,0],"mesh":0})";
}

// A node's matrix must decompose into translation, rotation and scale (glTF 2.0, §5.25): its last
// row (0, 0, 0, 1). A row of zeros divided every point the node placed by zero — a lone node of
// it was refused as "reaching inf m", and beside another node it loaded, its triangle a point,
// without a word. Exporters' rounding noise in that row is read as what it means.
TEST(GltfReadTest, ANodeMatrixThatIsNotTranslationRotationAndScaleIsRefusedNamingTheNode) {
    const std::string other = R"({"mesh":0},)";
    for (const auto& [matrix, row] :
         {std::pair<std::string, std::string>{"0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,0", "(0, 0, 0, 0)"},
          {"1,0,0,0.5, 0,1,0,0, 0,0,1,0, 0,0,0,1", "(0.5, 0, 0, 1)"},
          {"1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,2", "(0, 0, 0, 2)"}}) {
        const auto s =
            loadNodes("sk_projective.gltf", "0,1", other + R"({"name":"lamp","mesh":0,"matrix":[)" + matrix + "]}");
        ASSERT_FALSE(s) << matrix;
        EXPECT_NE(s.error().find("node 1 'lamp': its matrix's last row is " + row + ", not (0, 0, 0, 1)"),
                  std::string::npos)
            << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    }
    // Noise of a float's rounding in the last row, and a matrix moving the mesh 2 m up: loaded,
    // placed where the matrix says.
    const auto noisy =
        loadNodes("sk_noisy.gltf", "0", R"({"mesh":0,"matrix":[1,0,0,1e-9, 0,1,0,0, 0,0,1,-1e-9, 0,2,0,1.0000001]})");
    ASSERT_TRUE(noisy) << noisy.error();
    EXPECT_NEAR(noisy->wsBounds().min.y, 2.0, 1e-6);
}

// A rotation must be a unit quaternion (glTF 2.0, §5.25); one that is not is placed by the
// formula as it stands (in general a scale and shear) and named in one warning, its length the
// one farthest from 1. Float rounding in an exporter's quaternion is not named.
TEST(GltfReadTest, ARotationThatIsNotAUnitQuaternionIsNamedInOneWarning) {
    auto rotationWarnings = [](const core::Result<scene::Scene>& s) {
        std::vector<std::string> found;
        for (const std::string& w : s->warnings)
            if (w.find("unit quaternion") != std::string::npos) found.push_back(w);
        return found;
    };
    const auto off = loadNodes("sk_quaternion.gltf", "0,1,2",
                               R"({"mesh":0,"rotation":[0,1,0,1]},{"name":"half","mesh":0,"rotation":[0,0,0,0.5]},)"
                               R"({"mesh":0,"rotation":[0,0.7071068,0,0.7071068]})");
    ASSERT_TRUE(off) << off.error();
    const std::vector<std::string> named = rotationWarnings(off);
    ASSERT_EQ(named.size(), 1u);
    EXPECT_NE(named[0].find("node 0 and 1 more: a rotation that is not a unit quaternion (length 0.5;"),
              std::string::npos)
        << named[0];
    const auto rounded = loadNodes("sk_quaternion_rounded.gltf", "0", R"({"mesh":0,"rotation":[0,0.7071,0,0.7071]})");
    ASSERT_TRUE(rounded) << rounded.error();
    EXPECT_TRUE(rotationWarnings(rounded).empty());
}

TEST(GltfReadTest, NodeHierarchiesThatAreNotTreesAreRefusedInOneLine) {
    // glTF's nodes form disjoint trees. Each file below breaks that in a way that, unchecked,
    // places a node exponentially often; each was a hang before.
    auto expectError = [](const core::Result<scene::Scene>& s, const std::string& part) {
        ASSERT_FALSE(s) << "accepted; expected: " << part;
        EXPECT_NE(s.error().find(part), std::string::npos) << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    };
    // Each node naming the next twice: 2^40 placements of the mesh.
    std::string doubled;
    for (int i = 0; i < 40; ++i)
        doubled += "{\"children\":[" + std::to_string(i + 1) + "," + std::to_string(i + 1) + "]},";
    expectError(loadNodes("sk_doubled.gltf", "0", doubled + R"({"mesh":0})"),
                "node 1 is a child of node 0 and again of node 0");
    // Found by fuzz_gltf (a 12 s timeout under the sanitizers): a root that is its own child
    // beside a second child, doubling at each of 64 levels.
    expectError(loadNodes("sk_cycle.gltf", "0", R"({"name":"site","children":[0,1]},{"mesh":0})"),
                "node 0 'site' is its own ancestor (a cycle");
    // Two parents of one node.
    expectError(loadNodes("sk_parents.gltf", "0,1", R"({"children":[2]},{"children":[2]},{"mesh":0})"),
                "node 2 is a child of node 0 and again of node 1");
    expectError(loadNodes("sk_child.gltf", "0", R"({"children":[7]})"), "node 0 lists child 7, which is not a node");
    expectError(loadNodes("sk_deep.gltf", "0", chainOfNodes(600)), "deeper than 512 levels");
    // A loop of nodes that no scene lists, one of them a skin's joint: walking up from it never
    // ended (found by fuzz_gltf: a file whose `scenes` were mangled away, node 0 its own child).
    expectError(loadMeshNodes("sk_loop.gltf", R"("skins":[{"joints":[0]}],)",
                              R"({"children":[2]},{"mesh":0},{"children":[0]})"),
                "node 0 is its own ancestor (a cycle");
    expectError(loadMeshNodes("sk_self.gltf", "", R"({"children":[0]},{"mesh":0})"),
                "node 0 is its own ancestor (a cycle");
    // An animation library: a clip for another file's skeleton, no mesh (PlayCanvas's
    // jump-flip.glb). Said as such, not as a file of points or lines.
    {
        std::vector<unsigned char> keys;
        append<float>(keys, {0.0f, 1.0f, 0, 0, 0, 0, 2, 0});
        expectError(
            loadWritten(
                "sk_clip.gltf",
                R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"name":"hips"}],)"
                R"("animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
                R"("samplers":[{"input":0,"output":1}]}],)"
                R"("accessors":[{"bufferView":0,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},)"
                R"({"bufferView":0,"byteOffset":8,"componentType":5126,"count":2,"type":"VEC3"}],)"
                R"("bufferViews":[{"buffer":0,"byteLength":32}],"buffers":[{"byteLength":32,)"
                R"("uri":"data:application/octet-stream;base64,)" +
                    base64(keys) + "\"}]}"),
            "sk_clip.gltf: it holds no mesh, only an animation (clips for another file's model");
    }
    // A scene whose nodes name no mesh: the file's mesh is there, the scene leaves it out.
    expectError(loadNodes("sk_unplaced.gltf", "0", R"({"name":"empty"},{"mesh":0})"),
                "sk_unplaced.gltf: its mesh is placed by no node of its scene");
}

TEST(GltfReadTest, ASingleSidedMeshWoundAgainstItsNormalsIsNamedInAWarning) {
    // One triangle, counter-clockwise seen from +y, with its corners' normals given: up agrees
    // with its winding, down does not (a Blender test file's cube, every triangle).
    const auto load = [](const std::string& name, float normalY, const std::string& material) {
        std::vector<unsigned char> b;
        append<float>(b, {0, 0, 0, 0, 0, 1, 1, 0, 0}); // (0,0,0), (0,0,1), (1,0,0): up by its winding
        append<float>(b, {0, normalY, 0, 0, normalY, 0, 0, normalY, 0});
        return loadGltfText(name,
                            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"material":0}]}],)"
                            R"("materials":[)" +
                                material +
                                R"(],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                                R"({"bufferView":0,"byteOffset":36,"componentType":5126,"count":3,"type":"VEC3"}],)"
                                R"("bufferViews":[{"buffer":0,"byteLength":72}])",
                            b);
    };
    const auto outward = load("sk_outward.gltf", 1.0f, "{}");
    ASSERT_TRUE(outward) << outward.error();
    ASSERT_GT(windingFromAbove(outward->meshes.at(0), 0), 0.0f);
    EXPECT_TRUE(outward->warnings.empty());
    const auto inside = load("sk_inside_out.gltf", -1.0f, "{}");
    ASSERT_TRUE(inside) << inside.error();
    ASSERT_EQ(inside->warnings.size(), 1u);
    EXPECT_NE(inside->warnings[0].find("sk_inside_out.gltf: mesh 0 primitive 0: 100 % of its triangles wind clockwise "
                                       "about the normals it gives them"),
              std::string::npos)
        << inside->warnings[0];
    // Double-sided, its winding decides nothing: no word.
    const auto both = load("sk_both_sides.gltf", -1.0f, R"({"doubleSided":true})");
    ASSERT_TRUE(both) << both.error();
    EXPECT_TRUE(both->warnings.empty());
}

TEST(GltfReadTest, ASceneRootThatIsAChildIsPlacedOnceWhereViewersPlaceIt) {
    // glTF's scene roots have no parent, and exporters break it (Kenney's kits: the mesh node
    // listed, its `tmpParent` not). Node 0 sets node 1's mesh 10 m along x; node 1 sets it 5 m
    // along z; node 2 places the mesh where it is, as a reference.
    const std::string nodes = R"({"name":"tmpParent","translation":[10,0,0],"children":[1]},)"
                              R"({"name":"craft","translation":[0,0,5],"mesh":0},{"mesh":0})";
    const auto apart = [](const scene::Scene& s) {
        const auto& placed = s.batches.at(0).worldFromObject;
        return glm::vec3(placed.at(0)[3]) - glm::vec3(placed.at(1)[3]);
    };
    const auto expectWarning = [](const scene::Scene& s, const std::string& part) {
        ASSERT_EQ(s.warnings.size(), 1u);
        EXPECT_NE(s.warnings[0].find(part), std::string::npos) << s.warnings[0];
    };
    // Listed alone, it stands as a root with its own transform, as viewers draw it (refused as
    // "a cycle" before).
    const auto alone = loadNodes("sk_kit.gltf", "1,2", nodes);
    ASSERT_TRUE(alone) << alone.error();
    ASSERT_EQ(alone->instanceCount(), 2u);
    EXPECT_NEAR(glm::length(apart(*alone) - glm::vec3(0, 0, 5)), 0.0f, 1e-5f);
    expectWarning(*alone,
                  "sk_kit.gltf: scene 0 lists node 1 'craft' as a root though it is a child of node 0 "
                  "'tmpParent'; a scene's roots have no parent in glTF: drawn as a root with its own transform");
    // Listed with its parent, it is placed once, below it.
    const auto withParent = loadNodes("sk_kit_parent.gltf", "0,1,2", nodes);
    ASSERT_TRUE(withParent) << withParent.error();
    ASSERT_EQ(withParent->instanceCount(), 2u);
    EXPECT_NEAR(glm::length(apart(*withParent) - glm::vec3(10, 0, 5)), 0.0f, 1e-5f);
    expectWarning(*withParent, "scene 0 lists node 1 'craft' as a root below another node it lists: placed once");
    // Listed twice, once.
    const auto twice = loadNodes("sk_twice.gltf", "0,2,0", nodes);
    ASSERT_TRUE(twice) << twice.error();
    ASSERT_EQ(twice->instanceCount(), 2u);
    EXPECT_NEAR(glm::length(apart(*twice) - glm::vec3(10, 0, 5)), 0.0f, 1e-5f);
    expectWarning(*twice, "scene 0 lists 1 node more than once: placed once");
    // A chain of 400 nodes, each listed: one placement each, not 400 × 401 / 2.
    std::string all;
    for (int i = 0; i < 400; ++i) all += std::to_string(i) + ',';
    all.pop_back();
    const auto chain = loadNodes("sk_listed_chain.gltf", all, chainOfNodes(400));
    ASSERT_TRUE(chain) << chain.error();
    EXPECT_EQ(chain->instanceCount(), 1u);
    expectWarning(*chain, "scene 0 lists node 1 and 398 more as roots below another node it lists");
}

TEST(GltfReadTest, NodesHiddenByKhrNodeVisibilityPlaceNoMeshAndNoLightButKeepTheirCameras) {
    // KHR_node_visibility: node 1 hides itself and all below it — node 2 asking to be seen, a
    // light and a camera. Nodes 0 and 4 place the mesh at x = 0 and 30; node 5 is a light in view.
    const std::string members =
        R"("scene":0,"scenes":[{"nodes":[0,1,4,5]}],"extensionsUsed":["KHR_node_visibility","KHR_lights_punctual"],)"
        R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"directional"}]}},)"
        R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],)";
    const std::string nodes =
        R"({"mesh":0},)"
        R"({"translation":[10,0,0],"mesh":0,"children":[2,3],"extensions":{"KHR_node_visibility":{"visible":false}}},)"
        R"({"translation":[10,0,0],"mesh":0,"extensions":{"KHR_node_visibility":{"visible":true}}},)"
        R"({"camera":0,"extensions":{"KHR_lights_punctual":{"light":0}}},)"
        R"({"translation":[30,0,0],"mesh":0,"extensions":{"KHR_node_visibility":{"visible":true}}},)"
        R"({"extensions":{"KHR_lights_punctual":{"light":0}}})";
    const auto loaded = loadMeshNodes("sk_hidden_nodes.gltf", members, nodes);
    ASSERT_TRUE(loaded) << loaded.error();
    std::vector<float> xs;
    for (const scene::MeshBatch& batch : loaded->batches)
        for (const glm::mat4& m : batch.worldFromObject) xs.push_back(m[3].x);
    std::sort(xs.begin(), xs.end());
    EXPECT_EQ(xs, (std::vector<float>{0.0f, 30.0f})) << "the hidden node and its child place nothing";
    EXPECT_EQ(loaded->lights.size(), 1u) << "the hidden node's light is off, the one in view on";
    EXPECT_EQ(loaded->cameras.size(), 1u) << "visibility does not hide cameras";
    const auto said = std::count_if(loaded->warnings.begin(), loaded->warnings.end(), [](const std::string& w) {
        return w.find("sk_hidden_nodes.gltf: 1 node is hidden (KHR_node_visibility), with everything below: 2 meshes "
                      "left out, neither drawn nor casting") != std::string::npos;
    });
    EXPECT_EQ(said, 1);
    // Every mesh hidden: nothing to cast or receive a shadow, said so.
    const auto none = loadMeshNodes("sk_all_hidden.gltf", R"("scene":0,"scenes":[{"nodes":[1]}],)", nodes);
    ASSERT_FALSE(none);
    EXPECT_NE(none.error().find("sk_all_hidden.gltf: every mesh it places is hidden (KHR_node_visibility)"),
              std::string::npos)
        << none.error();
}

TEST(GltfReadTest, AHiddenMeshsTextureIsNotDecodedSoItCannotRefuseTheFile) {
    // Mesh 1 is masked by a texture that is no image (refused on a MASK material where drawn);
    // the only node placing it is hidden, so the file loads with mesh 0 alone.
    std::vector<unsigned char> triangle;
    append<float>(triangle, {0, 0, 0, 1, 0, 0, 0, 0, -1, /* uvs */ 0, 0, 1, 0, 0, 1});
    const auto file = [&](const std::string& visibility) {
        return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],)"
               R"("nodes":[{"mesh":0},{"mesh":1,"translation":[5,0,0])" +
               visibility +
               R"(}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]},)"
               R"({"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
               R"("materials":[{"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
               R"("textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,bm90IGFuIGltYWdl"}],)"
               R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
               R"({"bufferView":0,"byteOffset":36,"componentType":5126,"count":3,"type":"VEC2"}],)"
               R"("bufferViews":[{"buffer":0,"byteLength":60}],"buffers":[{"byteLength":60,)"
               R"("uri":"data:application/octet-stream;base64,)" +
               base64(triangle) + "\"}]}";
    };
    const auto shown = loadWritten("sk_hidden_texture_shown.gltf", file(""));
    ASSERT_FALSE(shown) << "drawn, the masked mesh's texture must decode";
    EXPECT_NE(shown.error().find("image 0"), std::string::npos) << shown.error();
    const auto hidden =
        loadWritten("sk_hidden_texture.gltf", file(R"(,"extensions":{"KHR_node_visibility":{"visible":false}})"));
    ASSERT_TRUE(hidden) << hidden.error();
    EXPECT_EQ(hidden->instanceCount(), 1u);
}

TEST(GltfReadTest, AFileWithoutASceneShowsEachOfItsRootNodes) {
    // glTF §3.5: a file with no scene is a library; Blender's exporter writes one. Its roots are
    // node 0 (placing node 1's mesh 10 m along x and 5 along z) and node 2; node 1 is a child.
    const auto library = loadMeshNodes("sk_library.gltf", "",
                                       R"({"translation":[10,0,0],"children":[1]},{"translation":[0,0,5],"mesh":0},)"
                                       R"({"mesh":0})");
    ASSERT_TRUE(library) << library.error();
    ASSERT_EQ(library->instanceCount(), 2u);
    const auto& placed = library->batches.at(0).worldFromObject;
    ASSERT_EQ(placed.size(), 2u);
    // Wherever the loader stands the scene (near_origin.cpp), the two lie (10, 0, 5) apart.
    const glm::vec3 apart = glm::vec3(placed[0][3]) - glm::vec3(placed[1][3]);
    EXPECT_NEAR(glm::length(apart - glm::vec3(10, 0, 5)), 0.0f, 1e-5f) << apart.x << " " << apart.y << " " << apart.z;
    ASSERT_EQ(library->warnings.size(), 1u);
    EXPECT_NE(library->warnings[0].find("sk_library.gltf: it has no scene (a library of entities); its 2 root nodes "
                                        "stand together as the scene"),
              std::string::npos)
        << library->warnings[0];
    // With a scene, only what it lists: node 2 alone.
    const auto listed = loadMeshNodes("sk_listed.gltf", R"("scenes":[{"nodes":[2]}],)",
                                      R"({"translation":[10,0,0],"children":[1]},{"translation":[0,0,5],"mesh":0},)"
                                      R"({"mesh":0})");
    ASSERT_TRUE(listed) << listed.error();
    EXPECT_EQ(listed->instanceCount(), 1u);
    EXPECT_TRUE(listed->warnings.empty());
}

TEST(GltfReadTest, ADeepTreeOfNodesComposesEveryTransform) {
    // 300 nested nodes, each a metre along x from its parent: the mesh lands 300 m along x, once.
    auto s = loadNodes("sk_chain.gltf", "0", chainOfNodes(300));
    ASSERT_TRUE(s) << s.error();
    ASSERT_EQ(s->batches.size(), 1u);
    ASSERT_EQ(s->batches[0].worldFromObject.size(), 1u);
    // In the world: a mesh 300 m out from a metre-sized one stands at its own origin (near_origin.cpp).
    EXPECT_NEAR(s->wsOrigin.x + double(s->batches[0].worldFromObject[0][3].x), 300.0, 1e-3);
}

TEST(GltfReadTest, MirroredNodesKeepTheirFacesOutward) {
    // glTF: a node whose transform has a negative determinant reverses its mesh's winding. One
    // triangle facing up (counter-clockwise from above), placed plainly, mirrored in x, and
    // mirrored twice (no mirror): in the world every triangle must wind counter-clockwise about
    // its own normal, or a pass culling back faces would drop the lit side.
    std::vector<unsigned char> triangle;
    append<float>(triangle, {0, 0, 0, 1, 0, 0, 0, 0, -1});
    const std::string text =
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],"nodes":[{"mesh":0},
        {"mesh":0,"scale":[-1,1,1],"translation":[5,0,0]},{"mesh":0,"scale":[-1,-1,1],"translation":[9,0,0]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]}],
        "bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
        base64(triangle) + "\"}]}";
    const auto scene = loadWritten("sk_mirrored.gltf", text);
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_EQ(expectEveryTriangleFacesOutward(*scene), 3u) << "one triangle per node";
    EXPECT_EQ(scene->batches.size(), 2u) << "plain and doubly mirrored share a batch; mirrored has its own";
}

namespace {

// EXT_mesh_gpu_instancing (gltfpack -mi): one node places its mesh once per instance, at
// node × T × R × S. A triangle, a node at (10, 0, 0) and three instances: (0, 0, 0) as it is;
// (0, 5, 0), turned 90° about y, twice the size; (0, 0, 3) mirrored in x, its quaternion (0, 0, 0, 2)
// not unit. `attributes` picks among their accessors (4: zeros).
core::Result<scene::Scene> loadInstanced(const std::string& name, const std::string& attributes,
                                         const std::string& rotationType = "VEC4", int scaleCount = 3) {
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1});             // the triangle: 36 bytes
    append<float>(b, {0, 0, 0, 0, 5, 0, 0, 0, 3});              // TRANSLATION: 36 at 36
    const float s45 = std::sqrt(0.5f);                          // 90° about y: (0, sin 45°, 0, cos 45°)
    append<float>(b, {0, 0, 0, 1, 0, s45, 0, s45, 0, 0, 0, 2}); // ROTATION: 48 at 72 (the last not unit)
    append<float>(b, {1, 1, 1, 2, 2, 2, -1, 1, 1});             // SCALE: 36 at 120
    append<float>(b, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});     // zeros: 48 at 156
    return loadWritten(
        name,
        R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],"scene":0,"scenes":[{"nodes":[0]}],
        "nodes":[{"mesh":0,"translation":[10,0,0],"extensions":{"EXT_mesh_gpu_instancing":{"attributes":)" +
            attributes + R"(}}}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                     {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"},
                     {"bufferView":2,"componentType":5126,"count":3,"type":")" +
            rotationType + R"("},
                     {"bufferView":3,"componentType":5126,"count":)" +
            std::to_string(scaleCount) + R"(,"type":"VEC3"},
                     {"bufferView":4,"componentType":5126,"count":3,"type":"VEC4"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36},
                       {"buffer":0,"byteOffset":72,"byteLength":48},{"buffer":0,"byteOffset":120,"byteLength":36},
                       {"buffer":0,"byteOffset":156,"byteLength":48}],
        "buffers":[{"byteLength":204,"uri":"data:application/octet-stream;base64,)" +
            base64(b) + "\"}]}");
}

} // namespace

TEST(GltfReadTest, AnInstancedNodePlacesItsMeshOncePerInstance) {
    const auto s = loadInstanced("sk_instanced.gltf", R"({"TRANSLATION":1,"ROTATION":2,"SCALE":3})");
    ASSERT_TRUE(s) << s.error();
    // Where each instance puts the corner (1, 0, 0), worked by hand: (11, 0, 0); (1, 0, 0) doubled,
    // turned to (0, 0, -2), raised 5 and moved with the node, (10, 5, -2); mirrored to (-1, 0, 0),
    // moved 3 along z and with the node, (9, 0, 3).
    std::vector<glm::vec3> corners;
    size_t mirrored = 0;
    for (const scene::MeshBatch& batch : s->batches)
        for (const glm::mat4& m : batch.worldFromObject) {
            corners.push_back(glm::vec3(m * glm::vec4(1, 0, 0, 1)));
            mirrored += glm::determinant(glm::mat3(m)) < 0.0f;
        }
    ASSERT_EQ(corners.size(), 3u) << "one instance per element, not one per node";
    EXPECT_EQ(mirrored, 1u);
    EXPECT_EQ(s->batches.size(), 2u) << "the mirrored instance has a batch of its own";
    for (const glm::vec3& expected : {glm::vec3(11, 0, 0), glm::vec3(10, 5, -2), glm::vec3(9, 0, 3)})
        EXPECT_TRUE(std::any_of(corners.begin(), corners.end(),
                                [&](const glm::vec3& c) { return glm::distance(c, expected) < 1e-5f; }))
            << expected.x << "," << expected.y << "," << expected.z;
}

TEST(GltfReadTest, InstancingThatCannotBePlacedIsRefusedInOneLine) {
    for (const auto& [what, s, expected] : {
             std::tuple{"counts differ", loadInstanced("sk_inst.gltf", R"({"TRANSLATION":1,"SCALE":3})", "VEC4", 2),
                        "its attributes have different counts (3 and 2)"},
             std::tuple{"a rotation of three components", loadInstanced("sk_inst.gltf", R"({"ROTATION":2})", "VEC3"),
                        "ROTATION must be a VEC4 accessor"},
             std::tuple{"a zero quaternion", loadInstanced("sk_inst.gltf", R"({"ROTATION":4})"),
                        "instance 0's rotation is not a quaternion"},
             std::tuple{"an accessor that is not there", loadInstanced("sk_inst.gltf", R"({"SCALE":9})"),
                        "SCALE: accessor 9: no such accessor"},
         }) {
        SCOPED_TRACE(what);
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().find("sk_inst.gltf: node 0 (EXT_mesh_gpu_instancing)"), std::string::npos) << s.error();
        EXPECT_NE(s.error().find(expected), std::string::npos) << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    }
}

TEST(GltfReadTest, ARequiredExtensionThatMayCarryShapesIsNamedInAWarning) {
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1});
    const auto file = [&](const std::string& required) {
        return R"({"asset":{"version":"2.0"},"extensionsUsed":[)" + required + R"(],"extensionsRequired":[)" +
               required + R"(],"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
            "bufferViews":[{"buffer":0,"byteLength":36}],
            "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
               base64(b) + "\"}]}";
    };
    const auto unknown = loadWritten("sk_required.gltf", file(R"("EXT_made_up_geometry")"));
    ASSERT_TRUE(unknown) << unknown.error();
    ASSERT_EQ(unknown->warnings.size(), 1u);
    EXPECT_NE(unknown->warnings[0].find("sk_required.gltf: it requires EXT_made_up_geometry, which shadowkit does "
                                        "not read"),
              std::string::npos)
        << unknown->warnings[0];
    // Extensions that only shade, or that the reader handles, say nothing.
    const auto shading = loadWritten(
        "sk_required.gltf", file(R"("KHR_materials_clearcoat","KHR_mesh_quantization","EXT_mesh_gpu_instancing")"));
    ASSERT_TRUE(shading) << shading.error();
    EXPECT_TRUE(shading->warnings.empty()) << shading->warnings.front();
}

TEST(GltfReadTest, AMaskThatItsVertexColoursWouldCutIsNamedInAWarning) {
    // COLOR_0's alpha multiplies the material's (glTF §3.9.2), and shadowkit's vertices keep
    // none: a masked triangle whose vertex alpha falls under the cutoff casts whole. Said once.
    std::vector<unsigned char> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 0, -1});            // positions
    append<float>(b, {1, 1, 1, 1, 1, 1, 1, 0.2f, 1, 1, 1, 1}); // COLOR_0, RGBA: one vertex at 0.2
    const auto loadWith = [&](const std::string& name, const std::string& material) {
        return loadGltfText(
            name,
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1},"material":0}]}],)"
            R"("materials":[)" +
                material +
                R"(],)"
                R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC4"}],)"
                R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":48}])",
            b);
    };
    const auto masked = loadWith("sk_vertex_alpha.gltf", R"({"alphaMode":"MASK"})");
    ASSERT_TRUE(masked) << masked.error();
    ASSERT_EQ(masked->warnings.size(), 1u);
    EXPECT_NE(masked->warnings[0].find("sk_vertex_alpha.gltf: mesh 0 primitive 0: its COLOR_0 alpha falls to 0.2, "
                                       "under its material's cutoff 0.5"),
              std::string::npos)
        << masked->warnings[0];
    // Under a lower cutoff, or on an opaque material, the vertex alpha changes nothing.
    const auto low = loadWith("sk_vertex_alpha_low.gltf", R"({"alphaMode":"MASK","alphaCutoff":0.1})");
    ASSERT_TRUE(low) << low.error();
    EXPECT_TRUE(low->warnings.empty()) << low->warnings.front();
    const auto opaque = loadWith("sk_vertex_alpha_opaque.gltf", "{}");
    ASSERT_TRUE(opaque) << opaque.error();
    EXPECT_TRUE(opaque->warnings.empty()) << opaque->warnings.front();
}
