// Scene's own bookkeeping: batches replaced (Scene::replaceBatches) take exactly the meshes they
// draw with them, and what moves follows its batch.
#include "shadowkit/scene/scene.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

using namespace shadowkit::scene;

TEST(SceneTest, ReplacedBatchesKeepTheMeshesTheyDrawInTheOrderTheyFirstDrawThemAndTracksFollow) {
    Scene scene;
    for (const char* name : {"unused", "wall", "mover", "roof"}) scene.meshes.push_back({.name = name});
    // Batch 0 draws the roof, 1 the wall (to be left out), 2 the mover, 3 the wall again.
    scene.batches = {{3, {glm::mat4(1.0f)}, false},
                     {1, {glm::mat4(1.0f)}, false},
                     {2, {glm::mat4(1.0f)}, true},
                     {1, {glm::mat4(1.0f), glm::mat4(2.0f)}, false}};
    scene.tracks.push_back({.batch = 2});
    scene.deformations.push_back({.batch = 2});

    // Kept: batches 2, 0 and 3 in that order; batch 1 is gone.
    std::vector<MeshBatch> kept = {scene.batches[2], scene.batches[0], scene.batches[3]};
    const std::vector<uint32_t> batchAt = {1, UINT32_MAX, 0, 2};
    scene.replaceBatches(std::move(kept), batchAt);

    std::vector<std::string> meshNames;
    for (const Mesh& mesh : scene.meshes) meshNames.push_back(mesh.name);
    EXPECT_EQ(meshNames, (std::vector<std::string>{"mover", "roof", "wall"})); // "unused" dropped
    ASSERT_EQ(scene.batches.size(), 3u);
    EXPECT_EQ(scene.meshes[scene.batches[0].mesh].name, "mover");
    EXPECT_TRUE(scene.batches[0].dynamic);
    EXPECT_EQ(scene.meshes[scene.batches[1].mesh].name, "roof");
    EXPECT_EQ(scene.meshes[scene.batches[2].mesh].name, "wall");
    EXPECT_EQ(scene.batches[2].worldFromObject.size(), 2u);
    EXPECT_EQ(scene.tracks[0].batch, 0u);
    EXPECT_EQ(scene.deformations[0].batch, 0u);
}
