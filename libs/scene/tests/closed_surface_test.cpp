#include "shadowkit/scene/closed_surface.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/mesh_lod.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <utility>

using namespace shadowkit::scene;

namespace {

const glm::vec3 kGrey(0.5f);

bool closed(const Mesh& mesh) { return boundsSolid(mesh, mesh.indices); }

Mesh box(const glm::mat4& objectFromPart = glm::mat4(1.0f)) {
    Mesh mesh;
    addBox(mesh, objectFromPart, glm::vec3(1.0f, 2.0f, 0.5f), kGrey);
    return mesh;
}

Mesh reversed(Mesh mesh) {
    for (size_t t = 0; t < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    return mesh;
}

} // namespace

TEST(ClosedSurfaceTest, SolidsWithSplitVerticesAreClosed) {
    // addBox splits its corners per face (flat normals): welded by position it is closed.
    const Mesh b = box();
    ASSERT_EQ(b.vertices.size(), 24u);
    EXPECT_TRUE(closed(b));
    Mesh sphere;
    addIcosphere(sphere, glm::mat4(1.0f), 2, 3.0f, kGrey);
    EXPECT_TRUE(closed(sphere));
    Mesh cylinder, cone;
    addCylinder(cylinder, glm::mat4(1.0f), 12, 0.5f, 2.0f, kGrey);
    addCone(cone, glm::mat4(1.0f), 24, 1.0f, 2.0f, kGrey);
    EXPECT_TRUE(closed(cylinder));
    EXPECT_TRUE(closed(cone));
    // Two separate solids, and two solids that overlap without sharing edges.
    Mesh two = box();
    addBox(two, glm::translate(glm::mat4(1.0f), {5.0f, 0.0f, 0.0f}), glm::vec3(1.0f), kGrey);
    addIcosphere(two, glm::translate(glm::mat4(1.0f), {0.5f, 1.0f, 0.0f}), 1, 1.0f, kGrey);
    EXPECT_TRUE(closed(two));
}

TEST(ClosedSurfaceTest, OpenOrInsideOutSurfacesAreNot) {
    Mesh holed = box();
    holed.indices.resize(holed.indices.size() - 3); // one triangle missing
    EXPECT_FALSE(closed(holed));
    // Inside out: closed and oriented, but its counter-clockwise faces point inwards, so the
    // faces towards a light are the ones a pass would cull.
    EXPECT_FALSE(closed(reversed(box())));
    // A card, and a two-sided card (the same corners wound both ways): closed edges, no volume.
    Mesh card;
    addCard(card, glm::mat4(1.0f), {0, 1}, {1, 0}, kGrey);
    EXPECT_FALSE(closed(card));
    Mesh twoSided = card;
    const Mesh back = reversed(card);
    twoSided.indices.insert(twoSided.indices.end(), back.indices.begin(), back.indices.end());
    EXPECT_FALSE(closed(twoSided));
    // One shell right, another inside out: the second would lose its lit side.
    Mesh mixed = box();
    const Mesh other = reversed(box(glm::translate(glm::mat4(1.0f), {9.0f, 0.0f, 0.0f})));
    const auto base = static_cast<uint32_t>(mixed.vertices.size());
    mixed.vertices.insert(mixed.vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const uint32_t i : other.indices) mixed.indices.push_back(base + i);
    EXPECT_FALSE(closed(mixed));
    // A triangle used twice (a duplicated face) is not a manifold surface.
    Mesh doubled = box();
    doubled.indices.insert(doubled.indices.end(), doubled.indices.begin(), doubled.indices.begin() + 3);
    EXPECT_FALSE(closed(doubled));
    // Nothing, and indices past the vertices.
    EXPECT_FALSE(closed(Mesh{}));
    Mesh bad = box();
    bad.indices[0] = 1000;
    EXPECT_FALSE(closed(bad));
}

TEST(ClosedSurfaceTest, TrianglesWithoutAreaDoNotOpenASurface) {
    Mesh b = box();
    // A sliver whose corners are two positions of the box (what vertex clustering leaves).
    b.indices.insert(b.indices.end(), {0, 0, 1});
    EXPECT_TRUE(closed(b));
}

TEST(ClosedSurfaceTest, ShadowChainsMarkTheirClosedLevelsAndCameraChainsNone) {
    ForestOptions o;
    o.trees = 20;
    o.terrainResolution = 64;
    const Scene forest = makeForest(o);
    int closedMeshes = 0;
    for (const Mesh& mesh : forest.meshes) {
        const MeshLods lods = buildLods(mesh);
        for (const LodLevel& level : lods.camera) EXPECT_FALSE(level.closed) << mesh.name;
        for (const LodLevel& level : lods.shadow)
            EXPECT_EQ(level.closed,
                      boundsSolid(mesh, std::span(lods.indices).subspan(level.firstIndex, level.indexCount)))
                << mesh.name;
        closedMeshes += lods.shadow[0].closed;
        if (mesh.name == "terrain") {
            EXPECT_FALSE(lods.shadow[0].closed) << "a height field has edges";
        }
    }
    EXPECT_GT(closedMeshes, 0) << "the forest's trees, rocks and buildings are solids";
}
