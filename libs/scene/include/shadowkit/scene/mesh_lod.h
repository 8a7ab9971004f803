// Levels of detail of a mesh: simplified index buffers over the mesh's own vertices, each
// with the geometric error it introduces, for the camera pass (attributes respected) and
// for shadow passes (positions only: normals and colours do not reach a depth map).
#pragma once

#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <vector>

namespace shadowkit::scene {

struct LodLevel {
    uint32_t firstIndex = 0; // into MeshLods::indices
    uint32_t indexCount = 0;
    // Largest distance, in object-space metres, between the simplified surface and the
    // original (meshoptimizer's error bound times the mesh's extent). 0 for the full mesh.
    float objectError = 0.0f;
    // Shadow chain: the level bounds solids (closed_surface.h), so a depth pass may cull the
    // faces turned away from the light and store the same depth. Always false in the camera chain.
    bool closed = false;
    // The level keeps what the mesh covers seen from afar — its leaves' area, their coverage
    // baked into planes — rather than its surface (leaf cards, billboard clouds: authored
    // levels that say so). Passes may let it move that coverage further than a surface
    // (RenderSettings::lodFoliageScale): under a pixel a leaf's exact place is noise, its
    // share of the pixel is not.
    bool keepsCoverage = false;
    // The level's own base-colour texture (an index into Scene::textures; a billboard cloud's
    // baked planes), read in place of its material's; -1: the material's. Its own texture, not a
    // part of the material's atlas: coarse mips of a shared atlas blend neighbouring parts, and
    // a sparse part thins the cells beside it.
    int32_t texture = -1;
    // The level is an impostor's card (scene.h, ImpostorCard), turned to each pass's viewer by its
    // vertex stage; shadow chain only.
    ImpostorCard impostor{};
};

struct MeshLods {
    std::vector<uint32_t> indices; // every level's triangles, back to back; level 0 first
    std::vector<LodLevel> camera;  // camera[0] is the full mesh
    std::vector<LodLevel> shadow;  // shadow[0] is the full mesh
};

struct LodOptions {
    // Each level aims at this fraction of the previous one's triangles...
    float reduction = 0.5f; // (0, 1)
    // ... without exceeding this error, relative to the mesh's extent (meshoptimizer's
    // target_error); a level that saves less than 20 % of its predecessor ends the chain.
    // Coarse levels are safe to offer: a pass only picks a level whose error projects to
    // under its bound (a fraction of a pixel or texel), i.e. for tiny instances.
    float maxRelativeError = 0.5f;
    int maxLevels = 4; // including the full mesh, [1, 8]
    // A mesh's own levels (Mesh::authoredLods), the full mesh included, are kept up to this
    // many: the leafy trees bring four billboard clouds. [1, 8]
    int maxAuthoredLevels = 5;
    // Meshes above this size keep one level: the terrain is one instance, near everything.
    size_t maxTriangles = 65536;
};

// Deterministic for a given mesh and options. A mesh with authored levels (Mesh::authoredLods)
// gets those, each in the chains of the passes it names, up to maxAuthoredLevels a chain.
// Precondition: an impostor's level names the shadow passes alone.
MeshLods buildLods(const Mesh& mesh, const LodOptions& options = {});

} // namespace shadowkit::scene
