// Whether a triangle list is the outward boundary of a solid, so that a depth pass may leave
// out its faces turned away from the light.
//
// Along any ray from outside, the first surface of a solid met is where the ray enters it: a
// face whose outward normal points back along the ray. A light's depth map stores, per texel,
// that first surface; so for a mesh that bounds solids the map is the same with the faces turned
// away from the light culled — which halves the samples a depth pass writes (docs/performance.md,
// "Work: samples written per shadow-map texel"). For an open surface (a card, a terrain patch, a
// mesh the shadow chain's vertex clustering has opened) the back of a face may be the first
// surface a ray meets, so those draw both sides.
#pragma once

#include "shadowkit/scene/scene.h"

#include <cstdint>
#include <span>

namespace shadowkit::scene {

// True when the triangles of `indices` (over `mesh`'s vertices, welded by position: seams of
// split normals or uvs do not open a surface) form closed, consistently wound shells, each
// enclosing a positive volume with its counter-clockwise faces outward. Precisely: every
// directed edge of a non-degenerate triangle occurs once and its reverse once (a watertight,
// edge-manifold, oriented surface), and every connected shell's signed volume is positive.
// Conservative: a cavity (a shell enclosing negative volume), two shells touching along an edge
// and a two-sided card (two opposite triangles over the same corners, volume 0) count as open.
// Triangles with two corners at one position have no area and are skipped.
bool boundsSolid(const Mesh& mesh, std::span<const uint32_t> indices);

} // namespace shadowkit::scene
