// A town of meshes placed once each loads as a few tiles of neighbours (static batching,
// mesh_merge.cpp) that hold the same triangles, wound the same way; what is not merged — an
// alpha-tested mesh, one placed twice, a scene of few meshes — is left as it was.
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// `meshes` distinct meshes (each names the same upward-facing triangle), one node each on a
// grid 30 m apart; node 0 mirrored in x; meshes 1–10 alpha-tested (MASK); the last mesh placed
// by a second node too. `lifted`: an animation moves node kLiftedNode from where it stands to
// 10 m above it over a second.
constexpr int kLiftedNode = 20;

std::string townGltf(int meshes, bool lifted = false) {
    const int side = int(std::ceil(std::sqrt(double(meshes))));
    const float x = float(30 * (kLiftedNode % side)), z = float(30 * (kLiftedNode / side));
    const float data[] = {0, 0, 0, 0, 0, 4, 4, 0, 0, /* times */ 0, 1, /* translations */ x, 0, z, x, 10, z};
    std::vector<unsigned char> buffer(sizeof data);
    std::memcpy(buffer.data(), data, sizeof data);
    std::ostringstream text;
    text << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)";
    for (int n = 0; n <= meshes; ++n) text << (n ? "," : "") << n;
    text << R"(]}],"nodes":[)";
    for (int n = 0; n < meshes; ++n)
        text << R"({"mesh":)" << n << R"(,"translation":[)" << 30 * (n % side) << ",0," << 30 * (n / side) << "]"
             << (n == 0 ? R"(,"scale":[-1,1,1])" : "") << "},";
    text << R"({"mesh":)" << meshes - 1 << R"(,"translation":[-50,0,-50]}],"meshes":[)";
    for (int m = 0; m < meshes; ++m)
        text << (m ? "," : "") << R"({"primitives":[{"attributes":{"POSITION":0})"
             << (m >= 1 && m <= 10 ? R"(,"material":0)" : "") << "}]}";
    text << R"(],"materials":[{"alphaMode":"MASK"}],)";
    if (lifted)
        text << R"("animations":[{"samplers":[{"input":1,"output":2}],"channels":[{"sampler":0,"target":{"node":)"
             << kLiftedNode << R"(,"path":"translation"}}]}],)";
    text << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[4,0,4]},)"
         << R"({"bufferView":0,"byteOffset":36,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},)"
         << R"({"bufferView":0,"byteOffset":44,"componentType":5126,"count":2,"type":"VEC3"}],)"
         << R"("bufferViews":[{"buffer":0,"byteLength":68}],"buffers":[{"byteLength":68,)"
         << R"("uri":"data:application/octet-stream;base64,)" << scene::testing::base64(buffer) << "\"}]}";
    return text.str();
}

Scene loadTown(int meshes, bool merge, bool lifted = false) {
    auto scene =
        scene::testing::loadWritten("shadowkit_town.gltf", townGltf(meshes, lifted), {.mergeSmallMeshes = merge});
    EXPECT_TRUE(scene) << scene.error();
    return scene ? std::move(*scene) : Scene{};
}

// Every placed triangle in world coordinates (to the millimetre), each rotated to start at its
// least corner so that the order of its corners — its winding — is kept; sorted.
using WoundTriangle = std::array<std::array<long, 3>, 3>;
std::vector<WoundTriangle> woundTriangles(const Scene& s) {
    std::vector<WoundTriangle> out;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject) {
            const Mesh& mesh = s.meshes[batch.mesh];
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                WoundTriangle t;
                for (int k = 0; k < 3; ++k) {
                    const glm::dvec3 p =
                        s.wsOrigin +
                        glm::dvec3(m * glm::vec4(mesh.vertices[mesh.indices[i + size_t(k)]].position, 1.0f));
                    t[size_t(k)] = {std::lround(p.x * 1000), std::lround(p.y * 1000), std::lround(p.z * 1000)};
                }
                std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
                out.push_back(t);
            }
        }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST(MeshMergeTest, ATownOfMeshesPlacedOnceLoadsAsAFewTilesOfNeighboursDrawingTheSameTriangles) {
    constexpr int kMeshes = 1500;
    const Scene merged = loadTown(kMeshes, true), apart = loadTown(kMeshes, false);
    ASSERT_EQ(apart.batches.size(), size_t(kMeshes));
    // 1,489 opaque meshes placed once in tiles of at most 256 (halved until they fit: 8), the 10
    // alpha-tested ones and the one placed twice as they were.
    constexpr size_t kMerged = kMeshes - 11;
    EXPECT_EQ(merged.triangleCount(), apart.triangleCount());
    EXPECT_EQ(woundTriangles(merged), woundTriangles(apart)); // the same triangles, wound alike

    size_t tiles = 0, alphaTested = 0, placedTwice = 0;
    const double townDiagonal = merged.localBounds().diagonal();
    for (const MeshBatch& batch : merged.batches) {
        const Mesh& mesh = merged.meshes[batch.mesh];
        if (batch.worldFromObject.size() == 2) ++placedTwice;
        if (const Material* material = merged.materialOf(mesh); material && material->alphaTested()) ++alphaTested;
        if (mesh.name.starts_with("tile ")) {
            ++tiles;
            EXPECT_EQ(batch.worldFromObject, std::vector<glm::mat4>{glm::mat4(1.0f)});
            EXPECT_LE(mesh.triangleCount(), 256u);
            // Neighbours: a tile spans a fraction of the town (Morton order), not the whole of it.
            EXPECT_LT(mesh.osBounds.diagonal(), 0.6 * townDiagonal) << mesh.name;
        }
    }
    EXPECT_GE(tiles, (kMerged + 255) / 256);
    EXPECT_LE(tiles, 2 * ((kMerged + 255) / 256)); // a median split at most halves a tile's fill
    EXPECT_EQ(merged.batches.size(), tiles + 10 + 1);
    EXPECT_EQ(alphaTested, 10u);
    EXPECT_EQ(placedTwice, 1u);
}

TEST(MeshMergeTest, ASceneOfFewerMeshesIsLeftAsItWas) {
    const Scene few = loadTown(1000, true);
    EXPECT_EQ(few.batches.size(), 1000u); // the corpus's largest has 55 batches
    EXPECT_EQ(woundTriangles(few), woundTriangles(loadTown(1000, false)));
}

// A town with one building that moves (a glTF animation: a track of a dynamic batch) is merged
// all the same; the moving building is left as it was, and its track still names its batch.
TEST(MeshMergeTest, ATownWithAMovingBuildingIsMergedAndItsTrackStillNamesIt) {
    constexpr int kMeshes = 1500;
    Scene merged = loadTown(kMeshes, true, true);
    const Scene apart = loadTown(kMeshes, false, true);
    ASSERT_EQ(merged.tracks.size(), 1u);
    EXPECT_LT(merged.batches.size(), size_t(kMeshes) / 10) << "merged, though it has a track";
    EXPECT_EQ(woundTriangles(merged), woundTriangles(apart));
    const Track& track = merged.tracks[0];
    ASSERT_LT(track.batch, merged.batches.size());
    const MeshBatch& moving = merged.batches[track.batch];
    EXPECT_TRUE(moving.dynamic);
    EXPECT_EQ(merged.meshes[moving.mesh].triangleCount(), 1u) << "its own triangle, not a tile";
    animate(merged, 0.5); // half way up (at t = 1 the one-second animation loops back to its start)
    const int side = int(std::ceil(std::sqrt(double(kMeshes))));
    const glm::dvec3 lifted(30 * (kLiftedNode % side), 5, 30 * (kLiftedNode / side));
    const glm::dvec3 at = merged.wsOrigin + glm::dvec3(moving.worldFromObject[track.instance][3]);
    EXPECT_LT(glm::distance(at, lifted), 1e-3);
}
