// Trees a user would recognise, for the leafy forest (`--forest leafy`): tapered trunks and
// boughs, twigs, and alpha-tested leaf cards over a leaf atlas drawn here — no downloaded
// asset. Three species, each one wood mesh (opaque, vertex colours) and one leaf mesh (cards
// whose material is the atlas, MASK, double-sided), 5,000–20,000 triangles a tree together.
//
// Cards are what real-time foliage is made of: a quad showing a cluster of leaves or a spray of
// needles, its holes in the texture's alpha. They are where shadow maps go wrong — thin, holed,
// seen edge-on by the light — which is why this forest exists (issue 33; docs/materials.md).
#pragma once

#include "shadowkit/scene/foliage_levels.h"
#include "shadowkit/scene/material.h"
#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace shadowkit::scene {

enum class TreeSpecies : uint8_t { Broadleaf, Conifer, Shrub };
inline constexpr int kTreeSpeciesCount = 3;

// The leaf atlas: 512² RGBA8 in 4 × 4 cells of 128² texels, alpha 255 on a leaf and 0 between
// leaves. Rows 0–1: broadleaf clusters (a twig with five to seven leaves), row 2: conifer needle
// sprays, row 3: shrub leaves. Every cell keeps a two-texel open border, so bilinear lookups of
// one cell never read its neighbour. Deterministic.
Texture makeLeafAtlas();
inline constexpr int kLeafAtlasCells = 4; // per side

// One tree of a species, standing at the origin with its base at y = 0 and its top at about
// y = 1 (the forest scales it to a height), both meshes in the same object space. `leaves`
// carries uvs into makeLeafAtlas()'s cells of its species; its `material` is left at -1 for the
// caller to set (the scene's index of the leaves' material), and two authored levels of detail
// (Mesh::authoredLods): every second card √2 larger, every fourth twice as large — the leaves'
// area kept while the cards halve. Deterministic for (species, seed).
struct LeafyTree {
    Mesh wood;
    Mesh leaves;
    size_t trunkIndices = 0; // wood.indices begins with the trunk's (the shrub's first stem's)
};
LeafyTree makeLeafyTree(TreeSpecies species, uint64_t seed);

// The tree's far levels, for where a canopy covers a few dozen pixels or texels and fewer: the
// cloud chain (foliage_levels.h: four billboard clouds, 32, 16, 8 and 4 slabs per orientation, each
// in a texture of its own) of its leaves (their alpha read from `leafAtlas`, makeLeafAtlas()'s
// image) and of every branch but the trunk, appended to `tree.leaves` as its last authored
// levels, finer first, the i-th reading Scene::textures[firstTextureIndex + i]; the card levels
// that err as much as the finest cloud are dropped. The trunk alone becomes `tree.wood`'s one
// authored level, at the finest cloud's error, so the branches leave the wood as they enter
// the leaves. Returns the clouds in chain order, with their textures (for the scene).
std::vector<BakedCloud> addFarLevels(LeafyTree& tree, const Image& leafAtlas, int32_t firstTextureIndex);

// The shadow passes' farthest level of the tree, after addFarLevels: an octahedral impostor of
// what its clouds hold in place of its coarsest cloud, which the camera keeps
// (foliage_levels.h, appendImpostorLevel), reading Scene::textures[textureIndex]; returns its
// texture (for the scene), nothing for a tree without leaves.
std::optional<Texture> addImpostorLevel(LeafyTree& tree, const Image& leafAtlas, int32_t textureIndex);

// The leaves' material: MASK at glTF's default cutoff 0.5, double-sided, the atlas at
// `atlasTexture` (an index into Scene::textures).
Material leafMaterial(int32_t atlasTexture);

} // namespace shadowkit::scene
