// Far levels of detail for foliage: a chain of billboard clouds (billboard_cloud.h) appended to a
// card mesh as authored levels, for the leafy forest's trees and for the alpha-tested meshes a
// loaded scene brings without levels of its own (a glTF's leaves).
//
// A simplifier cannot reduce a soup of cards (each is two triangles of its own) and a card level
// only halves them; a cloud draws a dozen to a few hundred planes. Three or four of them, each 1.3
// to 1.9 times the error and half the planes of the one before, let a tree's far level shrink
// with its projection.
#pragma once

#include "shadowkit/scene/billboard_cloud.h"
#include "shadowkit/scene/scene.h"

#include <optional>
#include <span>
#include <vector>

namespace shadowkit::scene {

// One cloud of a chain and the texture it was baked into (its own: clamped, coverage-kept mips).
struct BakedCloud {
    Texture texture;
    BillboardCloud cloud;
};

// The chain of `sources`: `finestSlabs` per orientation, then half as many, down to
// kCoarsestSlabs, each baked into (64 × slabs) × (32 × slabs) texels, 1024 × 512 for 16 (a
// coarser cloud's smaller projection needs a quarter of the texels), finer first. A cloud that
// would not err more than the one before it is left out, so errors grow along the chain as a
// pass's choice of the coarsest level within its bound needs. Deterministic. Precondition:
// finestSlabs in [4, 64].
std::vector<BakedCloud> bakeCloudChain(std::span<const CloudSource> sources, float alphaCutoff, int finestSlabs);

// The leafy forest's species start at 32 slabs (2048 × 1024 texels, 125–199 planes): between a
// tree's 5,000 card triangles and its 16-slab cloud's 132–212 the step was thirty-fold, and
// the trees just short of it were most of a frame's triangles. A loaded scene's meshes start at
// 16: each bakes textures of its own, and a file may bring hundreds of them. Every chain ends at
// 4 slabs: a 100,000-tree forest's farthest trees, most of its frame, cast from it.
inline constexpr int kSpeciesFinestSlabs = 32, kLoadedFinestSlabs = 16, kCoarsestSlabs = 4;

// Appends `clouds` to `mesh` as its last authored levels (keeping coverage), their planes after
// its vertices, the i-th reading Scene::textures[firstTextureIndex + i]; recomputes its bounds.
void appendCloudLevels(Mesh& mesh, std::span<const BakedCloud> clouds, int32_t firstTextureIndex);

// The shadow passes' farthest level of `mesh`: an octahedral impostor of `sources`
// (octahedral_impostor.h, 16 × 16 frames of 128² texels) in place of its coarsest cloud, which
// the camera keeps. A shadow pass draws the one card facing its light, two triangles where the
// coarsest cloud draws dozens of planes, and seen from the side the frames cover what the tree
// covers (the conifer's IoU 0.90–0.97 against its clouds' 0.61–0.72, docs/materials.md). A
// camera keeps the cloud: a card flat through the tree's centre would shade the tree's sunlit
// and shadowed halves as one plane. The level errs by the impostor's bound, or by the level
// before it in the shadow chain where that errs more (so the chain's errors grow). Returns the
// impostor's texture (2048² texels, its clamped mips kept by the coverage), which the level reads
// as Scene::textures[textureIndex]; nothing, and no level, for sources that cover nothing.
// Precondition: `mesh` has authored levels, its coarsest a cloud.
std::optional<Texture> appendImpostorLevel(Mesh& mesh, std::span<const CloudSource> sources, float alphaCutoff,
                                           int32_t textureIndex);

struct FoliageCloudOptions {
    // Meshes of fewer triangles keep their one level (a few cards draw as cheaply as a cloud)...
    size_t minTriangles = 256;
    // ... and of more, too (baking takes about a second per 100,000 triangles).
    size_t maxTriangles = 262144;
};

// Gives every alpha-tested mesh of `scene` that has no authored levels (and a triangle count in
// the options' range) the cloud chain of all its triangles, their coverage read from its
// material's base-colour texture (with the texture's wrap modes and the material's alpha factor
// and cutoff), the textures appended to Scene::textures. Returns how many meshes it gave levels.
int addFoliageClouds(Scene& scene, const FoliageCloudOptions& options = {});

} // namespace shadowkit::scene
