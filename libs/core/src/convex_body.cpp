// Convex polyhedron clipping (Sutherland–Hodgman per face plus a cap polygon).
//
// Based on: the body-clipping used for the focus body B in Wimmer et al., "Light Space
// Perspective Shadow Maps" (EGSR 2004, §3.3), written here from the definition:
// each face polygon is clipped against the plane, and the points that land on the plane
// are joined into the new cap face. The faces are stored one after another in one array, so a
// cut is a walk over it and a copy one block (a focus body costs a few microseconds a frame:
// docs/performance.md).
#include "shadowkit/core/convex_body.h"

#include <algorithm>
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

bool hasArea(std::span<const Vec3> poly, double eps) {
    return poly.size() >= 3 && glm::length(newellNormal(poly)) > eps * eps;
}

template <class Points>
void appendUnique(Points& points, const Vec3& p, double eps) {
    const double eps2 = eps * eps; // compared squared: no square root per pair
    for (const Vec3& q : points) {
        const Vec3 d = q - p;
        if (glm::dot(d, d) <= eps2) return;
    }
    points.push_back(p);
}

// Where the edge from `inside` (signed distance dIn < 0) to `outside` (dOut > 0) meets the
// plane. Always computed from the inside end, so the two faces sharing the edge get the same
// point to the last bit: shared vertices stay copies of one another.
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

// Appends points lying on a plane of normal `normal` to `out`, counter-clockwise around it.
template <class Out>
void appendOrderedOnPlane(std::span<const Vec3> points, const Vec3& normal, Out& out) {
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
    SmallVector<Keyed, 24> keyed;
    for (const Vec3& p : points) {
        const Vec3 d = p - centroid;
        keyed.push_back({pseudoAngle(glm::dot(d, u), glm::dot(d, v)), p});
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) { return a.angle < b.angle; });
    for (const Keyed& k : keyed) out.push_back(k.point);
}

} // namespace

ConvexBody ConvexBody::fromAabb(const Aabb& box) {
    ConvexBody body;
    // A box flat along an axis has no volume: the empty body, as a cut to a sliver gives.
    if (box.isEmpty() || !(box.min.x < box.max.x && box.min.y < box.max.y && box.min.z < box.max.z)) return body;
    const auto c = box.corners(); // bit 0: x, bit 1: y, bit 2: z
    // Each face listed counter-clockwise seen from outside.
    constexpr size_t faces[6][4] = {
        {0, 4, 6, 2}, // -x
        {1, 3, 7, 5}, // +x
        {0, 1, 5, 4}, // -y
        {2, 6, 7, 3}, // +y
        {0, 2, 3, 1}, // -z
        {4, 5, 7, 6}, // +z
    };
    for (const auto& f : faces) {
        for (const size_t corner : f) body.m_points.push_back(c[corner]);
        body.m_faceEnds.push_back(static_cast<uint32_t>(body.m_points.size()));
    }
    return body;
}

double ConvexBody::tolerance() const {
    // Relative to the body's size and distance from the origin: coordinates of a
    // kilometre-wide scene carry ~1e-13 m of rounding in double.
    const Aabb b = bounds();
    if (b.isEmpty()) return 1e-12;
    const double magnitude = glm::length(b.extent()) + glm::length(glm::abs(b.center()));
    return 1e-10 * std::max(magnitude, 1.0);
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

void ConvexBody::clip(const Plane& plane, double eps) {
    // Each face corner's signed distance once.
    SmallVector<double, 128> distances;
    bool anyOutside = false, anyInside = false;
    for (const Vec3& p : m_points) {
        const double dist = plane.signedDistance(p);
        distances.push_back(dist);
        anyOutside |= dist > eps;
        anyInside |= dist < -eps;
    }
    if (!anyOutside) return; // entirely kept: the plane does not cut the body
    if (!anyInside) {
        clear();
        return;
    } // at most a flat sliver remains

    // Each face clipped (Sutherland–Hodgman), the points on the plane gathered for the cap.
    decltype(m_points) points;
    decltype(m_faceEnds) faceEnds;
    SmallVector<Vec3, 24> capPoints;
    auto closeFace = [&](size_t start) {
        if (hasArea(std::span(points.data() + start, points.size() - start), eps))
            faceEnds.push_back(static_cast<uint32_t>(points.size()));
        else
            points.truncate(start); // a face cut down to a sliver
    };
    size_t begin = 0;
    for (const uint32_t end : m_faceEnds) {
        const size_t start = points.size();
        if (std::all_of(distances.begin() + begin, distances.begin() + end, [&](double d) { return d < -eps; })) {
            // Wholly inside, no corner on the plane: the face stays as it is (and keeps its area).
            for (size_t i = begin; i < end; ++i) points.push_back(m_points[i]);
            faceEnds.push_back(static_cast<uint32_t>(points.size()));
            begin = end;
            continue;
        }
        for (size_t i = begin; i < end; ++i) {
            const size_t next = i + 1 == end ? begin : i + 1;
            const double dc = distances[i], dn = distances[next];
            if (dc <= eps) {
                points.push_back(m_points[i]);
                if (dc >= -eps) appendUnique(capPoints, m_points[i], eps);
            }
            if (dc < -eps && dn > eps) {
                points.push_back(crossing(m_points[i], dc, m_points[next], dn));
                appendUnique(capPoints, points.back(), eps);
            } else if (dc > eps && dn < -eps) {
                points.push_back(crossing(m_points[next], dn, m_points[i], dc));
                appendUnique(capPoints, points.back(), eps);
            }
        }
        closeFace(start);
        begin = end;
    }
    if (capPoints.size() >= 3) {
        const size_t start = points.size();
        appendOrderedOnPlane(std::span<const Vec3>(capPoints.data(), capPoints.size()), plane.normal, points);
        closeFace(start);
    }
    if (faceEnds.size() < 4) { // < 4 faces: no volume
        clear();
        return;
    }
    m_points = std::move(points);
    m_faceEnds = std::move(faceEnds);
}

void ConvexBody::clear() {
    m_points.clear();
    m_faceEnds.clear();
}

ConvexBody::Planes ConvexBody::sweepHalfSpaces(const Vec3& wsDirection) const {
    Planes planes;
    if (isEmpty()) return planes;
    const Vec3 dir = glm::normalize(wsDirection);
    const double eps = tolerance();
    const Points verts = vertices();

    // A face whose outward normal has no component along the sweep bounds the swept body
    // too; one facing along the sweep is swept away.
    SmallVector<char, 32> sweptAway; // per face (char: SmallVector<bool> would have no data())
    for (size_t f = 0; f < faceCount(); ++f) {
        const std::span<const Vec3> poly = face(f);
        const Vec3 n = glm::normalize(newellNormal(poly));
        const bool away = glm::dot(n, dir) > 1e-12;
        sweptAway.push_back(away);
        if (!away) planes.push_back(Plane::fromPointNormal(poly[0], n));
    }
    // Silhouette edges: a plane through the edge containing the sweep direction is a facet of
    // the swept body exactly when the whole body lies on one side of it. A silhouette edge
    // joins a face swept away to one that is not, so the edges of the faces swept away are
    // all the candidates (each silhouette found once, from its swept side).
    for (size_t f = 0; f < faceCount(); ++f) {
        if (!sweptAway[f]) continue;
        const std::span<const Vec3> poly = face(f);
        for (size_t i = 0; i < poly.size(); ++i) {
            const Vec3& a = poly[i];
            const Vec3& b = poly[i + 1 == poly.size() ? 0 : i + 1];
            const Vec3 m = glm::cross(b - a, dir);
            if (glm::length(m) <= eps) continue; // edge parallel to the sweep
            const Plane plane = Plane::fromPointNormal(a, m);
            double lo = 0.0, hi = 0.0;
            for (const Vec3& v : verts) {
                const double dist = plane.signedDistance(v);
                lo = std::min(lo, dist);
                hi = std::max(hi, dist);
                if (lo < -eps && hi > eps) break; // vertices on both sides: not a facet
            }
            if (hi <= eps)
                planes.push_back(plane);
            else if (lo >= -eps)
                planes.push_back({-plane.normal, -plane.d});
        }
    }
    return planes;
}

void ConvexBody::translate(const Vec3& offset) {
    for (Vec3& p : m_points) p += offset;
}

ConvexBody::Points ConvexBody::vertices() const {
    // A vertex shared by faces is, but for near-coincident points met in one cut, the same
    // bits in each (crossing() makes it so): drop exact copies first, three compares each,
    // then merge what lies within the tolerance among the few left. The same points, in the
    // same order, as merging the whole list at the tolerance.
    Points distinct;
    for (const Vec3& p : m_points)
        if (std::none_of(distinct.begin(), distinct.end(), [&](const Vec3& q) { return q == p; }))
            distinct.push_back(p);
    Points out;
    const double eps = tolerance();
    for (const Vec3& p : distinct) appendUnique(out, p, eps);
    return out;
}

Aabb ConvexBody::bounds() const {
    Aabb b;
    for (const Vec3& p : m_points) b.extend(p);
    return b;
}

bool ConvexBody::contains(const Vec3& p, double eps) const {
    if (isEmpty()) return false;
    for (size_t f = 0; f < faceCount(); ++f) {
        const std::span<const Vec3> poly = face(f);
        const Vec3 n = glm::normalize(newellNormal(poly));
        if (glm::dot(n, p - poly[0]) > eps) return false;
    }
    return true;
}

double ConvexBody::volume() const {
    // Divergence theorem: V = 1/3 Σ_faces (point · area-weighted normal).
    double v = 0.0;
    for (size_t f = 0; f < faceCount(); ++f) {
        const std::span<const Vec3> poly = face(f);
        v += glm::dot(poly[0], 0.5 * newellNormal(poly));
    }
    return v / 3.0;
}

} // namespace shadowkit::core
