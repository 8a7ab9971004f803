// Procedural trees with leaf cards (leafy_trees.h).
//
// Based on the structure game foliage is built with (trunk and boughs as tapered cylinders,
// twigs, alpha-tested cards carrying clusters of leaves; e.g. SpeedTree's and Unreal's
// foliage), not on a botanical model: the point is the shadow a real game tree casts — thin
// wood a texel wide and a canopy that is mostly holes. All randomness is SplitMix64, so a
// (species, seed) gives the same tree on every machine.
#include "shadowkit/scene/leafy_trees.h"

#include "shadowkit/scene/mesh_builder.h"

#include "split_mix.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace shadowkit::scene {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kCellTexels = 128;
const glm::vec3 kLeafyBark(0.33f, 0.24f, 0.16f);

// Draws happen one per statement wherever several feed one call: the order in which a call's
// arguments are evaluated is unspecified (GCC 12 evaluates these last first, clang 14 first
// first), and a forest must not depend on the compiler that built it. Each such place draws in
// the order the recorded figures (data/golden) were made with: the last argument first.
float uniform(SplitMix64& rng, float lo, float hi) { return static_cast<float>(rng.uniform(lo, hi)); }

// A colour whose channels are drawn blue, green, red (see above).
glm::vec3 randomColour(SplitMix64& rng, glm::vec2 red, glm::vec2 green, glm::vec2 blue) {
    const float b = uniform(rng, blue.x, blue.y);
    const float g = uniform(rng, green.x, green.y);
    const float r = uniform(rng, red.x, red.y);
    return {r, g, b};
}

// --- the atlas ---------------------------------------------------------------------------

// Paints texel (x, y) of cell (cx, cy) if it lies inside the cell's open border.
void paint(Image& atlas, int cx, int cy, int x, int y, glm::vec3 colour) {
    if (x < 2 || y < 2 || x >= kCellTexels - 2 || y >= kCellTexels - 2) return;
    uint8_t* p = atlas.pixel(cx * kCellTexels + x, cy * kCellTexels + y);
    const glm::vec3 c = glm::clamp(colour, 0.0f, 1.0f) * 255.0f;
    p[0] = uint8_t(c.r), p[1] = uint8_t(c.g), p[2] = uint8_t(c.b), p[3] = 255;
}

// A filled ellipse of semi-axes (a, b) at `centre`, its long axis at `angle`, with a darker
// midrib along that axis.
void paintLeaf(Image& atlas, int cx, int cy, glm::vec2 centre, float a, float b, float angle, glm::vec3 colour) {
    const glm::vec2 along(std::cos(angle), std::sin(angle)), across(-along.y, along.x);
    const int reach = int(std::ceil(a)) + 1;
    for (int y = int(centre.y) - reach; y <= int(centre.y) + reach; ++y)
        for (int x = int(centre.x) - reach; x <= int(centre.x) + reach; ++x) {
            const glm::vec2 d = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) - centre;
            const float s = glm::dot(d, along) / a, t = glm::dot(d, across) / b;
            if (s * s + t * t > 1.0f) continue;
            const float shade = 0.85f + 0.15f * s;                // lighter towards the tip
            const float rib = std::abs(t) < 0.12f ? 0.75f : 1.0f; // the midrib
            paint(atlas, cx, cy, x, y, colour * shade * rib);
        }
}

// A line of `width` texels from a to b.
void paintLine(Image& atlas, int cx, int cy, glm::vec2 a, glm::vec2 b, float width, glm::vec3 colour) {
    const int steps = int(glm::length(b - a)) * 2 + 1;
    for (int i = 0; i <= steps; ++i) {
        const glm::vec2 p = glm::mix(a, b, float(i) / float(steps));
        for (int y = int(p.y - width); y <= int(p.y + width); ++y)
            for (int x = int(p.x - width); x <= int(p.x + width); ++x)
                if (glm::length(glm::vec2(float(x) + 0.5f, float(y) + 0.5f) - p) <= 0.5f * width + 0.5f)
                    paint(atlas, cx, cy, x, y, colour);
    }
}

// A broadleaf cluster: a twig up the cell's middle and five to seven leaves along it.
void paintBroadleafCell(Image& atlas, int cx, int cy, SplitMix64& rng) {
    const float n = kCellTexels;
    paintLine(atlas, cx, cy, {0.5f * n, 0.97f * n}, {0.5f * n, 0.2f * n}, 3.0f, kLeafyBark * 1.2f);
    const int leaves = 5 + int(rng.next() % 3);
    for (int i = 0; i < leaves; ++i) {
        const float along = 0.2f + 0.7f * float(i) / float(leaves);
        const float side = i % 2 == 0 ? -1.0f : 1.0f;
        const float angle = -0.5f * kPi + side * uniform(rng, 0.5f, 1.0f); // up and out
        const float a = uniform(rng, 20.0f, 27.0f), b = uniform(rng, 8.0f, 11.0f);
        const glm::vec2 stem(0.5f * n, (1.0f - along) * n);
        const glm::vec2 centre = stem + a * glm::vec2(std::cos(angle), std::sin(angle));
        const glm::vec3 green = randomColour(rng, {0.18f, 0.28f}, {0.38f, 0.5f}, {0.08f, 0.14f});
        paintLeaf(atlas, cx, cy, centre, a, b, angle, green);
    }
}

// A conifer spray: a twig across the cell with needles at ±50° along both sides.
void paintNeedleCell(Image& atlas, int cx, int cy, SplitMix64& rng) {
    const float n = kCellTexels;
    const glm::vec3 needle(0.10f, 0.26f, 0.12f);
    paintLine(atlas, cx, cy, {0.5f * n, 0.97f * n}, {0.5f * n, 0.06f * n}, 2.5f, kLeafyBark);
    for (int i = 0; i < 36; ++i) {
        const float y = (0.94f - 0.86f * float(i) / 36.0f) * n;
        const float side = i % 2 == 0 ? -1.0f : 1.0f;
        const float length = uniform(rng, 0.28f, 0.4f) * n * (0.6f + 0.4f * float(i % 18) / 18.0f);
        const glm::vec2 from(0.5f * n, y);
        const glm::vec2 to = from + length * glm::vec2(side * std::sin(0.9f), -std::cos(0.9f));
        paintLine(atlas, cx, cy, from, to, 2.0f, needle * uniform(rng, 0.85f, 1.15f));
    }
}

// Shrub leaves: a dozen small round leaves on short stalks around the cell's middle.
void paintShrubCell(Image& atlas, int cx, int cy, SplitMix64& rng) {
    const float n = kCellTexels;
    const glm::vec2 middle(0.5f * n, 0.55f * n);
    for (int i = 0; i < 12; ++i) {
        const float angle = 2.0f * kPi * float(i) / 12.0f + uniform(rng, -0.2f, 0.2f);
        const float distance = uniform(rng, 0.12f, 0.32f) * n;
        const glm::vec2 centre = middle + distance * glm::vec2(std::cos(angle), std::sin(angle));
        paintLine(atlas, cx, cy, middle, centre, 2.0f, kLeafyBark * 1.3f);
        const glm::vec3 green = randomColour(rng, {0.2f, 0.3f}, {0.36f, 0.46f}, {0.1f, 0.16f});
        const float across = uniform(rng, 8.0f, 11.0f);
        paintLeaf(atlas, cx, cy, centre, uniform(rng, 10.0f, 14.0f), across, angle, green);
    }
}

// The uvs of an atlas cell, bottom-left to top-right (addCard's convention: rows top first).
std::pair<glm::vec2, glm::vec2> cellUvs(int cx, int cy) {
    const float step = 1.0f / kLeafAtlasCells;
    return {{float(cx) * step, float(cy + 1) * step}, {float(cx + 1) * step, float(cy) * step}};
}

// The cell a card of this species shows, picked at random among the species' cells.
std::pair<glm::vec2, glm::vec2> speciesCell(TreeSpecies species, SplitMix64& rng) {
    const int column = int(rng.next() % kLeafAtlasCells);
    switch (species) {
    case TreeSpecies::Broadleaf:
        return cellUvs(column, int(rng.next() % 2));
    case TreeSpecies::Conifer:
        return cellUvs(column, 2);
    case TreeSpecies::Shrub:
    default:
        return cellUvs(column, 3);
    }
}

// --- the trees ---------------------------------------------------------------------------

// A tapered tube from `from` (radius r0) to `to` (radius r1), sides only: wood seen from
// outside, with radial normals.
void addBranch(Mesh& mesh, glm::vec3 from, glm::vec3 to, float r0, float r1, int segments) {
    const glm::vec3 axis = glm::normalize(to - from);
    const glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(axis, helper)), v = glm::cross(axis, u);
    const auto first = static_cast<uint32_t>(mesh.vertices.size());
    for (int i = 0; i < segments; ++i) {
        const float a = 2.0f * kPi * float(i) / float(segments);
        const glm::vec3 radial = std::cos(a) * u + std::sin(a) * v;
        mesh.vertices.push_back({from + r0 * radial, radial, kLeafyBark, {}});
        mesh.vertices.push_back({to + r1 * radial, radial, kLeafyBark, {}});
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t a0 = first + 2 * uint32_t(i), a1 = a0 + 1;
        const uint32_t b0 = first + 2 * uint32_t((i + 1) % segments), b1 = b0 + 1;
        mesh.indices.insert(mesh.indices.end(), {a0, b0, b1, a0, b1, a1});
    }
}

// A card of `size` centred at `centre`: its face turned by yaw about y, then tilted by `tilt`
// about its own horizontal axis, its up axis rolled by `roll` within its plane.
struct Card {
    glm::vec3 centre;
    float size, yaw, tilt, roll;
    std::pair<glm::vec2, glm::vec2> cell;
};

void addLeafCard(std::vector<Card>& cards, glm::vec3 centre, float size, float yaw, float tilt, float roll,
                 std::pair<glm::vec2, glm::vec2> cell) {
    cards.push_back({centre, size, yaw, tilt, roll, cell});
}

// A card of any yaw, its size, tilt and roll drawn within these ranges, showing one of the
// species' cells; drawn cell, roll, tilt, yaw, size (see uniform).
void addRandomCard(std::vector<Card>& cards, glm::vec3 centre, glm::vec2 size, glm::vec2 tilt, glm::vec2 roll,
                   TreeSpecies species, SplitMix64& rng) {
    const auto cell = speciesCell(species, rng);
    const float r = uniform(rng, roll.x, roll.y);
    const float t = uniform(rng, tilt.x, tilt.y);
    const float yaw = uniform(rng, 0, 2 * kPi);
    addLeafCard(cards, centre, uniform(rng, size.x, size.y), yaw, t, r, cell);
}

// The card's quad into `mesh`, `grow` times its size.
void emitCard(Mesh& mesh, const Card& card, float grow) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), card.centre);
    m = glm::rotate(m, card.yaw, {0, 1, 0});
    m = glm::rotate(m, card.tilt, {1, 0, 0});
    m = glm::rotate(m, card.roll, {0, 0, 1});
    m = glm::scale(m, glm::vec3(card.size * grow));
    m = glm::translate(m, {0.0f, -0.5f, 0.0f});
    addCard(mesh, m, card.cell.first, card.cell.second, glm::vec3(1.0f));
}

// Level 0: every card. Coarser levels (kCardLevels of them): every 2^k-th card, √(2^k) times
// larger, so the leaves' total area — and with it, on average, what a canopy covers — stays
// while the cards halve; a card-aware level of detail (closed-mesh simplifiers cannot reduce a
// card soup). Each level's error is half its mean card size: how far, in object metres, its
// coverage moves from the full canopy's, the bound a pass compares against its pixel or texel.
constexpr int kCardLevels = 2;
void emitCards(Mesh& leaves, const std::vector<Card>& cards) {
    for (const Card& card : cards) emitCard(leaves, card, 1.0f);
    orderQuadsHighestFirst(leaves.vertices, leaves.indices);
    for (int level = 1; level <= kCardLevels; ++level) {
        const size_t stride = size_t(1) << level;
        const float grow = std::sqrt(float(stride));
        const auto firstIndex = leaves.indices.size();
        double sizes = 0.0;
        size_t kept = 0;
        for (size_t c = 0; c < cards.size(); c += stride, ++kept) {
            emitCard(leaves, cards[c], grow);
            sizes += cards[c].size * grow;
        }
        // addCard appended to Mesh::indices: those triangles are this level's, not level 0's.
        AuthoredLod lod;
        lod.indices.assign(leaves.indices.begin() + std::ptrdiff_t(firstIndex), leaves.indices.end());
        leaves.indices.resize(firstIndex);
        orderQuadsHighestFirst(leaves.vertices, lod.indices);
        lod.objectError = kept > 0 ? float(0.5 * sizes / double(kept)) : 0.0f;
        lod.keepsCoverage = true; // the leaves' area, in fewer cards
        leaves.authoredLods.push_back(std::move(lod));
    }
}

// A point in the unit ball, uniform (rejection sampling).
glm::vec3 inBall(SplitMix64& rng) {
    for (;;) {
        const float z = uniform(rng, -1, 1), y = uniform(rng, -1, 1), x = uniform(rng, -1, 1);
        const glm::vec3 p(x, y, z);
        if (glm::dot(p, p) <= 1.0f) return p;
    }
}

// Trunk to 0.42, five boughs up and out, four twigs on each; 2,600 cards clumped round the
// twigs' ends into a crown of about 0.45 radius centred at 0.68.
void makeBroadleaf(LeafyTree& tree, std::vector<Card>& cards, SplitMix64& rng) {
    const glm::vec3 fork(0.0f, 0.42f, 0.0f);
    addBranch(tree.wood, {0, 0, 0}, fork, 0.03f, 0.022f, 12);
    tree.trunkIndices = tree.wood.indices.size();
    std::vector<glm::vec3> tips;
    const int boughs = 5;
    for (int b = 0; b < boughs; ++b) {
        const float yaw = 2.0f * kPi * (float(b) + uniform(rng, -0.2f, 0.2f)) / float(boughs);
        const float rise = uniform(rng, 0.5f, 0.9f); // radians above the horizontal
        const glm::vec3 direction(std::cos(yaw) * std::cos(rise), std::sin(rise), std::sin(yaw) * std::cos(rise));
        const glm::vec3 end = fork + uniform(rng, 0.28f, 0.36f) * direction;
        addBranch(tree.wood, fork, end, 0.018f, 0.008f, 8);
        for (int t = 0; t < 4; ++t) {
            const glm::vec3 start = glm::mix(fork, end, 0.45f + 0.18f * float(t));
            glm::vec3 out = glm::normalize(direction + 0.8f * inBall(rng) + glm::vec3(0, 0.3f, 0));
            const glm::vec3 tip = start + uniform(rng, 0.12f, 0.2f) * out;
            addBranch(tree.wood, start, tip, 0.007f, 0.002f, 6);
            tips.push_back(tip);
        }
    }
    const int count = 2600;
    for (int c = 0; c < count; ++c) {
        const glm::vec3 centre = tips[size_t(c) % tips.size()] + 0.11f * inBall(rng);
        addRandomCard(cards, centre, {0.06f, 0.085f}, {-1.1f, 1.1f}, {-0.6f, 0.6f}, TreeSpecies::Broadleaf, rng);
    }
}

// A trunk to the top and fourteen whorls of six drooping branches, shorter towards the top
// (a cone); 30 needle sprays along each branch, lying nearly flat.
void makeConifer(LeafyTree& tree, std::vector<Card>& cards, SplitMix64& rng) {
    addBranch(tree.wood, {0, 0, 0}, {0, 1.0f, 0}, 0.022f, 0.003f, 12);
    tree.trunkIndices = tree.wood.indices.size();
    const int whorls = 14, perWhorl = 6;
    for (int w = 0; w < whorls; ++w) {
        const float height = 0.16f + 0.78f * float(w) / float(whorls - 1);
        const float length = 0.05f + 0.26f * (1.0f - (height - 0.16f) / 0.78f);
        for (int b = 0; b < perWhorl; ++b) {
            const float yaw = 2.0f * kPi * (float(b) + 0.5f * float(w % 2) + uniform(rng, -0.15f, 0.15f)) / perWhorl;
            const glm::vec3 out(std::cos(yaw), 0.0f, std::sin(yaw));
            const glm::vec3 from(0.0f, height, 0.0f);
            const glm::vec3 to = from + length * glm::normalize(out + glm::vec3(0, -0.25f, 0));
            addBranch(tree.wood, from, to, 0.006f, 0.0015f, 6);
            for (int c = 0; c < 30; ++c) {
                const float along = 0.15f + 0.85f * uniform(rng, 0.0f, 1.0f);
                const glm::vec3 centre = glm::mix(from, to, along) + 0.015f * inBall(rng);
                // Flat sprays whose up axis runs out along the branch.
                const auto cell = speciesCell(TreeSpecies::Conifer, rng);
                const float roll = uniform(rng, -0.5f, 0.5f);
                const float tilt = -0.5f * kPi + uniform(rng, -0.35f, 0.35f);
                addLeafCard(cards, centre, uniform(rng, 0.04f, 0.06f), -yaw + 0.5f * kPi, tilt, roll, cell);
            }
        }
    }
}

// Eight stems fanning out from the ground and 2,500 cards in a dome about 0.7 wide and 1 high.
void makeShrub(LeafyTree& tree, std::vector<Card>& cards, SplitMix64& rng) {
    for (int s = 0; s < 8; ++s) {
        const float yaw = 2.0f * kPi * (float(s) + uniform(rng, -0.3f, 0.3f)) / 8.0f;
        const float rise = uniform(rng, 0.7f, 1.2f);
        const glm::vec3 direction(std::cos(yaw) * std::cos(rise), std::sin(rise), std::sin(yaw) * std::cos(rise));
        addBranch(tree.wood, {0, 0, 0}, uniform(rng, 0.55f, 0.8f) * direction, 0.02f, 0.005f, 8);
        if (s == 0) tree.trunkIndices = tree.wood.indices.size(); // the first stem stands for the trunk
    }
    for (int c = 0; c < 2500; ++c) {
        glm::vec3 p = inBall(rng);
        p.y = std::abs(p.y); // the upper half: a dome on the ground
        const glm::vec3 centre(0.7f * p.x, 0.08f + 0.84f * p.y, 0.7f * p.z);
        addRandomCard(cards, centre, {0.1f, 0.14f}, {-1.2f, 1.2f}, {-0.8f, 0.8f}, TreeSpecies::Shrub, rng);
    }
}

} // namespace

Texture makeLeafAtlas() {
    Texture atlas;
    atlas.image = Image(kLeafAtlasCells * kCellTexels, kLeafAtlasCells * kCellTexels);
    // Open texels keep a leaf green (alpha 0): bilinear lookups at a leaf's edge mix towards
    // green, not black.
    for (size_t i = 0; i < atlas.image.rgba.size(); i += 4) {
        atlas.image.rgba[i] = 50, atlas.image.rgba[i + 1] = 100, atlas.image.rgba[i + 2] = 30;
    }
    SplitMix64 rng(0x1eafa71a5ull);
    for (int cx = 0; cx < kLeafAtlasCells; ++cx) {
        paintBroadleafCell(atlas.image, cx, 0, rng);
        paintBroadleafCell(atlas.image, cx, 1, rng);
        paintNeedleCell(atlas.image, cx, 2, rng);
        paintShrubCell(atlas.image, cx, 3, rng);
    }
    atlas.wrapS = atlas.wrapT = TextureWrap::ClampToEdge;
    return atlas;
}

LeafyTree makeLeafyTree(TreeSpecies species, uint64_t seed) {
    LeafyTree tree;
    std::vector<Card> cards;
    SplitMix64 rng(seed * 0x2545f4914f6cdd1dull + uint64_t(species) + 1);
    switch (species) {
    case TreeSpecies::Broadleaf:
        tree.wood.name = "broadleaf wood", tree.leaves.name = "broadleaf leaves";
        makeBroadleaf(tree, cards, rng);
        break;
    case TreeSpecies::Conifer:
        tree.wood.name = "conifer wood", tree.leaves.name = "conifer needles";
        makeConifer(tree, cards, rng);
        break;
    case TreeSpecies::Shrub:
        tree.wood.name = "shrub wood", tree.leaves.name = "shrub leaves";
        makeShrub(tree, cards, rng);
        break;
    }
    emitCards(tree.leaves, cards);
    tree.wood.computeBounds();
    tree.leaves.computeBounds();
    return tree;
}

namespace {

// What a far level holds: the leaves, their alpha read from the atlas, and every branch but the trunk.
std::array<CloudSource, 2> farSources(const LeafyTree& tree, const Image& leafAtlas) {
    const std::span<const uint32_t> branches(tree.wood.indices.begin() + std::ptrdiff_t(tree.trunkIndices),
                                             tree.wood.indices.end());
    return {CloudSource{&tree.leaves, tree.leaves.indices, &leafAtlas}, CloudSource{&tree.wood, branches, nullptr}};
}

} // namespace

std::vector<BakedCloud> addFarLevels(LeafyTree& tree, const Image& leafAtlas, int32_t firstTextureIndex) {
    const std::array<CloudSource, 2> sources = farSources(tree, leafAtlas);
    std::vector<BakedCloud> far = bakeCloudChain(sources, leafMaterial(0).alphaCutoff, kSpeciesFinestSlabs);
    if (far.empty()) return far; // no leaves
    // A card level that errs as much as the finest cloud (its cards' own size) but draws fifty
    // times its triangles is dropped. Its cards stay in the vertex buffer, unreferenced.
    while (!tree.leaves.authoredLods.empty() &&
           tree.leaves.authoredLods.back().objectError >= far.front().cloud.objectError)
        tree.leaves.authoredLods.pop_back();
    appendCloudLevels(tree.leaves, far, firstTextureIndex);
    // The branches are in every cloud: the trunk alone from the first.
    tree.wood.authoredLods.push_back(
        {std::vector<uint32_t>(tree.wood.indices.begin(),
                               tree.wood.indices.begin() + std::ptrdiff_t(tree.trunkIndices)),
         far.front().cloud.objectError, true});
    return far;
}

std::optional<Texture> addImpostorLevel(LeafyTree& tree, const Image& leafAtlas, int32_t textureIndex) {
    return appendImpostorLevel(tree.leaves, farSources(tree, leafAtlas), leafMaterial(0).alphaCutoff, textureIndex);
}

Material leafMaterial(int32_t atlasTexture) {
    return {.name = "leaves",
            .baseColorTexture = atlasTexture,
            .alphaMode = AlphaMode::Mask,
            .alphaCutoff = 0.5f,
            .doubleSided = true};
}

} // namespace shadowkit::scene
