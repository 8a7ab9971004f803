// Foliage levels (foliage_levels.h): the alpha-tested meshes a loaded scene brings without levels
// get the leafy trees' chain of billboard clouds, their coverage read as the material says.
#include "shadowkit/scene/foliage_levels.h"
#include "shadowkit/scene/leafy_trees.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <filesystem>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// A scene as a loader makes it: a broadleaf tree's cards (5,200 triangles) under a masked
// material reading the leaf atlas, the same tree's wood opaque, and a handful of masked cards.
Scene loadedTree() {
    Scene s;
    s.textures.push_back(makeLeafAtlas());
    s.materials.push_back(leafMaterial(0));
    LeafyTree tree = makeLeafyTree(TreeSpecies::Broadleaf, 1);
    tree.leaves.authoredLods.clear(); // a glTF has no card levels
    tree.leaves.material = 0;
    Mesh few;
    for (int c = 0; c < 8; ++c)
        addCard(few, glm::translate(glm::mat4(1.0f), glm::vec3(float(c), 0, 0)), {0.0f, 0.25f}, {0.25f, 0.0f},
                glm::vec3(1.0f));
    few.material = 0;
    few.computeBounds();
    s.meshes = {tree.leaves, tree.wood, few};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::mat4(1.0f)}, false}, {2, {glm::mat4(1.0f)}, false}};
    return s;
}

} // namespace

TEST(FoliageLevelsTest, AMaskedMeshWithoutLevelsGetsTheCloudChainAndNothingElseChanges) {
    Scene s = loadedTree();
    const Scene before = s;
    EXPECT_EQ(addFoliageClouds(s), 1);
    const Mesh& leaves = s.meshes[0];
    ASSERT_EQ(leaves.authoredLods.size(), 3u);
    ASSERT_EQ(s.textures.size(), 4u);
    for (size_t l = 0; l < 3; ++l) {
        const AuthoredLod& level = leaves.authoredLods[l];
        EXPECT_EQ(level.texture, int32_t(1 + l)) << l << ": a texture of its own";
        EXPECT_TRUE(level.keepsCoverage) << l;
        // The loaded chain, not the species' finer one: 16, 8 and 4 slabs in 1024 × 512 texels
        // and down, a quarter of the species' memory for each of what may be hundreds of meshes.
        EXPECT_EQ(s.textures[1 + l].image.width, 1024 >> l) << l;
        EXPECT_EQ(s.textures[1 + l].image.height, 512 >> l) << l;
        if (l > 0) {
            EXPECT_GT(level.objectError, leaves.authoredLods[l - 1].objectError) << l;
            EXPECT_LT(level.indices.size(), leaves.authoredLods[l - 1].indices.size()) << l;
        }
        for (const uint32_t i : level.indices) ASSERT_GE(i, before.meshes[0].vertices.size()) << l << ": its planes";
    }
    EXPECT_EQ(leaves.indices, before.meshes[0].indices) << "the full mesh stays level 0";
    EXPECT_EQ(s.meshes[1].authoredLods.size(), 0u) << "opaque wood: the simplifier's levels";
    EXPECT_EQ(s.meshes[2].authoredLods.size(), 0u) << "16 triangles of cards: cheaper than a cloud";
    EXPECT_EQ(s.textures[0].image.rgba, before.textures[0].image.rgba) << "the material's texture is only read";
    // Levels of its own now: a second pass adds none.
    EXPECT_EQ(addFoliageClouds(s), 0);
    EXPECT_EQ(s.textures.size(), 4u);
}

// Coverage is read as the material says: through the texture's wrap modes, times its alpha
// factor. A card whose uvs run over its cell twice, under Repeat, shows the cell twice; under
// ClampToEdge the second half reads the atlas's edge column, which is open.
TEST(FoliageLevelsTest, CoverageFollowsTheTexturesWrapAndTheMaterialsAlphaFactor) {
    auto coverageWith = [](TextureWrap wrap, float alphaFactor) {
        Texture texture = makeLeafAtlas();
        texture.wrapS = texture.wrapT = wrap;
        Mesh card;
        // uvs from (0.75, 0.25) to (1.25, 0): the last cell of the first row, then (wrapped) the first.
        addCard(card, glm::scale(glm::mat4(1.0f), glm::vec3(0.4f)), {0.75f, 0.25f}, {1.25f, 0.0f}, glm::vec3(1.0f));
        card.computeBounds();
        const CloudSource source{&card, card.indices, &texture.image, texture.wrapS, texture.wrapT, alphaFactor};
        Image target(256, 256);
        return bakeBillboardCloud(std::span(&source, 1), target, {0, 0, 256, 256}).coverage;
    };
    const double repeat = coverageWith(TextureWrap::Repeat, 1.0f);
    const double clamp = coverageWith(TextureWrap::ClampToEdge, 1.0f);
    EXPECT_GT(repeat, 0.2);
    EXPECT_LT(clamp, 0.75 * repeat) << "half the card reads the open edge column";
    EXPECT_EQ(coverageWith(TextureWrap::Repeat, 0.0f), 0.0) << "alpha factor 0: nothing passes the cutoff";
}

// What a loader returns: a glTF written by the exporter (which keeps no levels) comes back with
// clouds on its leaves.
TEST(FoliageLevelsTest, ALoadedGltfsLeavesComeBackWithClouds) {
    const Scene s = loadedTree();
    const std::filesystem::path file = shadowkit::test_support::scratchDir() / "shadowkit_foliage_levels.glb";
    ASSERT_TRUE(exportScene(s, file));
    auto loaded = loadScene(file);
    std::filesystem::remove(file);
    ASSERT_TRUE(loaded) << loaded.error();
    int withClouds = 0;
    for (const Mesh& mesh : loaded->meshes) {
        const Material* material = loaded->materialOf(mesh);
        if (material && material->alphaTested() && mesh.triangleCount() >= 256) {
            EXPECT_EQ(mesh.authoredLods.size(), 3u) << mesh.name;
            ++withClouds;
        }
    }
    EXPECT_EQ(withClouds, 1);
}
