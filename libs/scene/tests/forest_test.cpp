#include "shadowkit/scene/forest.h"

#include <gtest/gtest.h>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {
ForestOptions tiny(uint64_t seed = 1) {
    ForestOptions o;
    o.seed = seed;
    o.trees = 200;
    o.terrainSize = 200;
    o.terrainResolution = 32;
    o.rocks = 5;
    o.buildings = 3;
    o.movers = 2;
    return o;
}
const MeshBatch* batchNamed(const Scene& s, const std::string& prefix, size_t nth = 0) {
    for (const MeshBatch& b : s.batches)
        if (s.meshes[b.mesh].name.rfind(prefix, 0) == 0 && nth-- == 0) return &b;
    return nullptr;
}
} // namespace

TEST(ForestTest, SameSeedGivesTheSameForestAndAnotherSeedAnotherOne) {
    const Scene a = makeForest(tiny(1)), b = makeForest(tiny(1)), c = makeForest(tiny(2));
    ASSERT_EQ(a.batches.size(), b.batches.size());
    for (size_t i = 0; i < a.batches.size(); ++i) EXPECT_EQ(a.batches[i].worldFromObject, b.batches[i].worldFromObject);
    EXPECT_EQ(a.terrain->heights, b.terrain->heights);
    EXPECT_NE(a.terrain->heights, c.terrain->heights);
    EXPECT_NE(batchNamed(a, "conifer")->worldFromObject, batchNamed(c, "conifer")->worldFromObject);
}

TEST(ForestTest, DefaultForestMatchesTheStandardScene) {
    const Scene s = makeForest(ForestOptions{});
    // docs/references.md, evaluation §1: 1024 m terrain, >= 256x256 quads, hills 0-30 m, 10,000 trees 6-20 m
    // of >= 200 triangles, a few dozen large casters, a handful of movers.
    const core::Aabb terrain = s.meshes[batchNamed(s, "terrain")->mesh].osBounds;
    EXPECT_NEAR(terrain.extent().x, 1024.0, 1e-3);
    EXPECT_NEAR(terrain.extent().z, 1024.0, 1e-3);
    EXPECT_GE(s.meshes[batchNamed(s, "terrain")->mesh].triangleCount(), 2u * 256u * 256u);
    EXPECT_GE(terrain.min.y, -1e-3);
    EXPECT_LE(terrain.max.y, 30.0 + 1e-3);
    EXPECT_GT(terrain.extent().y, 10.0); // hills, not a plane

    size_t trees = 0;
    for (const char* species : {"conifer", "broadleaf"})
        for (size_t nth = 0; const MeshBatch* b = batchNamed(s, species, nth); ++nth) {
            EXPECT_GE(s.meshes[b->mesh].triangleCount(), 200u) << species;
            trees += b->worldFromObject.size();
            for (const glm::mat4& m : b->worldFromObject) {
                const double height = core::transformBounds(core::Mat4(m), s.meshes[b->mesh].osBounds).extent().y;
                EXPECT_GE(height, 6.0 - 1e-3);
                EXPECT_LE(height, 20.0 + 1e-3);
                // Standing on the ground: the trunk base is just below the terrain surface.
                const double ground = s.terrain->heightAt(m[3].x, m[3].z);
                EXPECT_NEAR(m[3].y, ground - 0.1, 1e-3);
            }
        }
    EXPECT_EQ(trees, 10000u);
    EXPECT_EQ(batchNamed(s, "rock")->worldFromObject.size() + batchNamed(s, "building")->worldFromObject.size(), 36u);
    EXPECT_TRUE(batchNamed(s, "mover")->dynamic);
    // Instanced: a handful of batches, not one per tree.
    EXPECT_LE(s.batches.size(), 10u);
}

TEST(ForestTest, OptionsOutOfRangeAreNamed) {
    ForestOptions o;
    o.trees = -1;
    ASSERT_FALSE(validate(o));
    EXPECT_NE(validate(o).error().find("trees"), std::string::npos);
    o = ForestOptions{};
    o.terrainSize = 0;
    EXPECT_NE(validate(o).error().find("terrain size"), std::string::npos);
    o = ForestOptions{};
    o.impostors = true; // the simple forest's blobs have no far levels to stand in for
    EXPECT_NE(validate(o).error().find("impostors"), std::string::npos);
    o.kind = ForestKind::Leafy;
    EXPECT_TRUE(validate(o));
    EXPECT_TRUE(validate(ForestOptions{}));
}

TEST(ForestTest, ZeroTreesGivesTerrainAndCastersOnly) {
    ForestOptions o = tiny();
    o.trees = 0;
    const Scene s = makeForest(o);
    EXPECT_EQ(batchNamed(s, "conifer"), nullptr);
    for (const MeshBatch& b : s.batches) EXPECT_FALSE(b.worldFromObject.empty());
}

TEST(HeightfieldTest, HeightAtInterpolatesTheMeshTriangles) {
    Heightfield f;
    f.size = 2.0;
    f.resolution = 1;
    f.heights = {0.0f, 1.0f, 2.0f, 4.0f}; // (x=-1,z=-1), (1,-1), (-1,1), (1,1)
    EXPECT_NEAR(f.heightAt(-1, -1), 0.0, 1e-12);
    EXPECT_NEAR(f.heightAt(1, 1), 4.0, 1e-12);
    EXPECT_NEAR(f.heightAt(0, 0), 2.0, 1e-12); // on the diagonal: mean of the two ends
    EXPECT_NEAR(f.heightAt(1, -1), 1.0, 1e-12);
    EXPECT_NEAR(f.heightAt(50, 50), 4.0, 1e-12); // clamped outside
}
