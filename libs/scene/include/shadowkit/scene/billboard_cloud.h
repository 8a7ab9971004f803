// Billboard clouds: the far level of a card mesh (Décoret, Durand, Sillion & Dorsey 2003,
// "Billboard Clouds for Extreme Model Simplification", SIGGRAPH).
//
// A canopy of thousands of leaf cards is, from far enough, a few planes of baked coverage.
// The paper finds planes that every triangle lies within ε of and projects each triangle onto
// its plane, one texture per plane; a shadow map then sees the planes from any light direction,
// which a view-dependent impostor (one quad turned to the viewer) cannot give a depth pass
// whose light is not the viewer. Here the planes come from a fixed family of orientations (the
// three axes and the four cube diagonals, so a card meets one within 36°) cut into parallel
// slabs, rather than the paper's greedy search: each card is turned about its centre into the
// best-aligned orientation, which keeps its area (so, averaged over light directions, the area
// its shadow covers), and moved along that normal onto the middle of its slab. A plane's texels
// hold the fraction of their area the moved cards cover (their own alpha test at the
// material's cutoff, 4 × 4 samples a texel), written as a dithered 0/255 alpha so that the
// alpha test at any cutoff keeps that fraction on average (a coverage-kept mip chain keeps it
// further). Deterministic.
#pragma once

#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <span>

namespace shadowkit::scene {

// What a cloud is baked from: the triangles `indices` of `mesh`. Alpha-tested sources read
// their coverage from `texture` at the vertices' uvs (alphaFactor × alpha ≥ cutoff, the texel
// nearest, wrapped as the texture says); opaque ones (wood, no texture) cover wherever they lie
// and give the texels their vertex colour.
struct CloudSource {
    const Mesh* mesh = nullptr;
    std::span<const uint32_t> indices;
    const Image* texture = nullptr; // alpha-tested sources: what their uvs index
    TextureWrap wrapS = TextureWrap::ClampToEdge, wrapT = TextureWrap::ClampToEdge;
    float alphaFactor = 1.0f; // the material's baseColorFactor alpha
};

struct BillboardCloudOptions {
    int slabsPerOrientation = 8; // parallel planes per orientation across the sources' extent, [1, 64]
    float alphaCutoff = 0.5f;    // the cards' material cutoff
};

struct BillboardCloud {
    std::vector<Vertex> vertices;  // four per plane, normal along the plane's orientation, uvs into the target
    std::vector<uint32_t> indices; // two triangles per plane, over `vertices` (0-based)
    // Mean distance, in object metres, a unit of covered area moved (turn + slab + half a
    // baked texel): the level's geometric error, as AuthoredLod::objectError.
    float objectError = 0.0f;
    int planes = 0;
    float texelsPerMetre = 0.0f; // of the baked planes, in object metres
    double coverage = 0.0;       // covered texels over the planes' texels, after dithering
};

// Builds the cloud of `sources` (all in one object space) and bakes it into `region` of
// `target` (RGBA8; the region is overwritten), the planes packed at the largest texel density
// that fits. Give the cloud a texture of its own (LodLevel::texture): mips of an atlas shared
// with dense cells blend the two at coarse levels. Precondition: the region lies inside the
// target, which is none of the sources' textures, and the sources' triangles index their
// meshes' vertices.
BillboardCloud bakeBillboardCloud(std::span<const CloudSource> sources, Image& target, ImageRegion region,
                                  const BillboardCloudOptions& options = {});

} // namespace shadowkit::scene
