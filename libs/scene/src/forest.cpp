// The procedural forest (docs/references.md, evaluation §1).
//
// Randomness comes from SplitMix64 and integer-hash value noise rather than <random>
// distributions, whose outputs the C++ standard leaves to each library: the forest for a
// seed must be the same on every machine, so figures from different weeks compare.
#include "shadowkit/scene/forest.h"

#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/leafy_trees.h"

#include "shadowkit/scene/mesh_builder.h"

#include "split_mix.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shadowkit::scene {
namespace {

// Value noise: a hashed random value per integer lattice point, smoothly interpolated.
double latticeValue(uint64_t seed, int64_t x, int64_t z) {
    SplitMix64 h(seed ^ (static_cast<uint64_t>(x) * 0x9e3779b97f4a7c15ull) ^
                 (static_cast<uint64_t>(z) * 0xc2b2ae3d27d4eb4full));
    return h.uniform();
}

double valueNoise(uint64_t seed, double x, double z) {
    const double fx = std::floor(x), fz = std::floor(z);
    const auto ix = static_cast<int64_t>(fx), iz = static_cast<int64_t>(fz);
    auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
    const double tx = smooth(x - fx), tz = smooth(z - fz);
    const double a = latticeValue(seed, ix, iz), b = latticeValue(seed, ix + 1, iz);
    const double c = latticeValue(seed, ix, iz + 1), d = latticeValue(seed, ix + 1, iz + 1);
    return std::lerp(std::lerp(a, b, tx), std::lerp(c, d, tx), tz);
}

// Four octaves; wavelengths from 400 m down to 50 m give "gentle hills".
double hills(uint64_t seed, double x, double z) {
    double sum = 0.0, amplitude = 1.0, wavelength = 400.0;
    for (int octave = 0; octave < 4; ++octave) {
        sum += amplitude * valueNoise(seed + static_cast<uint64_t>(octave), x / wavelength, z / wavelength);
        amplitude *= 0.45;
        wavelength *= 0.5;
    }
    return sum;
}

Heightfield makeHeightfield(const ForestOptions& o) {
    Heightfield field;
    field.size = o.terrainSize;
    field.resolution = o.terrainResolution;
    const int n = o.terrainResolution + 1;
    std::vector<double> raw(static_cast<size_t>(n) * static_cast<size_t>(n));
    for (int iz = 0; iz < n; ++iz)
        for (int ix = 0; ix < n; ++ix) {
            const double x = -0.5 * o.terrainSize + ix * field.spacing();
            const double z = -0.5 * o.terrainSize + iz * field.spacing();
            raw[static_cast<size_t>(iz * n + ix)] = hills(o.seed * 7919u + 17u, x, z);
        }
    const auto [lo, hi] = std::minmax_element(raw.begin(), raw.end());
    const double range = *hi - *lo;
    field.heights.resize(raw.size());
    for (size_t i = 0; i < raw.size(); ++i)
        field.heights[i] = static_cast<float>(range > 0.0 ? (raw[i] - *lo) / range * o.hillHeight : 0.0);
    return field;
}

Mesh makeTerrainMesh(const Heightfield& field) {
    Mesh mesh;
    mesh.name = "terrain";
    const int n = field.resolution + 1;
    const double h = field.spacing();
    for (int iz = 0; iz < n; ++iz)
        for (int ix = 0; ix < n; ++ix) {
            const double y = field.sample(ix, iz);
            // Central differences; one-sided at the border through sample()'s clamping.
            const double dx = (field.sample(ix + 1, iz) - field.sample(ix - 1, iz)) / (2.0 * h);
            const double dz = (field.sample(ix, iz + 1) - field.sample(ix, iz - 1)) / (2.0 * h);
            const glm::vec3 normal = glm::normalize(glm::vec3(-dx, 1.0, -dz));
            const float t = static_cast<float>(y / 30.0);
            const glm::vec3 albedo =
                glm::mix(glm::vec3(0.30f, 0.42f, 0.18f), glm::vec3(0.45f, 0.42f, 0.30f), std::clamp(t, 0.0f, 1.0f));
            mesh.vertices.push_back(
                {glm::vec3(-0.5 * field.size + ix * h, y, -0.5 * field.size + iz * h), normal, albedo});
        }
    for (int iz = 0; iz < field.resolution; ++iz)
        for (int ix = 0; ix < field.resolution; ++ix) {
            const auto v00 = static_cast<uint32_t>(iz * n + ix), v10 = v00 + 1;
            const auto v01 = static_cast<uint32_t>(v00 + static_cast<uint32_t>(n)), v11 = v01 + 1;
            // Split along (0,0)-(1,1), as Heightfield::heightAt assumes; +Y faces up.
            mesh.indices.insert(mesh.indices.end(), {v00, v11, v10, v00, v01, v11});
        }
    mesh.computeBounds();
    return mesh;
}

const glm::vec3 kBark(0.33f, 0.23f, 0.14f);

// Unit-height conifer: 12-sided trunk and four 24-sided cone layers (228 triangles).
Mesh makeConifer(const glm::vec3& needles) {
    Mesh mesh;
    mesh.name = "conifer";
    // Top layer first, trunk last: a depth pass from a light above draws the nearest surfaces
    // first, so the layers and the trunk beneath them fail the depth test instead of
    // overwriting it (the samples per texel in docs/performance.md).
    for (int layer = 3; layer >= 0; --layer) {
        const float base = 0.22f + 0.17f * static_cast<float>(layer);
        const float radius = 0.24f - 0.045f * static_cast<float>(layer);
        addCone(mesh, glm::translate(glm::mat4(1.0f), {0.0f, base, 0.0f}), 24, radius, 1.0f - base, needles);
    }
    addCylinder(mesh, glm::mat4(1.0f), 12, 0.025f, 0.35f, kBark);
    mesh.computeBounds();
    return mesh;
}

// Unit-height broadleaf tree: trunk and a geodesic crown (356 triangles), crown first (as the conifer).
Mesh makeBroadleaf(const glm::vec3& leaves) {
    Mesh mesh;
    mesh.name = "broadleaf";
    glm::mat4 crown = glm::translate(glm::mat4(1.0f), {0.0f, 0.68f, 0.0f});
    crown = glm::scale(crown, {1.0f, 0.9f, 1.0f});
    addIcosphere(mesh, crown, 2, 0.32f, leaves);
    addCylinder(mesh, glm::mat4(1.0f), 12, 0.035f, 0.55f, kBark);
    mesh.computeBounds();
    return mesh;
}

Mesh makeRock() {
    Mesh mesh;
    mesh.name = "rock";
    addIcosphere(mesh, glm::scale(glm::mat4(1.0f), {1.0f, 0.6f, 0.8f}), 1, 1.0f, {0.45f, 0.44f, 0.42f});
    mesh.computeBounds();
    return mesh;
}

Mesh makeBuilding() {
    Mesh mesh;
    mesh.name = "building";
    addBox(mesh, glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}), {0.5f, 0.5f, 0.5f}, {0.70f, 0.64f, 0.55f});
    mesh.computeBounds();
    return mesh;
}

Mesh makeMover() {
    Mesh mesh;
    mesh.name = "mover";
    addIcosphere(mesh, glm::mat4(1.0f), 2, 1.0f, {0.75f, 0.20f, 0.15f});
    mesh.computeBounds();
    return mesh;
}

// A placement on the terrain outside the clearing: (x, z) and a random yaw.
struct Spot {
    double x, z, yaw;
};
Spot randomSpot(SplitMix64& rng, const ForestOptions& o) {
    const double half = 0.5 * o.terrainSize;
    for (int attempt = 0;; ++attempt) {
        Spot s{rng.uniform(-half, half), rng.uniform(-half, half), rng.uniform(0.0, 2.0 * std::numbers::pi)};
        // The clearing would be the whole terrain for a tiny one: give up after a few tries.
        if (std::hypot(s.x, s.z) >= o.clearingRadius || attempt > 16) return s;
    }
}

glm::mat4 placement(const Heightfield& field, const Spot& s, const glm::vec3& scale, double sink) {
    const double y = field.heightAt(s.x, s.z) - sink;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(float(s.x), float(y), float(s.z)));
    m = glm::rotate(m, static_cast<float>(s.yaw), glm::vec3(0, 1, 0));
    return glm::scale(m, scale);
}

// The leafy forest's trees: three species, a wood and a leaf batch each, every tree placed in
// both with one transform. The same draws from `rng` per tree as the simple forest (a spot, a
// kind, a height), so the two forests of a seed have their trees in the same places.
template <class AddMesh>
void addLeafyTrees(Scene& scene, SplitMix64& rng, const ForestOptions& o, AddMesh addMesh) {
    scene.textures.push_back(makeLeafAtlas());
    scene.materials.push_back(leafMaterial(0));
    struct Species {
        size_t wood, leaves;
        double minHeight, maxHeight, unitHeight;
    };
    const double heights[kTreeSpeciesCount][2] = {{8.0, 18.0}, {10.0, 24.0}, {1.5, 3.0}};
    std::vector<Species> species;
    for (int k = 0; k < kTreeSpeciesCount; ++k) {
        LeafyTree tree = makeLeafyTree(static_cast<TreeSpecies>(k), o.seed);
        tree.leaves.material = 0;
        // The height of the full tree: the far level's planes may reach a little past it.
        const double top = std::max(tree.wood.osBounds.max.y, tree.leaves.osBounds.max.y);
        for (BakedCloud& far : addFarLevels(tree, scene.textures[0].image, int32_t(scene.textures.size())))
            scene.textures.push_back(std::move(far.texture));
        if (o.impostors)
            if (auto card = addImpostorLevel(tree, scene.textures[0].image, int32_t(scene.textures.size())))
                scene.textures.push_back(std::move(*card));
        species.push_back(
            {addMesh(std::move(tree.wood)), addMesh(std::move(tree.leaves)), heights[k][0], heights[k][1], top});
    }
    const Heightfield& field = *scene.terrain;
    for (int i = 0; i < o.trees; ++i) {
        const Spot s = randomSpot(rng, o);
        const Species& kind = species[static_cast<size_t>(rng.next() % kTreeSpeciesCount)];
        const double height = kind.minHeight + (kind.maxHeight - kind.minHeight) * rng.uniform();
        const glm::mat4 m = placement(field, s, glm::vec3(static_cast<float>(height / kind.unitHeight)), 0.1);
        scene.batches[kind.wood].worldFromObject.push_back(m);
        scene.batches[kind.leaves].worldFromObject.push_back(m);
    }
}

} // namespace

core::Status validate(const ForestOptions& o) {
    auto bad = [](const char* name, const char* range) {
        return core::makeError(std::string("forest option ") + name + ": must be in " + range);
    };
    if (o.trees < 0 || o.trees > 1'000'000) return bad("trees", "[0, 1000000]");
    if (!(o.terrainSize > 0.0 && o.terrainSize <= 100'000.0)) return bad("terrain size", "(0, 100000] metres");
    if (o.terrainResolution < 1 || o.terrainResolution > 4096) return bad("terrain resolution", "[1, 4096]");
    if (!(o.hillHeight >= 0.0 && o.hillHeight <= 1000.0)) return bad("hill height", "[0, 1000] metres");
    if (o.rocks < 0 || o.rocks > 100'000) return bad("rocks", "[0, 100000]");
    if (o.buildings < 0 || o.buildings > 100'000) return bad("buildings", "[0, 100000]");
    if (o.movers < 0 || o.movers > 1000) return bad("movers", "[0, 1000]");
    if (!(o.clearingRadius >= 0.0)) return bad("clearing radius", "[0, inf) metres");
    if (o.impostors && o.kind != ForestKind::Leafy)
        return core::makeError(
            "forest option impostors: the leafy forest's (its trees' far levels), not the simple one's");
    return core::Ok{};
}

Scene makeForest(const ForestOptions& o) {
    SK_ASSERT(validate(o).hasValue(), "makeForest(): options out of range; call validate() first");
    Scene scene;
    scene.terrain = makeHeightfield(o);
    const Heightfield& field = *scene.terrain;
    SplitMix64 rng(o.seed);

    auto addMesh = [&](Mesh mesh, bool dynamic = false) {
        scene.meshes.push_back(std::move(mesh));
        scene.batches.push_back({static_cast<uint32_t>(scene.meshes.size() - 1), {}, dynamic});
        return scene.batches.size() - 1;
    };
    scene.batches.reserve(8);
    const size_t terrain = addMesh(makeTerrainMesh(field));
    scene.batches[terrain].worldFromObject.push_back(glm::mat4(1.0f));

    if (o.kind == ForestKind::Leafy) {
        addLeafyTrees(scene, rng, o, addMesh);
    } else {
        // Two species, two foliage tints each: 4 meshes, 4 instanced draws for all trees.
        const size_t species[4] = {
            addMesh(makeConifer({0.13f, 0.27f, 0.12f})), addMesh(makeConifer({0.17f, 0.32f, 0.14f})),
            addMesh(makeBroadleaf({0.22f, 0.38f, 0.13f})), addMesh(makeBroadleaf({0.28f, 0.42f, 0.16f}))};
        for (int i = 0; i < o.trees; ++i) {
            const Spot s = randomSpot(rng, o);
            const size_t kind = static_cast<size_t>(rng.next() % 4);
            const double height = rng.uniform(6.0, 20.0);
            MeshBatch& batch = scene.batches[species[kind]];
            // Meshes are roughly unit height; divide by the exact one so heights stay in range.
            const auto scale = static_cast<float>(height / scene.meshes[batch.mesh].osBounds.extent().y);
            batch.worldFromObject.push_back(placement(field, s, glm::vec3(scale), 0.1));
        }
    }
    const size_t rocks = addMesh(makeRock());
    for (int i = 0; i < o.rocks; ++i) {
        const float r = static_cast<float>(rng.uniform(2.0, 6.0));
        scene.batches[rocks].worldFromObject.push_back(placement(field, randomSpot(rng, o), glm::vec3(r), 0.3 * r));
    }
    const size_t buildings = addMesh(makeBuilding());
    for (int i = 0; i < o.buildings; ++i) {
        // Depth, height, width drawn in that order: one draw per statement, so the town does not
        // depend on the compiler (a call's arguments are evaluated in an unspecified order).
        const float depth = static_cast<float>(rng.uniform(8, 20)), height = static_cast<float>(rng.uniform(6, 12));
        const glm::vec3 size(static_cast<float>(rng.uniform(8, 16)), height, depth);
        scene.batches[buildings].worldFromObject.push_back(placement(field, randomSpot(rng, o), size, 1.0));
    }
    // Movers float 2-4 m above the ground on circles round the viewer's clearing, where the
    // standard views see them (up to 20 radii, 5 m apart, as many as fit the terrain), at
    // four speeds from a walk to a run, every other one the other way round. At t = 0 each
    // stands where the still views have always seen it.
    const size_t movers = addMesh(makeMover(), true);
    const double innermost = o.clearingRadius + 10.0, outermost = 0.45 * o.terrainSize;
    const int rings = std::clamp(static_cast<int>(std::floor((outermost - innermost) / 5.0)) + 1, 1, 20);
    for (int i = 0; i < o.movers; ++i) {
        Track track;
        track.batch = static_cast<uint32_t>(movers);
        track.instance = static_cast<uint32_t>(i);
        track.phase = 2.0 * std::numbers::pi * i / std::max(o.movers, 1);
        track.radius = std::min(innermost + 5.0 * (i % rings), std::max(outermost, 1.0));
        track.speed = (1.0 + 1.5 * (i % 4)) * (i % 2 == 0 ? 1.0 : -1.0);
        track.lift = rng.uniform(2.0, 4.0);
        scene.tracks.push_back(track);
        scene.batches[movers].worldFromObject.push_back(trackTransform(track, scene, 0.0));
    }
    // Drop empty batches so renderers never issue zero-instance draws (tracks follow their
    // batch's new index).
    std::vector<uint32_t> newIndex(scene.batches.size(), UINT32_MAX);
    for (uint32_t b = 0, kept = 0; b < scene.batches.size(); ++b)
        if (!scene.batches[b].worldFromObject.empty()) newIndex[b] = kept++;
    for (Track& track : scene.tracks) track.batch = newIndex[track.batch];
    std::erase_if(scene.batches, [](const MeshBatch& b) { return b.worldFromObject.empty(); });
    return scene;
}

} // namespace shadowkit::scene
