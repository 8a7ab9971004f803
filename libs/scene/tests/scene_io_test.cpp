#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/scene_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <utility>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {
Scene tinyForest() {
    ForestOptions o;
    o.trees = 20;
    o.terrainSize = 100;
    o.terrainResolution = 8;
    o.rocks = 2;
    o.buildings = 1;
    o.movers = 1;
    return makeForest(o);
}
// Bounds of every transformed vertex (Scene::wsBounds is the looser box of boxes).
core::Aabb exactBounds(const Scene& s) {
    core::Aabb b;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject)
            for (const Vertex& v : s.meshes[batch.mesh].vertices) b.extend(core::Vec3(m * glm::vec4(v.position, 1.0f)));
    return b;
}
void expectSameBounds(const core::Aabb& a, const core::Aabb& b) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.min[i], b.min[i], 1e-2);
        EXPECT_NEAR(a.max[i], b.max[i], 1e-2);
    }
}
} // namespace

TEST(SceneIoTest, ExportedGlbAndObjLoadBackWithTheSameTrianglesAndBounds) {
    const Scene forest = tinyForest();
    for (const char* name : {"shadowkit_io_test.glb", "shadowkit_io_test.obj"}) {
        const auto file = std::filesystem::temp_directory_path() / name;
        ASSERT_TRUE(exportScene(forest, file)) << name;
        const auto loaded = loadScene(file);
        ASSERT_TRUE(loaded) << loaded.error();
        EXPECT_EQ(loaded->triangleCount(), forest.triangleCount()) << name;
        expectSameBounds(exactBounds(*loaded), exactBounds(forest));
        const core::Aabb loose = forest.wsBounds();
        EXPECT_TRUE(loose.contains(exactBounds(*loaded).min, 1e-3) && loose.contains(exactBounds(*loaded).max, 1e-3));
        std::filesystem::remove(file);
    }
}

TEST(SceneIoTest, GltfNodesSharingAMeshBecomeOneInstancedBatch) {
    // Two nodes referencing mesh 0 (a single triangle in an embedded base64 buffer).
    const auto file = std::filesystem::temp_directory_path() / "shadowkit_instanced.gltf";
    std::ofstream(file) << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
      "nodes":[{"mesh":0},{"mesh":0,"translation":[10,0,0]}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
      "bufferViews":[{"buffer":0,"byteLength":36}],
      "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
    const auto scene = loadScene(file);
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_EQ(scene->batches.size(), 1u);
    EXPECT_EQ(scene->batches[0].worldFromObject.size(), 2u);
    EXPECT_NEAR(scene->wsBounds().max.x, 11.0, 1e-6);
    std::filesystem::remove(file);
}

TEST(SceneIoTest, BadFilesGiveOneLineNamingTheFile) {
    const auto dir = std::filesystem::temp_directory_path();
    const auto missing = loadScene(dir / "no_such_scene.glb");
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().find("no_such_scene.glb"), std::string::npos);
    EXPECT_EQ(missing.error().find('\n'), std::string::npos);

    const auto garbage = dir / "shadowkit_garbage.glb";
    std::ofstream(garbage) << "this is not a glb";
    const auto g = loadScene(garbage);
    ASSERT_FALSE(g);
    EXPECT_EQ(g.error().find('\n'), std::string::npos);
    std::filesystem::remove(garbage);

    EXPECT_FALSE(loadScene(dir / "x.fbx"));
    EXPECT_FALSE(exportScene(tinyForest(), dir / "x.fbx"));
}

// Finite geometry past the world's end: a view framing it put its eye at 1e20 m, and Embree
// aborted the program on the first ray from there (`eval --scene far.obj`).
TEST(SceneIoTest, GeometryPastTheWorldsEndIsRefusedInOneLine) {
    const auto dir = std::filesystem::temp_directory_path();
    const auto far = dir / "shadowkit_far.obj";
    std::ofstream(far) << "v 0 0 0\nv 1 0 0\nv 0 1e20 0\nf 1 2 3\n";
    const auto loaded = loadScene(far);
    ASSERT_FALSE(loaded);
    EXPECT_NE(loaded.error().find("shadowkit_far.obj: its geometry reaches 1e+20 m from the origin"), std::string::npos)
        << loaded.error();
    // A unit triangle put there by a node's scale, and one a node moves 9e12 m: only the first.
    for (const auto& [node, refused] : {std::pair{R"({"mesh":0,"scale":[1e15,1e15,1e15]})", true},
                                        std::pair{R"({"mesh":0,"translation":[9e12,0,0]})", false}}) {
        const auto file = dir / "shadowkit_far.gltf";
        std::ofstream(file) << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" << node
                            << R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                            << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
                            << R"("min":[0,0,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
                            << R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
                            << R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
        const auto scene = loadScene(file);
        EXPECT_EQ(!scene, refused) << node;
        if (!scene) {
            EXPECT_NE(scene.error().find("at most 1e13 m"), std::string::npos) << scene.error();
        }
        std::filesystem::remove(file);
    }
    std::filesystem::remove(far);
}

TEST(SceneIoTest, LoadedTerrainPlacesTheEyeOverItNotUnderIt) {
    // The exported forest has no heightfield once loaded: the ground under a point must
    // come from its terrain triangles (the clearing at the origin has no trees).
    const Scene forest = tinyForest();
    const auto file = std::filesystem::temp_directory_path() / "shadowkit_ground.glb";
    ASSERT_TRUE(exportScene(forest, file));
    const auto loaded = loadScene(file);
    ASSERT_TRUE(loaded);
    EXPECT_FALSE(loaded->terrain.has_value());
    for (auto [x, z] : {std::pair{0.0, 0.0}, std::pair{3.0, -2.0}})
        EXPECT_NEAR(loaded->groundHeightAt(x, z), forest.terrain->heightAt(x, z), 1e-3) << x << "," << z;
    std::filesystem::remove(file);
}

TEST(SceneIoTest, ObjKeepsVertexColoursNormalsAndObjects) {
    // shadowkit's own OBJ carries `v x y z r g b` and normals: both come back, and each exported
    // object is a mesh of its own. A file with neither is light grey with normals from its faces.
    const Scene forest = tinyForest();
    const auto file = std::filesystem::temp_directory_path() / "shadowkit_colours.obj";
    ASSERT_TRUE(exportScene(forest, file));
    const auto loaded = loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->meshes.size(), forest.batches.size());
    int green = 0;
    for (const Mesh& mesh : loaded->meshes)
        for (const Vertex& v : mesh.vertices)
            green += v.albedo.g > v.albedo.r + 0.05f && v.albedo.g > v.albedo.b; // foliage
    EXPECT_GT(green, 100);
    std::filesystem::remove(file);

    const auto plain = std::filesystem::temp_directory_path() / "shadowkit_plain.obj";
    std::ofstream(plain) << "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3 4\n";
    const auto quad = loadScene(plain);
    ASSERT_TRUE(quad) << quad.error();
    ASSERT_EQ(quad->meshes.size(), 1u);
    EXPECT_EQ(quad->meshes[0].name, "quad");
    EXPECT_EQ(quad->meshes[0].indices.size(), 6u); // the quad triangulated
    for (const Vertex& v : quad->meshes[0].vertices) {
        EXPECT_EQ(v.albedo, glm::vec3(0.7f));
        EXPECT_NEAR(v.normal.y, 1.0f, 1e-6f); // counter-clockwise from above: up
    }
    std::ofstream(plain) << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
    const auto bad = loadScene(plain);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().find("shadowkit_plain.obj"), std::string::npos) << bad.error();
    EXPECT_EQ(bad.error().find('\n'), std::string::npos) << bad.error();
    std::filesystem::remove(plain);
}
