// Convex polyhedron as its vertices and the face planes each lies on, clipped by half-spaces.
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

#include <array>
#include <cstdint>
#include <span>

namespace shadowkit::core {

/// A convex polyhedron, clipped by planes: the focus body B and its pieces. Held as its
/// vertices, each marked with the face planes it lies on (at most kMaxFaces faces).
class ConvexBody {
public:
    /// Inline capacities: a box clipped by a frustum, its sweep and the scene box has about a
    /// dozen faces and vertices (the flythrough's bodies: at most 20 faces); beyond these sizes
    /// the containers spill to the heap (still correct, no longer allocation-free).
    using Points = SmallVector<Vec3, 48>;  ///< a set of vertices
    using Planes = SmallVector<Plane, 48>; ///< a set of planes, outward
    /// An edge: the segment between two vertices.
    struct Segment {
        Vec3 a; ///< one end
        Vec3 b; ///< the other end
    };
    using Edges = SmallVector<Segment, 48>; ///< segments between vertices
    /// The most faces a body can have: one bit per face in each vertex's mark. The bodies this
    /// library builds have at most about 30 (a box cut by a frustum and by a sweep's planes).
    static constexpr size_t kMaxFaces = 64;

    ConvexBody() = default; ///< the empty body
    /// The box as a body of six faces (an empty or flat box gives the empty body).
    static ConvexBody fromAabb(const Aabb& box);

    /// Moves every vertex and face by `offset` (exact up to the rounding of each sum).
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

    /// The body swept along `wsDirection` as far as the plane `stop`, whose normal must point
    /// along the direction (stop.normal·dir > 0) and which the body must lie inside: the
    /// intersection of sweepHalfSpaces(dir) with stop's half-space, built at once — the body's
    /// vertices facing against the sweep, and where each edge along the sweep meets `stop` —
    /// instead of cut plane by plane out of a larger body.
    ConvexBody sweptUntil(const Vec3& wsDirection, const Plane& stop) const;

    bool isEmpty() const { return m_vertices.empty(); }  ///< no volume left
    size_t faceCount() const { return m_planes.size(); } ///< how many faces (0 for the empty body)
    /// Face f's vertices, counter-clockwise seen from outside (a convex polygon).
    Points face(size_t f) const;
    /// Each vertex once.
    Points vertices() const;
    /// Each edge once, as its two end vertices.
    Edges edges() const;
    Aabb bounds() const; ///< the smallest box holding every vertex
    /// The least and the greatest of axis·p over the vertices (axis need not be a unit vector):
    /// the body's extent along it, without copying the vertices out. Empty body: (+inf, -inf).
    Vec2 rangeAlong(const Vec3& axis) const;
    /// True if p lies inside every face plane, with a tolerance of eps metres.
    bool contains(const Vec3& p, double eps) const;
    double volume() const; ///< cubic metres (the divergence theorem over the faces)

private:
    friend class ConvexBodyStructure; // re-solves a body from its marks (convex_body_structure.h)
    using PlaneSet = uint64_t;        ///< bit f: on the plane of face f
    struct Vertex {
        Vec3 p;
        PlaneSet on = 0;
    };

    double tolerance() const;
    void clip(const Plane& plane, double eps); ///< one cut, at a tolerance of eps metres
    void keepOnlyFaces(PlaneSet candidates);   ///< drops those of the candidate planes that hold no face
    bool adjacent(size_t a, size_t b) const;   ///< whether vertices a and b span an edge
    /// Every face's bit.
    struct SweepFaces {
        Planes planes;     ///< sweepHalfSpaces()
        PlaneSet back = 0; ///< the faces facing against the sweep
    };
    SweepFaces sweepFaces(const Vec3& dir) const; ///< the swept body's planes, dir of unit length
    PlaneSet facesMask() const { return m_planes.size() == 64 ? ~PlaneSet(0) : (PlaneSet(1) << m_planes.size()) - 1; }
    void clear(); ///< the empty body

    SmallVector<Vertex, 48> m_vertices;
    SmallVector<Plane, kMaxFaces> m_planes; // the faces' planes, outward; bit f of a mark is m_planes[f]
};

/// The box's six face planes, outward: -x, +x, -y, +y, -z, +z.
std::array<Plane, 6> boxFaces(const Aabb& box);

} // namespace shadowkit::core
