#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_lod.h"

#include <gtest/gtest.h>

using namespace shadowkit::scene;

namespace {

const Mesh& meshNamed(const Scene& s, const std::string& name) {
    for (const Mesh& m : s.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh " + name);
}

void expectValidChain(const Mesh& mesh, const MeshLods& lods, const std::vector<LodLevel>& chain,
                      const std::string& what) {
    ASSERT_FALSE(chain.empty()) << what;
    EXPECT_EQ(chain[0].indexCount, mesh.indices.size()) << what << ": level 0 is the full mesh";
    EXPECT_EQ(chain[0].objectError, 0.0f) << what;
    for (size_t l = 0; l < chain.size(); ++l) {
        const LodLevel& level = chain[l];
        ASSERT_LE(size_t(level.firstIndex) + level.indexCount, lods.indices.size()) << what;
        EXPECT_EQ(level.indexCount % 3, 0u) << what;
        for (uint32_t i = level.firstIndex; i < level.firstIndex + level.indexCount; ++i)
            ASSERT_LT(lods.indices[i], mesh.vertices.size()) << what;
        if (l == 0) continue;
        // Each level saves at least a fifth of its predecessor and is allowed a larger error.
        EXPECT_LE(double(level.indexCount), 0.8 * chain[l - 1].indexCount) << what << " level " << l;
        EXPECT_GE(level.objectError, chain[l - 1].objectError) << what << " level " << l;
        EXPECT_GT(level.indexCount, 0u) << what << " level " << l;
    }
}

} // namespace

TEST(MeshLodTest, ForestMeshesGetValidChainsAndShadowChainsGoFurther) {
    ForestOptions o;
    o.trees = 50;
    o.terrainResolution = 256;
    const Scene forest = makeForest(o);
    for (const Mesh& mesh : forest.meshes) {
        const MeshLods lods = buildLods(mesh);
        expectValidChain(mesh, lods, lods.camera, mesh.name + " camera");
        expectValidChain(mesh, lods, lods.shadow, mesh.name + " shadow");
    }
    // The conifer's cone layers are open surfaces with split normals: with its seams the
    // simplifier stops early, welded by position (what a depth map sees) it goes further.
    const MeshLods conifer = buildLods(meshNamed(forest, "conifer"));
    EXPECT_LT(conifer.shadow.back().indexCount, conifer.camera.back().indexCount);
    EXPECT_GE(conifer.shadow.size(), 2u);
    EXPECT_GE(buildLods(meshNamed(forest, "broadleaf")).camera.size(), 3u);
    // The terrain (131,072 triangles, one instance) keeps its one level.
    const MeshLods terrain = buildLods(meshNamed(forest, "terrain"));
    EXPECT_EQ(terrain.camera.size(), 1u);
    EXPECT_EQ(terrain.shadow.size(), 1u);
}

TEST(MeshLodTest, EmptyMeshHasOneEmptyLevel) {
    const MeshLods lods = buildLods(Mesh{});
    ASSERT_EQ(lods.camera.size(), 1u);
    EXPECT_EQ(lods.camera[0].indexCount, 0u);
    EXPECT_EQ(lods.shadow.size(), 1u);
}
