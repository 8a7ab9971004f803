// Convex polyhedron clipping by the double description of a polytope: its vertices, each
// marked with the face planes it lies on.
//
// Based on: the body clipping used for the focus body B in Wimmer et al., "Light Space
// Perspective Shadow Maps" (EGSR 2004, §3.3), done as one step of the double description
// method (Motzkin et al. 1953; the combinatorial adjacency test of Fukuda & Prodon, "Double
// description method revisited", 1996; full citations in docs/references.md). A cut by a plane
// keeps the vertices inside it, marks those on it, and adds one vertex where each edge from a
// vertex inside to one outside crosses it. In three dimensions two vertices span an edge exactly
// when they share at least two face planes and no third vertex lies on all the planes they share
// (then it would lie on their line, between them or beyond). Nothing is merged or sorted: the
// marks are the structure, so a cut costs a few dozen bit operations per vertex pair instead of
// clipping every face as a polygon (docs/performance.md has the figures).
#include "shadowkit/core/convex_body.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace shadowkit::core {
namespace {

// Newell's method: robust normal (times twice the area) of a planar polygon.
Vec3 newellNormal(std::span<const Vec3> poly) {
    Vec3 n(0.0);
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[i + 1 == poly.size() ? 0 : i + 1];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n;
}

// Where the edge from `inside` (signed distance dIn < 0) to `outside` (dOut > 0) meets the
// plane.
Vec3 crossing(const Vec3& inside, double dIn, const Vec3& outside, double dOut) {
    const double t = dIn / (dIn - dOut); // |dIn - dOut| > 2 eps: no division by ~0
    return inside + t * (outside - inside);
}

// A pseudo-angle of (x, y): increases strictly with the angle from the direction (-1, -0)
// counter-clockwise, in [0, 4) — the order of atan2(y, x) over (-π, π] — from one division
// instead of a transcendental ("diamond angle": the position along the unit diamond
// |x| + |y| = 1 of the point's direction).
double pseudoAngle(double x, double y) {
    x = -x, y = -y; // start where atan2 does, at -π
    if (x == 0.0 && y == 0.0) return 0.0;
    if (y >= 0.0) return x >= 0.0 ? y / (x + y) : 1.0 - x / (y - x);
    return x < 0.0 ? 2.0 - y / (-x - y) : 3.0 + x / (x - y);
}

// Points lying on a plane of normal `normal`, counter-clockwise around it.
ConvexBody::Points orderedOnPlane(const ConvexBody::Points& points, const Vec3& normal) {
    if (points.size() < 3) return points;
    Vec3 centroid(0.0);
    for (const Vec3& p : points) centroid += p;
    centroid /= static_cast<double>(points.size());
    const Vec3 helper = std::abs(normal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 u = glm::normalize(glm::cross(helper, normal));
    const Vec3 v = glm::cross(normal, u); // u × v = normal: CCW about the normal
    struct Keyed {
        double angle;
        Vec3 point;
    };
    SmallVector<Keyed, 48> keyed;
    for (const Vec3& p : points) {
        const Vec3 d = p - centroid;
        keyed.push_back({pseudoAngle(glm::dot(d, u), glm::dot(d, v)), p});
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) { return a.angle < b.angle; });
    ConvexBody::Points out;
    for (const Keyed& k : keyed) out.push_back(k.point);
    return out;
}

} // namespace

std::array<Plane, 6> boxFaces(const Aabb& box) {
    // n·p + d = 0 on each, n outward.
    return {{{{-1, 0, 0}, box.min.x},
             {{1, 0, 0}, -box.max.x},
             {{0, -1, 0}, box.min.y},
             {{0, 1, 0}, -box.max.y},
             {{0, 0, -1}, box.min.z},
             {{0, 0, 1}, -box.max.z}}};
}

ConvexBody ConvexBody::fromAabb(const Aabb& box) {
    ConvexBody body;
    // A box flat along an axis has no volume: the empty body, as a cut to a sliver gives.
    if (box.isEmpty() || !(box.min.x < box.max.x && box.min.y < box.max.y && box.min.z < box.max.z)) return body;
    // Faces 0-5: -x, +x, -y, +y, -z, +z.
    for (const Plane& face : boxFaces(box)) body.m_planes.push_back(face);
    const auto c = box.corners(); // bit 0: x, bit 1: y, bit 2: z
    for (size_t i = 0; i < 8; ++i) {
        const PlaneSet on =
            PlaneSet(1) << (i & 1 ? 1 : 0) | PlaneSet(1) << (i & 2 ? 3 : 2) | PlaneSet(1) << (i & 4 ? 5 : 4);
        body.m_vertices.push_back({c[i], on});
    }
    return body;
}

double ConvexBody::tolerance() const {
    // Relative to the body's size and distance from the origin: coordinates of a
    // kilometre-wide scene carry ~1e-13 m of rounding in double.
    const Aabb b = bounds();
    if (b.isEmpty()) return 1e-12;
    const double magnitude = glm::length(b.extent()) + glm::length(glm::abs(b.center()));
    return 1e-12 * std::max(magnitude, 1.0);
}

void ConvexBody::clip(const Plane& plane) { clip(std::span<const Plane>(&plane, 1)); }

void ConvexBody::clip(std::span<const Plane> planes) {
    if (isEmpty()) return;
    // One tolerance for the whole intersection, that of the body it starts from: the body
    // only shrinks, so later cuts are judged at least as generously as the first.
    const double eps = tolerance();
    for (const Plane& plane : planes) {
        clip(plane, eps);
        if (isEmpty()) return;
    }
}

bool ConvexBody::adjacent(size_t a, size_t b) const {
    const PlaneSet shared = m_vertices[a].on & m_vertices[b].on;
    if ((shared & (shared - 1)) == 0) return false; // two planes at least make a line
    for (size_t w = 0; w < m_vertices.size(); ++w)
        if (w != a && w != b && (m_vertices[w].on & shared) == shared) return false; // a third on that line
    return true;
}

void ConvexBody::clip(const Plane& plane, double eps) {
    // Each vertex's signed distance once: inside (< -eps), on the plane, or outside (> eps).
    SmallVector<double, 48> distances;
    SmallVector<uint32_t, 48> inside, outside;
    for (size_t i = 0; i < m_vertices.size(); ++i) {
        const double dist = plane.signedDistance(m_vertices[i].p);
        distances.push_back(dist);
        if (dist > eps) outside.push_back(static_cast<uint32_t>(i));
        if (dist < -eps) inside.push_back(static_cast<uint32_t>(i));
    }
    if (outside.empty()) return; // entirely kept: the plane does not cut the body
    if (inside.empty()) {
        clear();
        return;
    } // at most a flat sliver remains
    SK_ASSERT(m_planes.size() < kMaxFaces, "ConvexBody::clip(): a body has at most kMaxFaces faces");
    const PlaneSet onCut = PlaneSet(1) << m_planes.size();

    // A new vertex on each edge from inside to outside, on the planes the edge lies on and the
    // cut; the faces that lose vertices outside are the only ones that may stop being faces.
    SmallVector<Vertex, 16> added;
    PlaneSet losing = 0;
    for (const uint32_t out : outside) {
        losing |= m_vertices[out].on;
        for (const uint32_t in : inside)
            if (adjacent(in, out))
                added.push_back({crossing(m_vertices[in].p, distances[in], m_vertices[out].p, distances[out]),
                                 (m_vertices[in].on & m_vertices[out].on) | onCut});
    }
    // The vertices kept, in place, those on the plane marked; then the new ones.
    size_t kept = 0;
    for (size_t i = 0; i < m_vertices.size(); ++i)
        if (distances[i] <= eps)
            m_vertices[kept++] = {m_vertices[i].p, m_vertices[i].on | (distances[i] >= -eps ? onCut : 0)};
    m_vertices.truncate(kept);
    for (const Vertex& v : added) m_vertices.push_back(v);
    m_planes.push_back(plane);
    keepOnlyFaces(losing);
    if (m_planes.size() < 4) clear(); // < 4 faces: no volume
}

void ConvexBody::keepOnlyFaces(PlaneSet candidates) {
    // A plane with fewer than three vertices on it only touches the body (at an edge or a
    // vertex, or not at all once cut away): it bounds no face. Counted a vertex's marks at a
    // time (a vertex lies on three or four planes).
    uint8_t count[kMaxFaces] = {};
    for (const Vertex& v : m_vertices)
        for (PlaneSet on = v.on & candidates; on != 0; on &= on - 1) ++count[std::countr_zero(on)];
    PlaneSet dropped = 0;
    for (size_t f = 0; f < m_planes.size(); ++f)
        if ((candidates & (PlaneSet(1) << f)) && count[f] < 3) dropped |= PlaneSet(1) << f;
    // Each dropped plane's bit taken out of every mark, the higher bits moved down one:
    // highest first, so the lower ones keep their places until their turn.
    for (size_t f = m_planes.size(); f-- > 0;) {
        if (!(dropped & (PlaneSet(1) << f))) continue;
        const PlaneSet below = (PlaneSet(1) << f) - 1;
        for (Vertex& v : m_vertices) v.on = (v.on & below) | ((v.on >> 1) & ~below);
        for (size_t g = f; g + 1 < m_planes.size(); ++g) m_planes[g] = m_planes[g + 1];
        m_planes.truncate(m_planes.size() - 1);
    }
}

void ConvexBody::clear() {
    m_vertices.clear();
    m_planes.clear();
}

ConvexBody::SweepFaces ConvexBody::sweepFaces(const Vec3& dir) const {
    // A face whose outward normal has no component along the sweep bounds the swept body
    // too; one facing along the sweep is swept away.
    SweepFaces sweep;
    SmallVector<double, kMaxFaces> along; // n·dir per face
    PlaneSet parallel = 0;                // faces along the sweep
    for (size_t f = 0; f < m_planes.size(); ++f) {
        along.push_back(glm::dot(m_planes[f].normal, dir));
        if (!(along[f] > 1e-12)) sweep.planes.push_back(m_planes[f]);
        if (along[f] < -1e-12)
            sweep.back |= PlaneSet(1) << f;
        else if (!(along[f] > 1e-12))
            parallel |= PlaneSet(1) << f;
    }
    // Silhouette edges join a face swept away (i) to one facing against the sweep (j); two
    // faces share an edge when two vertices lie on both, counted a vertex's marks at a time.
    // The swept body's facet there is the plane through the edge containing the sweep: its
    // normal m = -(n_j·d) n_i + (n_i·d) n_j has m·d = 0 and, a combination of the two faces'
    // normals with weights > 0, points out of the body. (Next to a face along the sweep the
    // silhouette's plane is that face's own, listed already.)
    const PlaneSet awayMask = ~sweep.back & ~parallel & facesMask();
    uint8_t shared[kMaxFaces][kMaxFaces]; // [swept away][facing against], only those pairs written
    for (PlaneSet i = awayMask; i != 0; i &= i - 1)
        for (PlaneSet j = sweep.back; j != 0; j &= j - 1) shared[std::countr_zero(i)][std::countr_zero(j)] = 0;
    struct FacePair {
        uint8_t i, j; // swept away, facing against
    };
    SmallVector<FacePair, 32> silhouettes; // once each
    for (const Vertex& v : m_vertices)
        for (PlaneSet i = v.on & awayMask; i != 0; i &= i - 1)
            for (PlaneSet j = v.on & sweep.back; j != 0; j &= j - 1) {
                const auto a = static_cast<uint8_t>(std::countr_zero(i)), b = static_cast<uint8_t>(std::countr_zero(j));
                if (++shared[a][b] == 2) silhouettes.push_back({a, b});
            }
    for (const auto [i, j] : silhouettes) {
        const Vec3 m = -along[j] * m_planes[i].normal + along[i] * m_planes[j].normal;
        const PlaneSet both = PlaneSet(1) << i | PlaneSet(1) << j;
        const Vertex* onEdge = &m_vertices[0];
        while ((onEdge->on & both) != both) ++onEdge;
        sweep.planes.push_back(Plane::fromPointNormal(onEdge->p, m));
    }
    return sweep;
}

ConvexBody::Planes ConvexBody::sweepHalfSpaces(const Vec3& wsDirection) const {
    if (isEmpty()) return {};
    return sweepFaces(glm::normalize(wsDirection)).planes;
}

ConvexBody ConvexBody::sweptUntil(const Vec3& wsDirection, const Plane& stop) const {
    ConvexBody swept;
    if (isEmpty()) return swept;
    const Vec3 dir = glm::normalize(wsDirection);
    const double stopAlong = glm::dot(stop.normal, dir);
    SK_ASSERT(stopAlong > 0.0, "ConvexBody::sweptUntil(): the stop plane must face along the sweep");
    const double eps = tolerance();

    // The swept body's faces, then the stop plane.
    const SweepFaces sweep = sweepFaces(dir);
    for (const Plane& plane : sweep.planes) swept.m_planes.push_back(plane);
    const PlaneSet back = sweep.back;
    SK_ASSERT(swept.m_planes.size() < kMaxFaces, "ConvexBody::sweptUntil(): a body has at most kMaxFaces faces");
    const size_t stopFace = swept.m_planes.size();
    swept.m_planes.push_back(stop);

    // Its vertices: the body's vertices on a face facing against the sweep (the others lie
    // inside the swept body or on its edges along the sweep), each marked with the planes it
    // lies on; and where each edge along the sweep — from a vertex on two planes containing the
    // sweep direction — meets the stop plane. A vertex already on the stop plane is its own end.
    for (const Vertex& v : m_vertices) {
        if (!(v.on & back)) continue;
        Vertex kept{v.p, 0};
        PlaneSet alongSweep = 0; // the planes through v containing the direction
        for (size_t f = 0; f < stopFace; ++f)
            if (std::abs(swept.m_planes[f].signedDistance(v.p)) <= eps) {
                kept.on |= PlaneSet(1) << f;
                if (!(std::abs(glm::dot(swept.m_planes[f].normal, dir)) > 1e-12)) alongSweep |= PlaneSet(1) << f;
            }
        const double toStop = stop.signedDistance(v.p); // <= 0: the body lies inside it
        if (toStop >= -eps) {
            kept.on |= PlaneSet(1) << stopFace;
            swept.m_vertices.push_back(kept);
            continue;
        }
        swept.m_vertices.push_back(kept);
        if ((alongSweep & (alongSweep - 1)) != 0) // two planes: an edge along the sweep starts here
            swept.m_vertices.push_back({v.p - (toStop / stopAlong) * dir, alongSweep | PlaneSet(1) << stopFace});
    }
    swept.keepOnlyFaces(~PlaneSet(0));
    if (swept.m_planes.size() < 4) swept.clear();
    return swept;
}

void ConvexBody::translate(const Vec3& offset) {
    for (Vertex& v : m_vertices) v.p += offset;
    for (Plane& plane : m_planes) plane.d -= glm::dot(plane.normal, offset);
}

ConvexBody::Points ConvexBody::face(size_t f) const {
    Points points;
    const PlaneSet bit = PlaneSet(1) << f;
    for (const Vertex& v : m_vertices)
        if (v.on & bit) points.push_back(v.p);
    return orderedOnPlane(points, m_planes[f].normal);
}

ConvexBody::Points ConvexBody::vertices() const {
    Points out;
    for (const Vertex& v : m_vertices) out.push_back(v.p);
    return out;
}

ConvexBody::Edges ConvexBody::edges() const {
    Edges out;
    for (size_t a = 0; a < m_vertices.size(); ++a)
        for (size_t b = a + 1; b < m_vertices.size(); ++b)
            if (adjacent(a, b)) out.push_back({m_vertices[a].p, m_vertices[b].p});
    return out;
}

Aabb ConvexBody::bounds() const {
    Aabb b;
    for (const Vertex& v : m_vertices) b.extend(v.p);
    return b;
}

Vec2 ConvexBody::rangeAlong(const Vec3& axis) const {
    Vec2 range(INFINITY, -INFINITY);
    for (const Vertex& v : m_vertices) {
        const double x = glm::dot(axis, v.p);
        range = Vec2(std::min(range.x, x), std::max(range.y, x));
    }
    return range;
}

bool ConvexBody::contains(const Vec3& p, double eps) const {
    if (isEmpty()) return false;
    return std::all_of(m_planes.begin(), m_planes.end(),
                       [&](const Plane& face) { return face.signedDistance(p) <= eps; });
}

double ConvexBody::volume() const {
    // Divergence theorem: V = 1/3 Σ_faces (point · area-weighted normal).
    double v = 0.0;
    for (size_t f = 0; f < faceCount(); ++f) {
        const Points loop = face(f);
        v += glm::dot(loop[0], 0.5 * newellNormal(std::span<const Vec3>(loop.data(), loop.size())));
    }
    return v / 3.0;
}

} // namespace shadowkit::core
