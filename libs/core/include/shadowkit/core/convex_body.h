// Convex polyhedron as a list of planar polygonal faces, clipped by half-spaces.
//
// This is the representation the focus body B of the LiSPSM papers needs (Wimmer et al. 2004 §3.3,
// Scherzer 2005 §4.1): start from a box, clip it by planes, sweep it towards a light.
// Clipping is exact up to a tolerance scaled to the body's size, so the result is a true
// intersection of half-spaces rather than the "vertex + exit point" approximation of the
// 2004 LiSPSM demo (docs/references.md, pitfall 6).
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/conventions.h"
#include "shadowkit/core/plane.h"
#include "shadowkit/core/small_vector.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::core {

/// A convex polyhedron as a list of faces (point loops), clipped by planes: the focus body B and its pieces.
class ConvexBody {
public:
    /// Inline capacities: a box clipped by a frustum, its sweep and the scene box has about a
    /// dozen faces and fifty face corners (the flythrough's bodies: at most 20 and 90); beyond
    /// these sizes the containers spill to the heap (still correct, no longer allocation-free).
    using Points = SmallVector<Vec3, 48>;  ///< a set of vertices
    using Planes = SmallVector<Plane, 48>; ///< a set of planes, outward

    ConvexBody() = default; ///< the empty body
    /// The box as a body of six faces (an empty or flat box gives the empty body).
    static ConvexBody fromAabb(const Aabb& box);

    /// Moves every vertex by `offset` (exact up to the rounding of each sum).
    void translate(const Vec3& offset);

    /// Keeps the part of the body with plane.signedDistance(p) <= 0.
    void clip(const Plane& plane);
    /// Clips by every plane in turn: the intersection with their half-spaces.
    void clip(std::span<const Plane> planes);

    /// Planes whose intersection is the body swept to infinity along `wsDirection`
    /// (the Minkowski sum with the ray {t·dir, t >= 0}): the faces that do not face along
    /// the direction, plus one plane through each silhouette edge containing the
    /// direction. Intersect with a bounded body to use it.
    Planes sweepHalfSpaces(const Vec3& wsDirection) const;

    bool isEmpty() const { return m_faceEnds.empty(); }    ///< no volume left
    size_t faceCount() const { return m_faceEnds.size(); } ///< how many faces (0 for the empty body)
    /// Face f's points, counter-clockwise seen from outside (a convex polygon).
    std::span<const Vec3> face(size_t f) const {
        const size_t begin = f == 0 ? 0 : m_faceEnds[f - 1];
        return {m_points.data() + begin, m_faceEnds[f] - begin};
    }
    /// Each distinct vertex once.
    Points vertices() const;
    Aabb bounds() const; ///< the smallest box holding every vertex
    /// True if p lies inside every face plane, with a tolerance of eps metres.
    bool contains(const Vec3& p, double eps) const;
    double volume() const; ///< cubic metres (the divergence theorem over the faces)

private:
    double tolerance() const;
    void clip(const Plane& plane, double eps); ///< one cut, at a tolerance of eps metres
    void clear();                              ///< the empty body

    // The faces' loops one after another (a vertex shared by faces appears once in each):
    // face f is m_points[m_faceEnds[f - 1], m_faceEnds[f]). Flat, so a cut walks one array
    // and a copy is one block.
    SmallVector<Vec3, 128> m_points;
    SmallVector<uint32_t, 24> m_faceEnds;
};

} // namespace shadowkit::core
