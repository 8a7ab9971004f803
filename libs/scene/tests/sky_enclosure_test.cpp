// A model shipped inside its sky (sky_enclosure.h): a sphere, a dome or a box round it that hides
// every sun is left out, and nothing else is — not a terrain round a valley, not a hall round its
// contents, not a sphere open at the top, not what moves.
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/sky_enclosure.h"

#include "gltf_test_files.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// A model: a 2 m box standing on a 20 m plate at the origin, each a batch of its own.
Scene modelOnAPlate() {
    Scene scene;
    Mesh box{.name = "box"}, plate{.name = "plate"};
    addBox(box, glm::translate(glm::mat4(1.0f), {0, 1, 0}), {1, 1, 1}, glm::vec3(0.7f));
    addBox(plate, glm::translate(glm::mat4(1.0f), {0, -0.05f, 0}), {10, 0.05f, 10}, glm::vec3(0.5f));
    for (Mesh* mesh : {&box, &plate}) {
        mesh->computeBounds();
        scene.meshes.push_back(std::move(*mesh));
        scene.batches.push_back({uint32_t(scene.meshes.size() - 1), {glm::mat4(1.0f)}, false});
    }
    return scene;
}

// Adds `mesh` placed once at `sceneFromObject`; returns its batch.
uint32_t place(Scene& scene, Mesh mesh, const glm::mat4& sceneFromObject = glm::mat4(1.0f), bool dynamic = false) {
    mesh.computeBounds();
    scene.meshes.push_back(std::move(mesh));
    scene.batches.push_back({uint32_t(scene.meshes.size() - 1), {sceneFromObject}, dynamic});
    return uint32_t(scene.batches.size() - 1);
}

// A sphere of `radius` round the origin, keeping the triangles whose middle `keep` accepts.
template <typename Keep>
Mesh sphere(const std::string& name, float radius, Keep keep) {
    Mesh whole;
    addIcosphere(whole, glm::mat4(1.0f), 3, radius, glm::vec3(0.4f, 0.6f, 1.0f));
    Mesh kept{.name = name};
    std::vector<uint32_t> at(whole.vertices.size(), UINT32_MAX); // only the vertices kept: its bounds are theirs
    for (size_t i = 0; i + 2 < whole.indices.size(); i += 3) {
        const glm::vec3 middle =
            (whole.vertices[whole.indices[i]].position + whole.vertices[whole.indices[i + 1]].position +
             whole.vertices[whole.indices[i + 2]].position) /
            3.0f;
        if (!keep(middle / radius)) continue;
        for (size_t k = i; k < i + 3; ++k) {
            const uint32_t v = whole.indices[k];
            if (at[v] == UINT32_MAX) {
                at[v] = uint32_t(kept.vertices.size());
                kept.vertices.push_back(whole.vertices[v]);
            }
            kept.indices.push_back(at[v]);
        }
    }
    return kept;
}
Mesh sphere(const std::string& name, float radius) {
    return sphere(name, radius, [](glm::vec3) { return true; });
}

std::vector<std::string> meshNames(const Scene& scene) {
    std::vector<std::string> names;
    for (const MeshBatch& batch : scene.batches) names.push_back(scene.meshes[batch.mesh].name);
    return names;
}

} // namespace

TEST(SkyEnclosureTest, ASkySphereDomeOrBoxRoundAModelIsLeftOutAndTheModelStays) {
    struct Case {
        const char* what;
        Mesh sky;
        glm::mat4 at{1.0f};
        bool deepGround = false; // the model stands on a block reaching 100 m down, below the sky's rim
    };
    Mesh box{.name = "sky box"};
    addBox(box, glm::mat4(1.0f), {300, 300, 300}, glm::vec3(0.5f, 0.7f, 1.0f));
    std::vector<Case> cases;
    cases.push_back({"sphere", sphere("sky sphere", 500.0f)});
    cases.push_back({"box", std::move(box)});
    // A sphere placed off the model's middle, by a node scaled ×2: still round all of it.
    cases.push_back({"moved sphere", sphere("sky sphere", 200.0f),
                     glm::scale(glm::translate(glm::mat4(1.0f), {60, -40, 30}), glm::vec3(2.0f))});
    // A dome ending a little below the horizon, over ground that reaches deeper than its rim.
    cases.push_back(
        {"dome", sphere("sky dome", 400.0f, [](glm::vec3 m) { return m.y > -0.1f; }), glm::mat4(1.0f), true});
    for (Case& c : cases) {
        SCOPED_TRACE(c.what);
        Scene model = modelOnAPlate();
        if (c.deepGround) {
            Mesh ground{.name = "ground"};
            addBox(ground, glm::translate(glm::mat4(1.0f), {0, -50.1f, 0}), {30, 50, 30}, glm::vec3(0.5f));
            place(model, std::move(ground));
        }
        const std::vector<std::string> names = meshNames(model);
        const std::string name = c.sky.name;
        // The sky first, as exporters often write it: the batches after it move down.
        Scene scene;
        place(scene, std::move(c.sky), c.at);
        for (const MeshBatch& batch : model.batches) place(scene, model.meshes[batch.mesh]);
        if (c.deepGround) {
            EXPECT_GT(scene.instanceBounds()[0].min.y, model.wsBounds().min.y) << "the ground reaches below the dome";
        }
        const std::vector<SkyEnclosure> skies = leaveOutSkyEnclosures(scene);
        ASSERT_EQ(skies.size(), 1u);
        EXPECT_EQ(skies[0].meshName, name);
        EXPECT_EQ(skies[0].instance.batch, 0u);
        EXPECT_NEAR(skies[0].restMetres, model.wsBounds().diagonal(), 1e-6);
        EXPECT_GE(skies[0].skyMetres, kSkyExtentRatio * skies[0].restMetres);
        EXPECT_EQ(meshNames(scene), names);
        EXPECT_EQ(scene.meshes.size(), names.size()) << "the sky's mesh, drawn by nothing, is dropped too";
        EXPECT_NEAR(scene.wsBounds().diagonal(), model.wsBounds().diagonal(), 1e-6);
    }
}

TEST(SkyEnclosureTest, WhatLeavesTheSkyOpenOrIsNoLargerThanAHallStays) {
    struct Case {
        const char* what;
        Mesh mesh;
    };
    // A terrain round a valley: a bowl 2 km across whose rim stands 200 m above the model, open above it.
    Mesh bowl{.name = "valley"};
    constexpr int kQuads = 32;
    for (int j = 0; j <= kQuads; ++j)
        for (int i = 0; i <= kQuads; ++i) {
            const float x = 2000.0f * (float(i) / kQuads - 0.5f), z = 2000.0f * (float(j) / kQuads - 0.5f);
            bowl.vertices.push_back(
                {{x, 200.0f * (x * x + z * z) / (1000.0f * 1000.0f) - 1.0f, z}, {0, 1, 0}, {0.5f, 0.5f, 0.5f}});
        }
    for (int j = 0; j < kQuads; ++j)
        for (int i = 0; i < kQuads; ++i) {
            const uint32_t a = uint32_t(j * (kQuads + 1) + i), b = a + 1, c = a + kQuads + 1, d = c + 1;
            bowl.indices.insert(bowl.indices.end(), {a, c, b, b, c, d});
        }
    // A hall round the model, closed, three times its size: a room, not a sky.
    Mesh hall{.name = "hall"};
    addBox(hall, glm::translate(glm::mat4(1.0f), {0, 4, 0}), {30, 9, 30}, glm::vec3(0.8f));
    std::vector<Case> cases;
    cases.push_back({"valley", std::move(bowl)});
    cases.push_back({"hall", std::move(hall)});
    // A sphere 50 times the model, open above 60°: the sun comes in through the top.
    cases.push_back({"open sphere",
                     sphere("open sphere", 500.0f, [](glm::vec3 m) { return m.y < std::sin(glm::radians(60.0f)); })});
    // A sphere whose top is below the model's: the model's top pokes out of it.
    cases.push_back({"sphere below the model's top", sphere("low sphere", 500.0f)});
    for (Case& c : cases) {
        SCOPED_TRACE(c.what);
        Scene scene = modelOnAPlate();
        const glm::mat4 at = std::string(c.what) == "sphere below the model's top"
                                 ? glm::translate(glm::mat4(1.0f), {0, -499.0f, 0})
                                 : glm::mat4(1.0f);
        place(scene, std::move(c.mesh), at);
        EXPECT_TRUE(findSkyEnclosures(scene).empty());
        EXPECT_TRUE(leaveOutSkyEnclosures(scene).empty());
        EXPECT_EQ(scene.batches.size(), 3u);
    }
    // A sphere alone: no model inside it to hide the sky from.
    Scene alone;
    place(alone, sphere("ball", 5.0f));
    EXPECT_TRUE(findSkyEnclosures(alone).empty());
}

TEST(SkyEnclosureTest, SkiesOneInAnotherGoOutermostFirstAndWhatMovesKeepsItsTrack) {
    Scene scene = modelOnAPlate();
    const uint32_t outer = place(scene, sphere("stars", 5000.0f));
    place(scene, sphere("clouds", 400.0f));
    // A mover after the skies: its track names its batch, which moves down as they go.
    Mesh mover{.name = "mover"};
    addBox(mover, glm::mat4(1.0f), {0.5f, 0.5f, 0.5f}, glm::vec3(0.9f));
    const uint32_t moving = place(scene, std::move(mover), glm::translate(glm::mat4(1.0f), {3, 1, 0}), true);
    scene.tracks.push_back({.batch = moving, .instance = 0, .centreX = 0, .centreZ = 0, .radius = 3});
    // A moving sky is part of the scene: it is kept, and so is what lies within it.
    Scene movingSky = modelOnAPlate();
    place(movingSky, sphere("moving sky", 500.0f), glm::mat4(1.0f), true);
    EXPECT_TRUE(findSkyEnclosures(movingSky).empty());

    const std::vector<SkyEnclosure> skies = leaveOutSkyEnclosures(scene);
    ASSERT_EQ(skies.size(), 2u);
    EXPECT_EQ(skies[0].meshName, "stars");
    EXPECT_EQ(skies[0].instance.batch, outer);
    EXPECT_EQ(skies[1].meshName, "clouds");
    EXPECT_EQ(meshNames(scene), (std::vector<std::string>{"box", "plate", "mover"}));
    ASSERT_EQ(scene.tracks.size(), 1u);
    EXPECT_EQ(scene.tracks[0].batch, 2u);
    EXPECT_TRUE(scene.batches[scene.tracks[0].batch].dynamic);
    EXPECT_EQ(scene.meshes[scene.batches[scene.tracks[0].batch].mesh].name, "mover");
}

TEST(SkyEnclosureTest, ALoadedFileLosesItsSkyWithOneWarningUnlessAskedToKeepIt) {
    Scene scene;
    place(scene, sphere("Sky", 500.0f));
    Scene model = modelOnAPlate();
    for (const MeshBatch& batch : model.batches) place(scene, model.meshes[batch.mesh]);
    const auto file = shadowkit::test_support::scratchDir() / "sk_model_in_its_sky.glb";
    ASSERT_TRUE(exportScene(scene, file));

    const auto loaded = loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->instanceCount(), 2u);
    EXPECT_LT(loaded->wsBounds().diagonal(), 30.0) << "what is framed and shadowed is the model";
    const auto sky = std::count_if(loaded->warnings.begin(), loaded->warnings.end(), [](const std::string& w) {
        return w.find("mesh 'Sky' encloses the rest of the scene") != std::string::npos &&
               w.find("--keep-sky") != std::string::npos;
    });
    EXPECT_EQ(sky, 1) << "one line, naming the mesh and the flag that keeps it";

    const auto kept = loadScene(file, {.keepSky = true});
    ASSERT_TRUE(kept) << kept.error();
    EXPECT_EQ(kept->instanceCount(), 3u);
    EXPECT_GT(kept->wsBounds().diagonal(), 1000.0);
    std::filesystem::remove(file);
}
