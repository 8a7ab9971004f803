// The leafy forest: trees of branches and alpha-tested leaf cards (leafy_trees.h), as a
// second standard scene.
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/leafy_trees.h"
#include "shadowkit/scene/mesh_lod.h"
#include "shadowkit/scene/texture_mips.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

ForestOptions smallLeafy(uint64_t seed = 1) {
    ForestOptions o;
    o.kind = ForestKind::Leafy;
    o.seed = seed;
    o.trees = 60;
    o.terrainSize = 120;
    o.terrainResolution = 16;
    o.rocks = 2;
    o.buildings = 1;
    o.movers = 1;
    return o;
}

bool sameMesh(const Mesh& a, const Mesh& b) {
    return a.indices == b.indices && a.vertices.size() == b.vertices.size() &&
           std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vertex)) == 0;
}

// The atlas cell (column, row) a uv lies in.
glm::ivec2 cellOf(glm::vec2 uv) { return glm::ivec2(glm::floor(uv * float(kLeafAtlasCells))); }

} // namespace

TEST(LeafyTreesTest, EachSpeciesIsFiveToTwentyThousandTrianglesOfWoodAndCardsAboutAUnitHigh) {
    for (int k = 0; k < kTreeSpeciesCount; ++k) {
        const auto species = static_cast<TreeSpecies>(k);
        const LeafyTree tree = makeLeafyTree(species, 1);
        const size_t triangles = tree.wood.triangleCount() + tree.leaves.triangleCount();
        EXPECT_GE(triangles, 5000u) << k;
        EXPECT_LE(triangles, 20000u) << k;
        EXPECT_GT(tree.wood.triangleCount(), 100u) << k << ": a trunk, boughs or stems";
        // Cards, 4 vertices and 2 triangles each, every level's in the vertex buffer.
        size_t lodTriangles = 0;
        for (const AuthoredLod& lod : tree.leaves.authoredLods) lodTriangles += lod.indices.size() / 3;
        EXPECT_EQ(tree.leaves.vertices.size(), 2 * (tree.leaves.triangleCount() + lodTriangles)) << k;
        EXPECT_NEAR(tree.wood.osBounds.min.y, 0.0, 0.02) << k << ": standing on its base";
        EXPECT_GT(std::max(tree.wood.osBounds.max.y, tree.leaves.osBounds.max.y), 0.85) << k;
        EXPECT_LT(std::max(tree.wood.osBounds.max.y, tree.leaves.osBounds.max.y), 1.15) << k;
        // Every card shows one whole cell of its species' rows, corner to corner.
        const int firstRow = species == TreeSpecies::Broadleaf ? 0 : species == TreeSpecies::Conifer ? 2 : 3;
        const int lastRow = species == TreeSpecies::Broadleaf ? 1 : firstRow;
        for (size_t v = 0; v < tree.leaves.vertices.size(); v += 4) {
            const glm::vec2 uvMin = tree.leaves.vertices[v].uv, uvMax = tree.leaves.vertices[v + 2].uv;
            const glm::ivec2 cell = cellOf(0.5f * (uvMin + uvMax));
            ASSERT_GE(cell.y, firstRow) << k;
            ASSERT_LE(cell.y, lastRow) << k;
            ASSERT_NEAR(std::abs(uvMax.x - uvMin.x), 1.0f / kLeafAtlasCells, 1e-6f);
        }
    }
}

TEST(LeafyTreesTest, CardLevelsHalveTheCardsAndKeepTheLeafArea) {
    for (int k = 0; k < kTreeSpeciesCount; ++k) {
        const LeafyTree tree = makeLeafyTree(static_cast<TreeSpecies>(k), 1);
        // A card's area from its triangles.
        auto area = [&](const std::vector<uint32_t>& indices) {
            double sum = 0.0;
            for (size_t i = 0; i + 2 < indices.size(); i += 3) {
                const glm::vec3 a = tree.leaves.vertices[indices[i]].position,
                                b = tree.leaves.vertices[indices[i + 1]].position,
                                c = tree.leaves.vertices[indices[i + 2]].position;
                sum += 0.5 * glm::length(glm::cross(b - a, c - a));
            }
            return sum;
        };
        ASSERT_EQ(tree.leaves.authoredLods.size(), 2u) << k;
        const double full = area(tree.leaves.indices);
        size_t previous = tree.leaves.indices.size();
        float previousError = 0.0f;
        for (const AuthoredLod& lod : tree.leaves.authoredLods) {
            EXPECT_NEAR(double(lod.indices.size()), 0.5 * double(previous), 6.0) << k; // half the cards (rounded up)
            EXPECT_NEAR(area(lod.indices) / full, 1.0, 0.05) << k;                     // the same leaf area
            EXPECT_GT(lod.objectError, previousError) << k;                            // coarser, larger error
            for (uint32_t i : lod.indices) ASSERT_LT(i, tree.leaves.vertices.size());
            previous = lod.indices.size();
            previousError = lod.objectError;
        }
        // The levels build into two chains that are the same (mesh_lod.h).
        const MeshLods lods = buildLods(tree.leaves);
        ASSERT_EQ(lods.camera.size(), 3u);
        EXPECT_EQ(lods.shadow.size(), 3u);
        EXPECT_EQ(lods.camera[2].indexCount, tree.leaves.authoredLods[1].indices.size());
    }
}

// Every level of the leaves, cards and clouds, lists its quads highest first (mesh_builder.h,
// orderQuadsHighestFirst: a shadow pass then rejects the leaves the upper ones hide), each quad
// whole — its two triangles together, as they were built.
TEST(LeafyTreesTest, EveryLevelsQuadsComeHighestFirst) {
    const Texture atlas = makeLeafAtlas();
    for (int k = 0; k < kTreeSpeciesCount; ++k) {
        LeafyTree tree = makeLeafyTree(static_cast<TreeSpecies>(k), 3);
        const size_t cardLevels = tree.leaves.authoredLods.size();
        ASSERT_FALSE(addFarLevels(tree, atlas.image, 1).empty()) << k;
        std::vector<std::vector<uint32_t>> levels{tree.leaves.indices};
        for (const AuthoredLod& level : tree.leaves.authoredLods) levels.push_back(level.indices);
        ASSERT_GE(levels.size(), 5u) << k << ": the cards, then four clouds (" << cardLevels << " card levels before)";
        for (size_t l = 0; l < levels.size(); ++l) {
            const std::vector<uint32_t>& indices = levels[l];
            ASSERT_EQ(indices.size() % 6, 0u) << k << " level " << l;
            float previous = INFINITY;
            for (size_t q = 0; q < indices.size() / 6; ++q) {
                const uint32_t* quad = &indices[6 * q];
                // Two triangles sharing an edge: the second starts at the first's first corner
                // and takes its third (addCard's and the clouds' a, b, c / a, c, d).
                ASSERT_TRUE(quad[3] == quad[0] && quad[4] == quad[2]) << k << " level " << l << " quad " << q;
                float height = 0.0f;
                for (int i = 0; i < 6; ++i) height += tree.leaves.vertices[quad[i]].position.y;
                EXPECT_LE(height, previous) << k << " level " << l << " quad " << q;
                previous = height;
            }
        }
    }
}

TEST(LeafyTreesTest, TheSameSeedGivesTheSameTreeAndAnotherSeedAnotherOne) {
    for (int k = 0; k < kTreeSpeciesCount; ++k) {
        const auto species = static_cast<TreeSpecies>(k);
        const LeafyTree a = makeLeafyTree(species, 7), b = makeLeafyTree(species, 7), c = makeLeafyTree(species, 8);
        EXPECT_TRUE(sameMesh(a.wood, b.wood) && sameMesh(a.leaves, b.leaves)) << k;
        EXPECT_FALSE(sameMesh(a.leaves, c.leaves)) << k;
    }
}

TEST(LeafyTreesTest, TheAtlasCellsAreLeavesWithHolesAndOpenBorders) {
    const Texture atlas = makeLeafAtlas();
    ASSERT_EQ(atlas.image.width, 512);
    ASSERT_EQ(atlas.image.height, 512);
    EXPECT_EQ(makeLeafAtlas().image.rgba, atlas.image.rgba); // deterministic
    const int cell = atlas.image.width / kLeafAtlasCells;
    for (int cy = 0; cy < kLeafAtlasCells; ++cy)
        for (int cx = 0; cx < kLeafAtlasCells; ++cx) {
            Image one(cell, cell);
            for (int y = 0; y < cell; ++y)
                std::memcpy(one.pixel(0, y), atlas.image.pixel(cx * cell, cy * cell + y), size_t(cell) * 4);
            const double coverage = alphaCoverage(one, 0.5f);
            EXPECT_GT(coverage, 0.08) << cx << "," << cy << ": leaves";
            EXPECT_LT(coverage, 0.7) << cx << "," << cy << ": holes between them";
            for (int i = 0; i < cell; ++i) // a bilinear lookup of one cell never reads its neighbour
                ASSERT_TRUE(one.pixel(i, 0)[3] == 0 && one.pixel(0, i)[3] == 0 && one.pixel(i, cell - 1)[3] == 0 &&
                            one.pixel(cell - 1, i)[3] == 0);
        }
}

TEST(LeafyForestTest, TreesStandWhereTheSimpleForestsDoEachAsWoodAndMaskedLeaves) {
    const Scene leafy = makeForest(smallLeafy());
    ForestOptions simpleOptions = smallLeafy();
    simpleOptions.kind = ForestKind::Simple;
    const Scene simple = makeForest(simpleOptions);
    ASSERT_EQ(leafy.materials.size(), 1u);
    // The atlas, then each species' four billboard clouds, each level reading a texture of its own.
    ASSERT_EQ(leafy.textures.size(), 1u + 4u * kTreeSpeciesCount);
    std::vector<int32_t> levelTextures;
    for (const Mesh& m : leafy.meshes)
        for (const AuthoredLod& level : m.authoredLods)
            if (level.texture >= 0) levelTextures.push_back(level.texture);
    std::sort(levelTextures.begin(), levelTextures.end());
    std::vector<int32_t> clouds(4u * kTreeSpeciesCount);
    std::iota(clouds.begin(), clouds.end(), 1);
    EXPECT_EQ(levelTextures, clouds);
    EXPECT_EQ(leafy.materials[0].alphaMode, AlphaMode::Mask);
    EXPECT_TRUE(leafy.materials[0].doubleSided);
    EXPECT_EQ(leafy.materials[0].baseColorTexture, 0);
    // Tree positions: the translations of every tree, in either forest.
    auto treeSpots = [](const Scene& s, bool leavesOnly) {
        std::vector<std::pair<float, float>> spots;
        for (const MeshBatch& b : s.batches) {
            const Mesh& m = s.meshes[b.mesh];
            const bool tree = m.name.find("conifer") != std::string::npos ||
                              m.name.find("broadleaf") != std::string::npos ||
                              m.name.find("shrub") != std::string::npos;
            if (!tree || (leavesOnly && m.material < 0)) continue;
            for (const glm::mat4& t : b.worldFromObject) spots.emplace_back(t[3].x, t[3].z);
        }
        std::sort(spots.begin(), spots.end());
        return spots;
    };
    EXPECT_EQ(treeSpots(leafy, true), treeSpots(simple, false));
    size_t leafBatches = 0;
    for (const MeshBatch& b : leafy.batches) {
        const Mesh& m = leafy.meshes[b.mesh];
        if (m.material < 0) continue;
        ++leafBatches;
        EXPECT_TRUE(leafy.materialOf(m)->alphaTested());
        // Its wood is the batch before it, with the same placements.
        const MeshBatch& wood = (&b)[-1];
        EXPECT_EQ(wood.worldFromObject, b.worldFromObject) << m.name;
    }
    EXPECT_EQ(leafBatches, size_t(kTreeSpeciesCount));
    const Scene again = makeForest(smallLeafy()), other = makeForest(smallLeafy(2));
    for (size_t i = 0; i < leafy.batches.size(); ++i)
        EXPECT_EQ(leafy.batches[i].worldFromObject, again.batches[i].worldFromObject);
    EXPECT_NE(treeSpots(leafy, true), treeSpots(other, true));
}
