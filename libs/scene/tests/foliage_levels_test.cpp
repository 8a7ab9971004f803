// Foliage levels (foliage_levels.h): the alpha-tested meshes a loaded scene brings without levels
// get the leafy trees' chain of billboard clouds, their coverage read as the material says.
#include "shadowkit/scene/foliage_levels.h"
#include "shadowkit/scene/leafy_trees.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/mesh_lod.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
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

TEST(FoliageLevelsTest, AnImpostorStandsInForTheCoarsestCloudInTheShadowChainAlone) {
    // appendImpostorLevel: the shadow chain's last level becomes the impostor's card, the camera's
    // keeps the coarsest cloud; every other level is in both, and each chain's errors still grow
    // (a pass takes the coarsest level within its bound by walking them in order).
    const Texture atlas = makeLeafAtlas();
    LeafyTree tree = makeLeafyTree(TreeSpecies::Conifer, 1);
    const std::vector<BakedCloud> clouds = addFarLevels(tree, atlas.image, 1);
    const MeshLods before = buildLods(tree.leaves);
    const auto texture = addImpostorLevel(tree, atlas.image, 1 + int32_t(clouds.size()));
    ASSERT_TRUE(texture.has_value());
    EXPECT_EQ(texture->image.width, 2048);
    EXPECT_EQ(texture->wrapS, TextureWrap::ClampToEdge);
    const MeshLods after = buildLods(tree.leaves);

    ASSERT_EQ(after.camera.size(), before.camera.size());
    for (size_t l = 0; l < after.camera.size(); ++l) {
        EXPECT_EQ(after.camera[l].objectError, before.camera[l].objectError) << l;
        EXPECT_EQ(after.camera[l].impostor.framesPerSide, 0) << l;
    }
    ASSERT_EQ(after.shadow.size(), before.shadow.size());
    for (size_t l = 0; l + 1 < after.shadow.size(); ++l)
        EXPECT_EQ(after.shadow[l].objectError, before.shadow[l].objectError) << l;
    const LodLevel& card = after.shadow.back();
    EXPECT_EQ(card.impostor.framesPerSide, 16);
    EXPECT_EQ(card.impostor.texelsPerFrame, 128);
    EXPECT_EQ(card.indexCount, 6u) << "two triangles";
    EXPECT_EQ(card.texture, 1 + int32_t(clouds.size()));
    EXPECT_TRUE(card.keepsCoverage);
    for (size_t l = 1; l < after.shadow.size(); ++l)
        EXPECT_GE(after.shadow[l].objectError, after.shadow[l - 1].objectError) << l;

    // Its corners are the sphere's: centre ± radius along x and y, which the vertex stages read,
    // and the mesh's box holds the sphere's, which a turned card reaches.
    const ImpostorCard& sphere = card.impostor;
    for (uint32_t k = 0; k < 6; ++k) {
        const glm::vec3 offset = tree.leaves.vertices[after.indices[card.firstIndex + k]].position - sphere.osCentre;
        EXPECT_FLOAT_EQ(std::abs(offset.x), sphere.osRadius) << k;
        EXPECT_FLOAT_EQ(std::abs(offset.y), sphere.osRadius) << k;
    }
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(tree.leaves.osBounds.min[axis], sphere.osCentre[axis] - sphere.osRadius) << axis;
        EXPECT_GE(tree.leaves.osBounds.max[axis], sphere.osCentre[axis] + sphere.osRadius) << axis;
    }
}
