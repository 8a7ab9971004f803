// The hemi-octahedral map: the directions of the upper hemisphere (+y up) onto the unit square,
// as octahedral impostors index their frames by the direction a tree is seen from (Brucks 2018,
// "Octahedral Impostors"; the map itself: Cigolle, Donow, Evangelakos, Mara, McGuire & Meyer
// 2014, "A Survey of Efficient Representations for Independent Unit Vectors", JCGT 3(2), §3.6).
//
// A direction d = (x, y, z), y ≥ 0, is scaled onto the octahedron |x| + |y| + |z| = 1, whose
// upper half seen from above is the square |x| + |z| ≤ 1 turned by 45°; turned back and moved
// to [0, 1]²:
//
//     p = d / (|x| + |y| + |z|),    uv = ((p.x + p.z) / 2 + 1/2,  (p.x − p.z) / 2 + 1/2).
//
// The zenith lands at the square's middle, the horizon on its edge, and every point of the
// square is one direction: the inverse takes x = (u' + v') / 2, z = (u' − v') / 2 with
// u' = 2u − 1, v' = 2v − 1, y = 1 − |x| − |z| ≥ 0, and normalises. The map is continuous; the
// cells of an even grid over the square differ in solid angle (the octahedron's faces are flat,
// the sphere is not: ×4.2 between the largest and the smallest of a 16 × 16 grid), and a
// direction lies up to 22.2°, 17.3°, 11.5°, 8.7° or 4.4° from the middle of its cell in a grid of
// 6, 8, 12, 16 or 32 cells a side (the farthest at the cells' corners; measured on a lattice of
// 120 points a cell side and more).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace shadowkit::core {

/// The point of [0, 1]² that `direction` (any length) maps to. A direction below the horizon
/// (y < 0) maps as its horizontal part does, onto the square's edge: an impostor seen from
/// below is seen from the horizon; straight down, with no horizontal part, maps to (1, 1), the
/// horizon towards +x, and a zero or non-finite vector to the zenith's (0.5, 0.5).
glm::vec2 hemiOctahedralFromDirection(glm::vec3 direction);

/// The unit direction of the upper hemisphere that `uv` maps to; `uv` is clamped to [0, 1]²
/// first (a non-finite component reads 0.5).
glm::vec3 directionFromHemiOctahedral(glm::vec2 uv);

} // namespace shadowkit::core
