// Re-solving a convex body from last frame's combinatorial structure.
//
// The double description (convex_body.cpp; Motzkin et al. 1953, Fukuda & Prodon 1996) holds a
// body as its vertices marked with the face planes they lie on. From one frame to the next the
// focus body's planes move a little and its marks mostly do not: the same triples of planes
// meet at its corners. This is the "reuse across frames" of the real-time issue: keep the
// marks, solve each vertex from its three planes (Cramer's rule, one division), and accept the
// result only where the proof in convex_body_structure.h holds, which costs a signed distance
// per vertex and plane — a fraction of clipping the body again.
#include "shadowkit/core/convex_body_structure.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace shadowkit::core {
namespace {

// Strictly inside means farther from a plane than this times the definition's largest distance
// from the origin: about a thousand times the clipping tolerance (ConvexBody::tolerance, 1e-12 of
// the body's size and distance from the origin), so a vertex accepted here is one that clipping
// afresh would also have found on its three planes only.
constexpr double kStrictMargin = 1e-9;
// Three planes whose normals span less than this volume meet at an ill-conditioned point.
constexpr double kMinDeterminant = 1e-9;

bool valueBefore(const Plane& a, const Plane& b) {
    if (a.normal.x != b.normal.x) return a.normal.x < b.normal.x;
    if (a.normal.y != b.normal.y) return a.normal.y < b.normal.y;
    if (a.normal.z != b.normal.z) return a.normal.z < b.normal.z;
    return a.d < b.d;
}

bool onThreePlanes(uint64_t marks) {
    marks &= marks - 1;
    marks &= marks - 1; // the lowest two dropped: one left
    return marks != 0 && (marks & (marks - 1)) == 0;
}

bool samePlane(const Plane& a, const Plane& b) { return a.normal == b.normal && a.d == b.d; }

// Where three planes meet, or nothing when they are nearly dependent. The planes are taken in the
// order of their values, so the point does not depend on the order they are named in.
std::optional<Vec3> meet(Plane a, Plane b, Plane c) {
    if (valueBefore(b, a)) std::swap(a, b);
    if (valueBefore(c, b)) std::swap(b, c);
    if (valueBefore(b, a)) std::swap(a, b);
    const Vec3 bc = glm::cross(b.normal, c.normal), ca = glm::cross(c.normal, a.normal),
               ab = glm::cross(a.normal, b.normal);
    const double det = glm::dot(a.normal, bc);
    if (!(std::abs(det) > kMinDeterminant)) return std::nullopt;
    return -(a.d * bc + b.d * ca + c.d * ab) / det;
}

} // namespace

void ConvexBodyStructure::clear() {
    m_faces.clear();
    m_vertices.clear();
    m_faceOf.clear();
    m_sameAs.clear();
}

bool ConvexBodyStructure::remember(const ConvexBody& body, std::span<const Plane> definition) {
    clear();
    if (body.isEmpty() || definition.size() >= kNone) return false;
    for (size_t k = 0; k < definition.size(); ++k) m_faceOf.push_back(kNone), m_sameAs.push_back(kNone);
    for (const Plane& face : body.m_planes) {
        const auto it =
            std::find_if(definition.begin(), definition.end(), [&](const Plane& p) { return samePlane(p, face); });
        if (it == definition.end()) return clear(), false;
        m_faceOf[size_t(it - definition.begin())] = static_cast<uint8_t>(m_faces.size());
        m_faces.push_back(static_cast<uint8_t>(it - definition.begin()));
    }
    // A plane of the definition equal to a face (the same half-space named twice, as a box's face
    // is in the sweep's planes and in the box's) is not held to "strictly inside".
    for (size_t k = 0; k < definition.size(); ++k)
        for (size_t f = 0; f < m_faces.size() && m_faceOf[k] == kNone; ++f)
            if (samePlane(definition[k], definition[m_faces[f]])) {
                m_sameAs[k] = static_cast<uint8_t>(f);
                break;
            }
    for (const ConvexBody::Vertex& v : body.m_vertices) {
        if (!onThreePlanes(v.on)) return clear(), false;
        m_vertices.push_back(v.on);
    }
    // The proof needs the marks to be a simple polytope's graph: for each two faces of a vertex,
    // exactly one other vertex lies on both (the other end of their edge).
    for (size_t a = 0; a < m_vertices.size(); ++a)
        for (uint64_t i = m_vertices[a]; i != 0; i &= i - 1)
            for (uint64_t j = i & (i - 1); j != 0; j &= j - 1) {
                const uint64_t pair = (i & -i) | (j & -j);
                size_t ends = 0;
                for (size_t b = 0; b < m_vertices.size(); ++b)
                    if (b != a && (m_vertices[b] & pair) == pair) ++ends;
                if (ends != 1) return clear(), false;
            }
    return true;
}

std::optional<ConvexBody> ConvexBodyStructure::resolve(std::span<const Plane> definition) const {
    if (!holds() || definition.size() != m_faceOf.size()) return std::nullopt;
    // The margin scales with the definition's distance from the origin, which bounds the
    // rounding of every point solved from it; it depends on nothing remembered, so whether a
    // body is accepted does not depend on which frame's structure is tried.
    double magnitude = 1.0;
    for (const Plane& p : definition) magnitude = std::max(magnitude, std::abs(p.d));
    const double margin = kStrictMargin * magnitude;
    // Which planes each vertex is held to: every one but its own three faces, and but copies of
    // a face that are still copies.
    SmallVector<uint8_t, 80> check; // definition indices that are no face's copy
    for (size_t k = 0; k < definition.size(); ++k)
        if (m_faceOf[k] == kNone &&
            !(m_sameAs[k] != kNone && samePlane(definition[k], definition[m_faces[m_sameAs[k]]])))
            check.push_back(static_cast<uint8_t>(k));

    ConvexBody body;
    for (const uint8_t k : m_faces) body.m_planes.push_back(definition[k]);
    for (const uint64_t on : m_vertices) {
        const int a = std::countr_zero(on), b = std::countr_zero(on & (on - 1)), c = 63 - std::countl_zero(on);
        const std::optional<Vec3> p =
            meet(body.m_planes[size_t(a)], body.m_planes[size_t(b)], body.m_planes[size_t(c)]);
        if (!p) return std::nullopt;
        for (size_t f = 0; f < body.m_planes.size(); ++f)
            if (!(on & (uint64_t(1) << f)) && !(body.m_planes[f].signedDistance(*p) < -margin)) return std::nullopt;
        for (const uint8_t k : check)
            if (!(definition[k].signedDistance(*p) < -margin)) return std::nullopt;
        body.m_vertices.push_back({*p, on});
    }
    return body;
}

std::optional<ConvexBody> ConvexBodyStructures::resolve(std::span<const Plane> definition) {
    // The last that fitted first (a caller that builds one body a frame), then the one after it
    // (one that builds several, in the same order every frame), then the rest.
    for (size_t k = 0; k < kCapacity; ++k) {
        const size_t at = (m_last + k) % kCapacity;
        if (std::optional<ConvexBody> body = m_structures[at].resolve(definition)) {
            m_last = at;
            return body;
        }
    }
    return std::nullopt;
}

ConvexBody ConvexBodyStructures::remember(ConvexBody body, std::span<const Plane> definition) {
    ConvexBodyStructure& slot = m_structures[m_oldest];
    if (!slot.remember(body, definition)) return body;
    std::optional<ConvexBody> resolved = slot.resolve(definition);
    if (!resolved) {
        slot.clear(); // too near a degenerate configuration to be re-solved: clipped each frame
        return body;
    }
    m_last = m_oldest;
    m_oldest = (m_oldest + 1) % kCapacity;
    return *resolved;
}

} // namespace shadowkit::core
