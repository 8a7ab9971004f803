// Octahedral impostors: the farthest level of a tree as pictures of it, one for each of a grid
// of directions over the upper hemisphere (Brucks 2018, "Octahedral Impostors"; the grid is the
// hemi-octahedral map of core/octahedral.h).
//
// A billboard cloud (billboard_cloud.h) keeps a tree's leaves on a few dozen shared planes, and
// a conifer's needle sprays, lying within 20° of flat, are turned flat onto them: seen from the
// side the cloud shows ×0.68–0.76 of the tree's area, and no cloud of shared planes came near a
// coverage IoU of 0.9 there (docs/materials.md). A picture of the tree taken from the direction
// it is seen from cannot lose what that direction sees. Here frame f is the tree drawn
// orthographically along its direction d_f (from the tree towards the viewer) onto a square of
// side 2r through the centre c of the sphere (c, r) that holds every vertex, its texels the
// fraction of 16 samples the tree's triangles cover under their own alpha test, dithered to
// 0/255 (as the clouds' planes are). Its *card* is that square placed in the object's space,
// facing d_f: a viewer along v draws the card of the frame whose cell v's hemi-octahedral point
// lies in.
//
// The error. A point p at depth z = (p − c)·d_f from the card's plane is drawn where p − z·d_f
// lies; seen along v, at angle α to d_f, the two differ by |z| sin α across the view. With |z|
// ≤ r and α at most the grid's largest angle from a direction to its cell's middle (maxTurn:
// 8.7° for 16 frames a side), the level errs by at most r sin(maxTurn) plus half a texel —
// a bound, where the clouds' error is a mean: an impostor is for trees a few pixels wide.
// Deterministic: the frames bake in parallel, each into its own texels.
#pragma once

#include "shadowkit/scene/billboard_cloud.h"
#include "shadowkit/scene/image.h"

#include <span>

namespace shadowkit::scene {

struct OctahedralImpostorOptions {
    int framesPerSide = 16;   // frames along each side of the hemi-octahedral grid, [1, 64]
    int texelsPerFrame = 128; // texels along each side of a frame, the outermost one open, [8, 2048]
    float alphaCutoff = 0.5f; // the cards' material cutoff
};

struct OctahedralImpostor {
    int framesPerSide = 0, texelsPerFrame = 0;
    glm::vec3 osCentre{0.0f}; // the sphere every frame's square holds, object space
    float osRadius = 0.0f;
    // Frame f's card: vertices [4f, 4f + 4) (a square of side 2·osRadius through osCentre,
    // its normal the frame's direction, uvs into the target) and indices [6f, 6f + 6) (two
    // triangles, 0-based). Frame f = j · framesPerSide + i lies in cell (i, j) of the grid: i
    // along the map's u, j along its v.
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    float maxTurn = 0.0f;     // radians: the largest angle from a direction to its frame's
    float objectError = 0.0f; // osRadius · sin(maxTurn) + half a texel, object metres
    double coverage = 0.0;    // kept texels over the frames' inner texels
};

// Bakes the impostor of `sources` (one object space) into `region` of `target` (RGBA8; the
// region is overwritten), frame (i, j) at (region.x + i·texelsPerFrame, region.y +
// j·texelsPerFrame). Precondition: the region is framesPerSide · texelsPerFrame texels square
// and lies inside the target, which is none of the sources' textures; the options in range.
OctahedralImpostor bakeOctahedralImpostor(std::span<const CloudSource> sources, Image& target, ImageRegion region,
                                          const OctahedralImpostorOptions& options = {});

// The frame drawn for a viewer in `osToViewer` (object space, from the object towards the
// viewer or, for a light, towards the light; any length): the grid cell its hemi-octahedral point lies in.
int impostorFrame(int framesPerSide, glm::vec3 osToViewer);

// Frame f's direction: the middle of its cell, as a unit vector of the upper hemisphere.
glm::vec3 impostorFrameDirection(int framesPerSide, int frame);

} // namespace shadowkit::scene
