#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <tuple>
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
// Bounds of every transformed vertex of the full meshes' triangles (Scene::wsBounds is the looser
// box of boxes; a leafy mesh's coarser levels have vertices of their own).
core::Aabb exactBounds(const Scene& s) {
    core::Aabb b;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject)
            for (uint32_t i : s.meshes[batch.mesh].indices)
                b.extend(core::Vec3(m * glm::vec4(s.meshes[batch.mesh].vertices[i].position, 1.0f)));
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
        const auto file = shadowkit::test_support::scratchDir() / name;
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

namespace {
// What an export must carry: the vertices each batch's mesh's full triangles use, once per
// instance (baked into world space: OBJ) or once (placed by nodes: glb).
size_t verticesDrawn(const Scene& s, bool perInstance) {
    size_t count = 0;
    for (const MeshBatch& batch : s.batches) {
        const std::set<uint32_t> used(s.meshes[batch.mesh].indices.begin(), s.meshes[batch.mesh].indices.end());
        count += used.size() * (perInstance ? batch.worldFromObject.size() : 1);
    }
    return count;
}

// A .glb read by hand, not by the loader under test: its JSON chunk and its binary chunk.
struct GlbChunks {
    nlohmann::json json;
    std::string bin;
};
GlbChunks readGlb(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    GlbChunks out;
    size_t at = 12; // magic, version, length
    while (at + 8 <= bytes.size()) {
        uint32_t length = 0, type = 0;
        std::memcpy(&length, bytes.data() + at, 4);
        std::memcpy(&type, bytes.data() + at + 4, 4);
        const std::string chunk = bytes.substr(at + 8, length);
        if (type == 0x4E4F534Au) out.json = nlohmann::json::parse(chunk);
        if (type == 0x004E4942u) out.bin = chunk;
        at += 8 + length;
    }
    return out;
}
// Every triangle of every instance in world space, by its centroid, with which way its winding
// faces (counter-clockwise seen from the front).
std::vector<std::pair<glm::vec3, glm::vec3>> worldTriangles(const Scene& s) {
    std::vector<std::pair<glm::vec3, glm::vec3>> out;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject) {
            const Mesh& mesh = s.meshes[batch.mesh];
            for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
                glm::vec3 p[3];
                for (int k = 0; k < 3; ++k)
                    p[k] = glm::vec3(m * glm::vec4(mesh.vertices[mesh.indices[t + k]].position, 1.0f));
                out.push_back({(p[0] + p[1] + p[2]) / 3.0f, glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]))});
            }
        }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return std::tie(a.first.x, a.first.y, a.first.z) < std::tie(b.first.x, b.first.y, b.first.z);
    });
    return out;
}
} // namespace

TEST(SceneIoTest, MirroredAndShearedInstancesComeBackWhereTheyWereFacingOutwards) {
    // A box placed as it is, mirrored (Scene keeps a mirrored batch's triangles already turned,
    // as the glTF reader does), and sheared (no node matrix can hold a shear: baked).
    Mesh box;
    addBox(box, glm::mat4(1.0f), {1.0f, 0.5f, 0.25f}, glm::vec3(0.5f));
    box.computeBounds();
    Mesh turned = box;
    for (size_t t = 0; t + 2 < turned.indices.size(); t += 3) std::swap(turned.indices[t + 1], turned.indices[t + 2]);
    glm::mat4 sheared = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 6.0f});
    sheared[1][0] = 0.5f; // x grows with y
    Scene s;
    s.meshes = {box, turned};
    s.batches = {{0, {glm::mat4(1.0f), sheared}, false},
                 {1, {glm::scale(glm::translate(glm::mat4(1.0f), {5.0f, 0.0f, 0.0f}), {-1.0f, 1.0f, 1.0f})}, false}};
    const auto source = worldTriangles(s);
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_io_mirrored.glb";
    ASSERT_TRUE(exportScene(s, file));
    const auto loaded = loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    const auto back = worldTriangles(*loaded);
    ASSERT_EQ(back.size(), source.size());
    for (size_t t = 0; t < source.size(); ++t) {
        EXPECT_LT(glm::distance(back[t].first, source[t].first), 1e-4f) << t;
        EXPECT_GT(glm::dot(back[t].second, source[t].second), 0.999f) << t << ": turned inside out";
    }
    const nlohmann::json j = readGlb(file).json;
    std::set<std::string> meshes;
    for (const auto& mesh : j["meshes"]) meshes.insert(mesh.value("name", ""));
    EXPECT_EQ(meshes.size(), 3u) << "placed, mirrored and baked";
    std::filesystem::remove(file);
}

TEST(SceneIoTest, AGlbPastItsFourGigabytesIsRefusedBeforeItIsBuilt) {
    // 2^20 vertices drawn by 100 sheared placements, which no node can hold, so baked: 5 GB, past
    // the 2^32 bytes a binary glTF's 32-bit lengths can say (tinygltf wrote such lengths truncated).
    Mesh strip;
    strip.vertices.resize(size_t(1) << 20);
    for (size_t v = 0; v < strip.vertices.size(); ++v)
        strip.vertices[v].position = glm::vec3(float(v % 1024), float(v / 1024), 0.0f);
    for (uint32_t v = 0; v + 2 < strip.vertices.size(); ++v)
        strip.indices.insert(strip.indices.end(), {v, v + 1, v + 2});
    strip.computeBounds();
    glm::mat4 sheared(1.0f);
    sheared[1][0] = 0.5f;
    Scene s;
    s.meshes = {strip};
    s.batches = {{0, std::vector<glm::mat4>(100, sheared), false}};
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_io_too_large.glb";
    std::filesystem::remove(file);
    const core::Status status = exportScene(s, file);
    ASSERT_FALSE(status);
    // (2^20 × 36 + (2^20 − 2) × 3 × 4) × 100 bytes: 3 vec3 a vertex, uint32 indices.
    EXPECT_NE(status.error().find(file.string() + ": the scene needs 5.03 GB"), std::string::npos) << status.error();
    EXPECT_NE(status.error().find("a binary glTF can hold"), std::string::npos) << status.error();
    EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(SceneIoTest, AnExportedFileHoldsOnlyWhatItDrawsEachMeshOnceWithANodePerInstance) {
    // A leafy forest: its leaf meshes' vertex lists also hold their card levels' vertices, and its
    // textures the billboard clouds' beside the leaf atlas its material uses.
    ForestOptions o;
    o.kind = ForestKind::Leafy;
    o.trees = 3;
    o.terrainSize = 40;
    o.terrainResolution = 4;
    o.rocks = o.buildings = o.movers = 0;
    const Scene forest = makeForest(o);
    std::set<int32_t> texturesUsed;
    for (const Material& m : forest.materials)
        if (m.baseColorTexture >= 0) texturesUsed.insert(m.baseColorTexture);
    ASSERT_FALSE(texturesUsed.empty());
    ASSERT_GT(forest.textures.size(), texturesUsed.size()); // the clouds' textures, which no material uses
    size_t held = 0;
    for (const MeshBatch& batch : forest.batches) held += forest.meshes[batch.mesh].vertices.size();
    ASSERT_GT(held, verticesDrawn(forest, false)); // the case that matters: vertices only the coarser levels use

    const auto glb = shadowkit::test_support::scratchDir() / "shadowkit_io_drawn.glb";
    ASSERT_TRUE(exportScene(forest, glb));
    const GlbChunks chunks = readGlb(glb);
    const nlohmann::json& j = chunks.json;
    ASSERT_TRUE(j.is_object());
    // The images: the used textures, each once, in the binary chunk (not base64 in the JSON).
    ASSERT_EQ(j["images"].size(), texturesUsed.size());
    for (const auto& image : j["images"]) {
        EXPECT_FALSE(image.contains("uri"));
        EXPECT_EQ(image.value("mimeType", ""), "image/png");
        const auto& view = j["bufferViews"][image["bufferView"].get<size_t>()];
        EXPECT_EQ(chunks.bin.compare(view.value("byteOffset", size_t(0)), 8, "\x89PNG\r\n\x1a\n"), 0);
    }
    std::set<size_t> imagesReferenced;
    for (const auto& material : j["materials"])
        if (material["pbrMetallicRoughness"].contains("baseColorTexture"))
            imagesReferenced.insert(
                j["textures"][material["pbrMetallicRoughness"]["baseColorTexture"]["index"].get<size_t>()]["source"]
                    .get<size_t>());
    EXPECT_EQ(imagesReferenced.size(), j["images"].size());
    // Every accessor aligned to its component (glTF 2.0 §3.6.2.4), and every vertex of every
    // primitive used by one of its triangles.
    size_t vertices = 0;
    for (const auto& accessor : j["accessors"]) {
        const auto& view = j["bufferViews"][accessor["bufferView"].get<size_t>()];
        EXPECT_EQ((view.value("byteOffset", size_t(0)) + accessor.value("byteOffset", size_t(0))) % 4, 0u);
    }
    for (const auto& mesh : j["meshes"])
        for (const auto& primitive : mesh["primitives"]) {
            const size_t count = j["accessors"][primitive["attributes"]["POSITION"].get<size_t>()]["count"];
            const auto& indices = j["accessors"][primitive["indices"].get<size_t>()];
            ASSERT_EQ(indices["componentType"], 5125); // UNSIGNED_INT
            const size_t offset = j["bufferViews"][indices["bufferView"].get<size_t>()].value("byteOffset", size_t(0));
            std::vector<bool> used(count, false);
            for (size_t i = 0; i < indices["count"].get<size_t>(); ++i) {
                uint32_t index = 0;
                std::memcpy(&index, chunks.bin.data() + offset + 4 * i, 4);
                ASSERT_LT(index, count);
                used[index] = true;
            }
            EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << mesh.value("name", "");
            vertices += count;
        }
    EXPECT_EQ(vertices, verticesDrawn(forest, false));
    // Each batch's mesh once, and a node placing it per instance (under a node per batch).
    size_t instances = 0;
    for (const MeshBatch& batch : forest.batches) instances += batch.worldFromObject.size();
    EXPECT_EQ(j["meshes"].size(), forest.batches.size());
    EXPECT_EQ(j["nodes"].size(), forest.batches.size() + instances);
    // Loaded back: the same batches, placements and triangles.
    const auto loaded = loadScene(glb);
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->triangleCount(), forest.triangleCount());
    ASSERT_EQ(loaded->batches.size(), forest.batches.size());
    for (size_t b = 0; b < forest.batches.size(); ++b) {
        ASSERT_EQ(loaded->batches[b].worldFromObject.size(), forest.batches[b].worldFromObject.size()) << b;
        for (size_t i = 0; i < forest.batches[b].worldFromObject.size(); ++i)
            for (int c = 0; c < 4; ++c)
                EXPECT_LT(
                    glm::distance(loaded->batches[b].worldFromObject[i][c], forest.batches[b].worldFromObject[i][c]),
                    1e-5f)
                    << b << " " << i;
    }
    expectSameBounds(exactBounds(*loaded), exactBounds(forest));
    std::filesystem::remove(glb);

    // The OBJ: the same vertices, one `v` line each.
    const auto obj = shadowkit::test_support::scratchDir() / "shadowkit_io_drawn.obj";
    ASSERT_TRUE(exportScene(forest, obj));
    std::ifstream in(obj);
    size_t vLines = 0;
    for (std::string line; std::getline(in, line);) vLines += line.rfind("v ", 0) == 0;
    EXPECT_EQ(vLines, verticesDrawn(forest, true));
    std::filesystem::remove(obj);
}

TEST(SceneIoTest, GltfNodesSharingAMeshBecomeOneInstancedBatch) {
    // Two nodes referencing mesh 0 (a single triangle in an embedded base64 buffer).
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_instanced.gltf";
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
    const auto dir = shadowkit::test_support::scratchDir();
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
    const auto dir = shadowkit::test_support::scratchDir();
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

// A scene of triangles without area frames a point (eye at the origin, near 0.0009 m, far
// 0.0011 m, as the glTF Validator's node and skin files loaded: accessors with no buffer view are
// zeros) and casts nothing: refused in one line. A flat plane has area and loads.
TEST(SceneIoTest, AScenePlacingNoAreaIsRefusedInOneLine) {
    const auto dir = shadowkit::test_support::scratchDir();
    const auto expectRefused = [](const std::filesystem::path& file) {
        const auto loaded = loadScene(file);
        ASSERT_FALSE(loaded) << file;
        EXPECT_NE(loaded.error().find(file.filename().string() + ": every triangle it places has no area"),
                  std::string::npos)
            << loaded.error();
        EXPECT_EQ(loaded.error().find('\n'), std::string::npos) << loaded.error();
    };
    const auto line = dir / "shadowkit_line.obj";
    std::ofstream(line) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
    expectRefused(line);
    const auto plane = dir / "shadowkit_plane.obj";
    std::ofstream(plane) << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n";
    EXPECT_TRUE(loadScene(plane));
    const auto gltf = [&](const std::string& name, const std::string& node, const std::string& accessor) {
        const auto file = dir / name;
        std::ofstream(file) << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" << node
                            << R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"accessors":[)"
                            << accessor << R"(],"bufferViews":[{"buffer":0,"byteLength":36}],)"
                            << R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
                            << R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
        return file;
    };
    const std::string unitTriangle = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
    expectRefused(gltf("shadowkit_zeros.gltf", R"({"mesh":0})", R"({"componentType":5126,"count":3,"type":"VEC3"})"));
    expectRefused(gltf("shadowkit_scaled_away.gltf", R"({"mesh":0,"scale":[0,0,0]})", unitTriangle));
    EXPECT_TRUE(loadScene(gltf("shadowkit_unit.gltf", R"({"mesh":0})", unitTriangle)));
}

TEST(SceneIoTest, LoadedTerrainPlacesTheEyeOverItNotUnderIt) {
    // The exported forest has no heightfield once loaded: the ground under a point must
    // come from its terrain triangles (the clearing at the origin has no trees).
    const Scene forest = tinyForest();
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_ground.glb";
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
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_colours.obj";
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

    const auto plain = shadowkit::test_support::scratchDir() / "shadowkit_plain.obj";
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
