// Convex polyhedron clipping (Sutherland–Hodgman per face plus a cap polygon).
//
// Based on: the body-clipping used for the focus body B in Wimmer et al., "Light Space
// Perspective Shadow Maps" (EGSR 2004, §3.3), written here from the definition:
// each face polygon is clipped against the plane, and the points that land on the plane
// are joined into the new cap face.
#include "shadowkit/core/convex_body.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::core {
namespace {

// Newell's method: robust normal (times twice the area) of a planar polygon.
Vec3 newellNormal(const ConvexBody::Polygon& poly) {
    Vec3 n(0.0);
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n;
}

template <class Points>
void appendUnique(Points& points, const Vec3& p, double eps) {
    for (const Vec3& q : points)
        if (glm::length(q - p) <= eps) return;
    points.push_back(p);
}

// Orders points lying on `plane` counter-clockwise around its normal.
ConvexBody::Polygon orderOnPlane(ConvexBody::Polygon points, const Vec3& normal) {
    Vec3 centroid(0.0);
    for (const Vec3& p : points) centroid += p;
    centroid /= static_cast<double>(points.size());
    const Vec3 helper = std::abs(normal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 u = glm::normalize(glm::cross(helper, normal));
    const Vec3 v = glm::cross(normal, u); // u × v = normal: CCW about the normal
    // Sort by angle, each angle computed once (the comparisons, and so the order, are the
    // same as comparing freshly computed angles).
    struct Keyed {
        double angle;
        Vec3 point;
    };
    SmallVector<Keyed, 16> keyed;
    for (const Vec3& p : points) {
        const Vec3 d = p - centroid;
        keyed.push_back({std::atan2(glm::dot(d, v), glm::dot(d, u)), p});
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) { return a.angle < b.angle; });
    ConvexBody::Polygon ordered;
    for (const Keyed& k : keyed) ordered.push_back(k.point);
    return ordered;
}

} // namespace

ConvexBody ConvexBody::fromAabb(const Aabb& box) {
    ConvexBody body;
    if (box.isEmpty()) return body;
    const auto c = box.corners(); // bit 0: x, bit 1: y, bit 2: z
    // Each face listed counter-clockwise seen from outside.
    const int faces[6][4] = {
        {0, 4, 6, 2}, // -x
        {1, 3, 7, 5}, // +x
        {0, 1, 5, 4}, // -y
        {2, 6, 7, 3}, // +y
        {0, 2, 3, 1}, // -z
        {4, 5, 7, 6}, // +z
    };
    for (const auto& f : faces)
        body.m_faces.push_back(Polygon{c[static_cast<size_t>(f[0])], c[static_cast<size_t>(f[1])],
                                       c[static_cast<size_t>(f[2])], c[static_cast<size_t>(f[3])]});
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

void ConvexBody::clip(const Plane& plane) {
    if (isEmpty()) return;
    const double eps = tolerance();

    bool anyOutside = false, anyInside = false;
    for (const Polygon& face : m_faces)
        for (const Vec3& p : face) {
            const double dist = plane.signedDistance(p);
            anyOutside |= dist > eps;
            anyInside |= dist < -eps;
        }
    if (!anyOutside) return; // entirely kept
    if (!anyInside) {
        m_faces.clear();
        return;
    } // at most a flat sliver remains

    Faces kept;
    Polygon capPoints;
    for (const Polygon& face : m_faces) {
        Polygon out;
        for (size_t i = 0; i < face.size(); ++i) {
            const Vec3& cur = face[i];
            const Vec3& next = face[(i + 1) % face.size()];
            const double dc = plane.signedDistance(cur);
            const double dn = plane.signedDistance(next);
            if (dc <= eps) {
                out.push_back(cur);
                if (dc >= -eps) appendUnique(capPoints, cur, eps);
            }
            if ((dc < -eps && dn > eps) || (dc > eps && dn < -eps)) {
                const double t = dc / (dc - dn); // |dc - dn| > 2 eps: no division by ~0
                const Vec3 hit = cur + t * (next - cur);
                out.push_back(hit);
                appendUnique(capPoints, hit, eps);
            }
        }
        if (out.size() >= 3 && glm::length(newellNormal(out)) > eps * eps) kept.push_back(std::move(out));
    }
    if (capPoints.size() >= 3) {
        Polygon cap = orderOnPlane(std::move(capPoints), plane.normal);
        if (glm::length(newellNormal(cap)) > eps * eps) kept.push_back(std::move(cap));
    }
    if (kept.size() >= 4)
        m_faces = std::move(kept);
    else
        m_faces.clear(); // < 4 faces: no volume
}

void ConvexBody::clip(std::span<const Plane> planes) {
    for (const Plane& p : planes) clip(p);
}

ConvexBody::Planes ConvexBody::sweepHalfSpaces(const Vec3& wsDirection) const {
    Planes planes;
    if (isEmpty()) return planes;
    const Vec3 dir = glm::normalize(wsDirection);
    const double eps = tolerance();
    const Points verts = vertices();

    for (const Polygon& face : m_faces) {
        const Vec3 n = glm::normalize(newellNormal(face));
        // A face whose outward normal has no component along the sweep bounds the swept
        // body too; one facing along the sweep is swept away.
        if (glm::dot(n, dir) <= 1e-12) planes.push_back(Plane::fromPointNormal(face[0], n));
    }
    // Silhouette edges: a plane through the edge containing the sweep direction is a
    // facet of the swept body exactly when the whole body lies on one side of it.
    for (const Polygon& face : m_faces) {
        for (size_t i = 0; i < face.size(); ++i) {
            const Vec3& a = face[i];
            const Vec3& b = face[(i + 1) % face.size()];
            const Vec3 m = glm::cross(b - a, dir);
            if (glm::length(m) <= eps) continue; // edge parallel to the sweep
            Plane plane = Plane::fromPointNormal(a, m);
            double lo = 0.0, hi = 0.0;
            for (const Vec3& v : verts) {
                const double dist = plane.signedDistance(v);
                lo = std::min(lo, dist);
                hi = std::max(hi, dist);
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
    for (Polygon& face : m_faces)
        for (Vec3& p : face) p += offset;
}

ConvexBody::Points ConvexBody::vertices() const {
    Points out;
    const double eps = tolerance();
    for (const Polygon& face : m_faces)
        for (const Vec3& p : face) appendUnique(out, p, eps);
    return out;
}

Aabb ConvexBody::bounds() const {
    Aabb b;
    for (const Polygon& face : m_faces)
        for (const Vec3& p : face) b.extend(p);
    return b;
}

bool ConvexBody::contains(const Vec3& p, double eps) const {
    if (isEmpty()) return false;
    for (const Polygon& face : m_faces) {
        const Vec3 n = glm::normalize(newellNormal(face));
        if (glm::dot(n, p - face[0]) > eps) return false;
    }
    return true;
}

double ConvexBody::volume() const {
    // Divergence theorem: V = 1/3 Σ_faces (point · area-weighted normal).
    double v = 0.0;
    for (const Polygon& face : m_faces) v += glm::dot(face[0], 0.5 * newellNormal(face));
    return v / 3.0;
}

} // namespace shadowkit::core
