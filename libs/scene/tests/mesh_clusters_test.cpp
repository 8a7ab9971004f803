// Triangle clusters of a large mesh: the same triangles (winding kept), each cluster's box
// holds its triangles, and clusters are compact — what lets a page draw a sliver of terrain.
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// A triangle as its three indices rotated so the smallest comes first: the winding kept.
std::array<uint32_t, 3> canonical(const uint32_t* t) {
    const int first = int(std::min_element(t, t + 3) - t);
    return {t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
}

} // namespace

TEST(MeshClustersTest, TheSameTrianglesInCompactClustersEachInsideItsBox) {
    ForestOptions options;
    options.trees = 0;
    options.terrainResolution = 128;
    const Scene forest = makeForest(options);
    const Mesh& terrain = forest.meshes[forest.batches[0].mesh];
    ASSERT_EQ(terrain.name, "terrain");
    std::vector<uint32_t> indices = terrain.indices;
    const uint32_t offset = 300; // as if the range started further into a buffer
    const std::vector<TriangleCluster> clusters = clusterTriangles(terrain, indices, offset, 1024);

    std::vector<std::array<uint32_t, 3>> before, after;
    for (size_t t = 0; t < terrain.indices.size(); t += 3) {
        before.push_back(canonical(&terrain.indices[t]));
        after.push_back(canonical(&indices[t]));
    }
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    EXPECT_EQ(before, after);

    ASSERT_EQ(clusters.size(), (terrain.triangleCount() + 1023) / 1024);
    uint32_t next = offset;
    double clusterArea = 0.0;
    for (const TriangleCluster& c : clusters) {
        EXPECT_EQ(c.firstIndex, next);
        next += c.indexCount;
        for (uint32_t i = c.firstIndex - offset; i < c.firstIndex - offset + c.indexCount; ++i)
            EXPECT_TRUE(c.osBounds.contains(core::Vec3(terrain.vertices[indices[i]].position), 1e-6));
        const core::Vec3 e = c.osBounds.extent();
        clusterArea += e.x * e.z;
    }
    EXPECT_EQ(next, offset + uint32_t(indices.size()));
    // Compact: together the clusters' footprints cover the terrain about once, not once each.
    const core::Vec3 whole = terrain.osBounds.extent();
    EXPECT_LT(clusterArea, 2.0 * whole.x * whole.z);
}
