// The standard `forest` scene of docs/references.md, evaluation §1, procedural and deterministic.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <cstdint>

namespace shadowkit::scene {

// What the trees are made of: the standard scene's opaque blobs, or leafy trees of branches
// and alpha-tested leaf cards (leafy_trees.h).
enum class ForestKind : uint8_t { Simple, Leafy };

struct ForestOptions {
    ForestKind kind = ForestKind::Simple;
    uint64_t seed = 1;           // any value; same seed, same forest on every platform
    int trees = 10000;           // [0, 1,000,000]
    double terrainSize = 1024.0; // metres per side, (0, 100,000]
    int terrainResolution = 256; // quads per side, [1, 4096]
    double hillHeight = 30.0;    // metres from lowest to highest terrain point, [0, 1000]
    int rocks = 24;              // large casters, [0, 100,000]
    int buildings = 12;          // [0, 100,000]
    int movers = 6;              // dynamic objects near the origin, [0, 1000]
    double clearingRadius = 8.0; // metres around the origin kept free of trees, rocks and buildings
    // Leafy: the shadow passes' farthest level of each species an octahedral impostor (one card
    // facing the light, leafy_trees.h addImpostorLevel) in place of its coarsest cloud.
    bool impostors = false;
};

// Checks the ranges above; the message names the option.
core::Status validate(const ForestOptions& options);

// Terrain of gentle hills, trees, rocks, buildings and movers. Simple: two tree species
// (conifers: trunk + four cone layers; broadleaf: trunk + geodesic crown; each >= 200
// triangles) 6-20 m tall. Leafy: broadleaf trees 8–18 m, conifers 10–24 m and shrubs 1.5–3 m
// of leafyTrees.h, each species a wood batch and a leaf batch placed together, the leaf atlas
// Scene::textures[0] and its material Scene::materials[0]; the trees stand where the simple
// forest's of the same seed stand.
// Precondition: validate(options) succeeded.
Scene makeForest(const ForestOptions& options);

} // namespace shadowkit::scene
