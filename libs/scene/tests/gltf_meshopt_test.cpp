// glTF with meshopt-compressed buffer views (EXT_meshopt_compression): gltfpack's files load as
// the same tool's uncompressed output of the same models; every mode and filter decodes what
// meshoptimizer's encoder wrote; what is malformed or hostile is refused in one line, before
// memory is given to it.
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <vector>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

// tests/data/meshopt: written by tools/make-meshopt-fixtures.sh (gltfpack 1.3).
fs::path fixture(const std::string& name) {
    return fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "meshopt" / name;
}

// A triangle as placed in the world: its corners' positions, normals and texture coordinates.
struct Triangle {
    std::array<glm::vec3, 3> position, normal;
    std::array<glm::vec2, 3> uv;
};

std::vector<Triangle> worldTriangles(const scene::Scene& s) {
    std::vector<Triangle> out;
    for (const scene::MeshBatch& batch : s.batches) {
        const scene::Mesh& mesh = s.meshes[batch.mesh];
        for (const glm::mat4& worldFromObject : batch.worldFromObject) {
            const glm::mat3 normalFromObject = glm::transpose(glm::inverse(glm::mat3(worldFromObject)));
            for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
                Triangle tri;
                for (int k = 0; k < 3; ++k) {
                    const scene::Vertex& v = mesh.vertices[mesh.indices[t + size_t(k)]];
                    tri.position[k] = glm::vec3(worldFromObject * glm::vec4(v.position, 1.0f));
                    tri.normal[k] = glm::normalize(normalFromObject * v.normal);
                    tri.uv[k] = v.uv;
                }
                out.push_back(tri);
            }
        }
    }
    return out;
}

// The largest differences between matched triangles of two scenes, each triangle matched to the
// other scene's nearest in position (any of its three rotations, the winding kept): a decoder
// may not reorder what it decodes, but gltfpack orders vertices for its codecs.
struct Differences {
    float position = 0, normal = 0, uv = 0;
};

Differences compare(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
    Differences worst;
    for (const Triangle& ta : a) {
        float best = std::numeric_limits<float>::infinity();
        Differences atBest;
        for (const Triangle& tb : b)
            for (int r = 0; r < 3; ++r) {
                Differences d;
                for (int k = 0; k < 3; ++k) {
                    const int j = (k + r) % 3;
                    d.position = std::max(d.position, glm::length(ta.position[k] - tb.position[j]));
                    d.normal = std::max(d.normal, glm::length(ta.normal[k] - tb.normal[j]));
                    d.uv = std::max(d.uv, glm::length(ta.uv[k] - tb.uv[j]));
                }
                if (d.position < best) best = d.position, atBest = d;
            }
        worst.position = std::max(worst.position, atBest.position);
        worst.normal = std::max(worst.normal, atBest.normal);
        worst.uv = std::max(worst.uv, atBest.uv);
    }
    return worst;
}

float extentOf(const std::vector<Triangle>& triangles) {
    core::Aabb box;
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.position) box.extend(core::Vec3(p));
    return float(box.diagonal());
}

TEST(GltfMeshoptTest, GltfpacksCompressedFilesLoadAsItsUncompressedOnes) {
    struct Case {
        const char* compressed;
        const char* reference;
        float positionBound, normalBound, uvBound; // the filter's precision; 0 where lossless
    };
    // gltfpack quantizes both files alike (KHR_mesh_quantization); the codecs are lossless, and
    // its filters round: octahedral normals to 8 bits (a direction within 2/127 of the 8-bit
    // normal), exponential floats to 14 mantissa bits of the largest component of each vector
    // (the tree has no normals: the loader's, from the rounded positions of its small cards,
    // turn by up to half a degree).
    for (const Case& c :
         {Case{"pillar-cc.glb", "pillar-q.glb", 0.0f, 0.03f, 0.0f},
          Case{"pillar-c.gltf", "pillar-q.glb", 0.0f, 0.0f, 0.0f},
          Case{"pillar-cf.glb", "pillar-q.glb", 0.0f, 0.0f, 0.0f}, Case{"tree-c.glb", "tree-q.glb", 0.0f, 0.0f, 0.0f},
          Case{"tree-exp.glb", "tree-f.glb", 3e-4f, 0.01f, 3e-4f}}) {
        SCOPED_TRACE(c.compressed);
        const auto compressed = scene::loadScene(fixture(c.compressed));
        const auto reference = scene::loadScene(fixture(c.reference));
        ASSERT_TRUE(compressed) << compressed.error();
        ASSERT_TRUE(reference) << reference.error();
        const auto a = worldTriangles(*compressed), b = worldTriangles(*reference);
        ASSERT_EQ(a.size(), b.size());
        ASSERT_GT(a.size(), 10u);
        const Differences d = compare(a, b);
        const float extent = extentOf(b);
        EXPECT_LE(d.position, c.positionBound * extent) << "extent " << extent;
        EXPECT_LE(d.normal, c.normalBound);
        EXPECT_LE(d.uv, c.uvBound);
        // The alpha-cut tree keeps its material and its texture (an image in the binary chunk,
        // beside the compressed streams).
        ASSERT_EQ(compressed->materials.size(), reference->materials.size());
        for (size_t m = 0; m < compressed->materials.size(); ++m)
            EXPECT_EQ(compressed->materials[m].alphaMode, reference->materials[m].alphaMode);
    }
}

TEST(GltfMeshoptTest, GltfpacksInstancedFilesPlaceEveryInstanceWhereItsNodesDid) {
    // grove.gltf places one cube by 25 nodes, each turned and scaled its own way; gltfpack -mi
    // folds them into one node of EXT_mesh_gpu_instancing (its rotations as 16-bit quaternions),
    // and with -cc quantizes the cube and compresses the instances (quaternion filter too). The
    // bounds are those roundings' (measured: 4e-6 and 1.2e-4 of the grove's 17 m); transforms
    // composed in another order are metres off.
    const auto reference = scene::loadScene(fixture("grove.gltf"));
    ASSERT_TRUE(reference) << reference.error();
    const auto b = worldTriangles(*reference);
    ASSERT_EQ(b.size(), 25u * 12u);
    for (const auto& [file, bound] : {std::pair{"grove-mi.glb", 2e-5f}, std::pair{"grove-mi-cc.glb", 5e-4f}}) {
        SCOPED_TRACE(file);
        const auto instanced = scene::loadScene(fixture(file));
        ASSERT_TRUE(instanced) << instanced.error();
        const auto a = worldTriangles(*instanced);
        ASSERT_EQ(a.size(), b.size()) << "every instance placed";
        EXPECT_LE(compare(a, b).position, bound * extentOf(b)) << "extent " << extentOf(b);
        EXPECT_LE(compare(b, a).position, bound * extentOf(b));
    }
}

TEST(GltfMeshoptTest, ACompressedFileNeedsNoFallbackBuffer) {
    // pillar-cf.glb names its uncompressed copy, pillar-cf.fallback.bin, which is not there (the
    // fixture script removes it): a decoder never reads it.
    ASSERT_FALSE(fs::exists(fixture("pillar-cf.fallback.bin")));
    const auto s = scene::loadScene(fixture("pillar-cf.glb"));
    ASSERT_TRUE(s) << s.error();
    EXPECT_GT(s->triangleCount(), 10u);
}

TEST(GltfMeshoptTest, AVertexCodecNewerThanTheLibraryIsRefusedByNameInOneLine) {
    const auto s = scene::loadScene(fixture("pillar-khr.glb"));
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().find("pillar-khr.glb: buffer view 0 (KHR_meshopt_compression)"), std::string::npos)
        << s.error();
    EXPECT_NE(s.error().find("vertex codec version 1"), std::string::npos) << s.error();
    EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
}

// --- files written here with meshoptimizer's encoder, one stream per mode and filter ---------

template <class T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values) {
    std::vector<unsigned char> out(values.size() * sizeof(T));
    std::memcpy(out.data(), values.data(), out.size());
    return out;
}

std::vector<unsigned char> encodeAttributes(const std::vector<unsigned char>& raw, size_t count, size_t stride) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), raw.data(), count, stride));
    return out;
}

// A square of two triangles facing +y, as meshoptimizer encodes it: positions (exponential filter,
// float VEC3), normals (octahedral, 8-bit), colours (quaternion filter on normalized 16-bit
// VEC4, read as colour: q = (1,0,0,0), (0,1,0,0), (0,0,1,0), (1,0,0,0)), one triangle's indices
// as a sequence (INDICES, 32-bit), the other's as a triangle list (TRIANGLES, 16-bit). The
// views decode into a placeholder buffer with no data; `edit` changes the JSON before it is
// written (the stream's bytes, in buffer 0, are not touched unless `corrupt`).
std::string squareFile(const std::function<void(std::string&)>& edit = {}, bool corrupt = false) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 0, -1, 0, 0, -1};
    std::vector<int8_t> normals(16);
    const std::vector<float> up = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
    meshopt_encodeFilterOct(normals.data(), 4, 4, 8, up.data());
    std::vector<int16_t> colours(16);
    const std::vector<float> quats = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0};
    meshopt_encodeFilterQuat(colours.data(), 4, 8, 12, quats.data());
    std::vector<uint32_t> exp(12);
    meshopt_encodeFilterExp(exp.data(), 4, 12, 24, positions.data());
    const std::vector<uint32_t> sequence = {0, 1, 2};
    std::vector<unsigned char> encodedSequence(meshopt_encodeIndexSequenceBound(3, 4));
    encodedSequence.resize(
        meshopt_encodeIndexSequence(encodedSequence.data(), encodedSequence.size(), sequence.data(), 3));
    const std::vector<uint32_t> list = {0, 2, 3};
    std::vector<unsigned char> encodedList(meshopt_encodeIndexBufferBound(3, 4));
    encodedList.resize(meshopt_encodeIndexBuffer(encodedList.data(), encodedList.size(), list.data(), 3));

    // Buffer 0: the streams one after another, each view's extension pointing at its own.
    std::vector<std::vector<unsigned char>> streams = {
        encodeAttributes(bytesOf(exp), 4, 12), encodeAttributes(bytesOf(normals), 4, 4),
        encodeAttributes(bytesOf(colours), 4, 8), encodedSequence, encodedList};
    if (corrupt) streams[0][0] = 0x00; // not the attribute codec's header byte
    std::vector<unsigned char> buffer;
    std::vector<size_t> offsets;
    for (const auto& s : streams) {
        offsets.push_back(buffer.size());
        buffer.insert(buffer.end(), s.begin(), s.end());
    }
    // Buffer 1, the placeholder: positions 48 bytes at 0, normals 16 at 48, colours 32 at 64,
    // the sequence 12 at 96 and the list 6 at 108.
    // (The normals' view gives its stride: their accessor's elements, 3 bytes, lie 4 apart.)
    const auto view = [&](size_t i, size_t target, size_t length, size_t stride, size_t count, const char* mode,
                          const char* filter) {
        return R"({"buffer":1,"byteOffset":)" + std::to_string(target) + R"(,"byteLength":)" + std::to_string(length) +
               (i == 1 ? R"(,"byteStride":4)" : "") +
               R"(,"extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":)" + std::to_string(offsets[i]) +
               R"(,"byteLength":)" + std::to_string(streams[i].size()) + R"(,"byteStride":)" + std::to_string(stride) +
               R"(,"count":)" + std::to_string(count) + R"(,"mode":")" + mode + R"(","filter":")" + filter + R"("}}})";
    };
    std::string text =
        R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_meshopt_compression"],
        "extensionsRequired":["EXT_meshopt_compression"],"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"COLOR_0":2},"indices":3},
                                 {"attributes":{"POSITION":0,"NORMAL":1,"COLOR_0":2},"indices":4}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                     {"bufferView":1,"componentType":5120,"normalized":true,"count":4,"type":"VEC3"},
                     {"bufferView":2,"componentType":5122,"normalized":true,"count":4,"type":"VEC4"},
                     {"bufferView":3,"componentType":5125,"count":3,"type":"SCALAR"},
                     {"bufferView":4,"componentType":5125,"count":3,"type":"SCALAR"}],
        "bufferViews":[)" +
        view(0, 0, 48, 12, 4, "ATTRIBUTES", "EXPONENTIAL") + "," + view(1, 48, 16, 4, 4, "ATTRIBUTES", "OCTAHEDRAL") +
        "," + view(2, 64, 32, 8, 4, "ATTRIBUTES", "QUATERNION") + "," + view(3, 96, 12, 4, 3, "INDICES", "NONE") + "," +
        view(4, 108, 12, 4, 3, "TRIANGLES", "NONE") + R"(],
        "buffers":[{"byteLength":)" +
        std::to_string(buffer.size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
        scene::testing::base64(buffer) +
        R"("},{"byteLength":120,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}]})";
    if (edit) edit(text);
    return text;
}

void replace(std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
}

TEST(GltfMeshoptTest, EveryModeAndFilterDecodesWhatMeshoptimizersEncoderWrote) {
    const auto s = scene::testing::loadWritten("sk_meshopt_square.gltf", squareFile());
    ASSERT_TRUE(s) << s.error();
    ASSERT_EQ(s->meshes.size(), 2u);
    const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, -1}};
    // Colour = the default albedo (0.7) times the decoded quaternion's x, y, z.
    const glm::vec3 colours[4] = {{0.7f, 0, 0}, {0, 0.7f, 0}, {0, 0, 0.7f}, {0.7f, 0, 0}};
    const std::vector<uint32_t> indices[2] = {{0, 1, 2}, {0, 2, 3}};
    for (size_t m = 0; m < 2; ++m) {
        const scene::Mesh& mesh = s->meshes[m];
        ASSERT_EQ(mesh.vertices.size(), 4u);
        EXPECT_EQ(mesh.indices, indices[m]) << "primitive " << m;
        for (size_t i = 0; i < 4; ++i) {
            EXPECT_EQ(mesh.vertices[i].position, corners[i]) << i; // exact at 24 bits
            EXPECT_NEAR(glm::distance(mesh.vertices[i].normal, glm::vec3(0, 1, 0)), 0.0f, 1e-6f) << i;
            EXPECT_NEAR(glm::distance(mesh.vertices[i].albedo, colours[i]), 0.0f, 2e-3f) << i; // 12-bit quaternions
        }
    }
}

TEST(GltfMeshoptTest, APlaceholderIsKnownByItsMissingDataWhateverItsMarkSays) {
    // A buffer with no uri that compressed views decode into is a placeholder, marked or not, and
    // a mark of the wrong type is no reason to stop (the JSON library throws on a mistyped read).
    for (const char* mark : {R"("fallback":"yes")", R"("fallback":false)", R"("other":1)"}) {
        SCOPED_TRACE(mark);
        const auto s = scene::testing::loadWritten(
            "sk_meshopt_mark.gltf", squareFile([&](std::string& t) { replace(t, R"("fallback":true)", mark); }));
        ASSERT_TRUE(s) << s.error();
        EXPECT_EQ(s->triangleCount(), 2u);
    }
}

TEST(GltfMeshoptTest, MalformedAndHostileViewsAreRefusedInOneLine) {
    const auto edit = [](const std::string& from, const std::string& to) {
        return [=](std::string& text) { replace(text, from, to); };
    };
    struct Case {
        const char* what;
        std::string text;
        const char* expected;
    };
    const std::vector<Case> cases = {
        {"a stream that is not meshopt's", squareFile({}, true),
         "buffer view 0 (EXT_meshopt_compression): its compressed bytes are not a valid ATTRIBUTES stream"},
        {"a view whose length is not count × stride",
         squareFile(edit(R"("byteOffset":0,"byteLength":48)", R"("byteOffset":0,"byteLength":60)")),
         "buffer view 0 (EXT_meshopt_compression): the view holds 60 bytes, not count × byteStride"},
        {"a million elements from a few bytes (no allocation: refused by the codec's bound)",
         squareFile([](std::string& t) {
             replace(t, R"("byteOffset":0,"byteLength":48)", R"("byteOffset":0,"byteLength":12000000)");
             replace(t, R"("byteStride":12,"count":4)", R"("byteStride":12,"count":1000000)");
             replace(t, R"("byteLength":120,)", R"("byteLength":12000120,)");
         }),
         "12000000 bytes cannot be decoded from"},
        {"a triangle list of four indices", squareFile([](std::string& t) {
             replace(t, R"("byteOffset":108,"byteLength":12)", R"("byteOffset":108,"byteLength":16)");
             replace(t, R"("count":3,"mode":"TRIANGLES")", R"("count":4,"mode":"TRIANGLES")");
         }),
         "TRIANGLES need a count divisible by 3"},
        {"a filter on indices",
         squareFile(edit(R"("mode":"INDICES","filter":"NONE")", R"("mode":"INDICES","filter":"OCTAHEDRAL")")),
         "INDICES take no filter"},
        {"a filter this library does not have", squareFile(edit(R"("filter":"QUATERNION")", R"("filter":"COLOR")")),
         "filter 'COLOR', which shadowkit cannot apply"},
        {"an unknown mode", squareFile(edit(R"("mode":"INDICES")", R"("mode":"STRIPS")")),
         "mode 'STRIPS' is none of ATTRIBUTES, TRIANGLES, INDICES"},
        {"an attribute stride of 6", squareFile([](std::string& t) {
             replace(t, R"("byteOffset":64,"byteLength":32)", R"("byteOffset":64,"byteLength":24)");
             replace(t, R"("byteStride":8,"count":4)", R"("byteStride":6,"count":4)");
         }),
         "ATTRIBUTES need a byteStride divisible by 4"},
        {"a view whose stride is not its extension's",
         squareFile(edit(R"("byteStride":4,"ext)", R"("byteStride":8,"ext)")),
         "the view's byteStride 8 differs from the extension's 4"},
        {"views past the placeholder's declared length",
         squareFile(edit(R"("byteLength":120,)", R"("byteLength":100,)")),
         "reaches past the 100 bytes its buffer declares"},
        {"compressed bytes past their buffer",
         squareFile(edit(R"("extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":0,)",
                         R"("extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":100000,)")),
         "its compressed bytes reach past buffer 0"},
        {"compressed bytes in the placeholder",
         squareFile(edit(R"("extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":0,)",
                         R"("extensions":{"EXT_meshopt_compression":{"buffer":1,"byteOffset":0,)")),
         "its compressed data lies in buffer 1, a placeholder"},
        {"an uncompressed view of the placeholder",
         squareFile(edit(R"("bufferViews":[)", R"("bufferViews":[{"buffer":1,"byteLength":4},)")),
         "reads buffer 1, a placeholder for compressed views, which holds no data of its own"},
        {"a count that is not a whole number",
         squareFile(edit(R"("count":4,"mode":"ATTRIBUTES","filter":"EXPONENTIAL")",
                         R"("count":4.5,"mode":"ATTRIBUTES","filter":"EXPONENTIAL")")),
         "must be whole numbers"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        const auto s = scene::testing::loadWritten("sk_meshopt_bad.gltf", c.text);
        ASSERT_FALSE(s) << "accepted";
        EXPECT_NE(s.error().find("sk_meshopt_bad.gltf: buffer view"), std::string::npos) << s.error();
        EXPECT_NE(s.error().find(c.expected), std::string::npos) << s.error();
        EXPECT_EQ(s.error().find('\n'), std::string::npos) << s.error();
    }
}

} // namespace
