// A convex body's combinatorial structure kept from one frame to the next: which of its defining
// planes each vertex lies on, so that the next frame's body — the same planes, moved a little by
// the camera and the sun — is re-solved vertex by vertex instead of clipped again.
#pragma once

#include "shadowkit/core/convex_body.h"

#include <cstdint>
#include <optional>
#include <span>

namespace shadowkit::core {

/// A remembered body as three indices into the list of planes that define it, per vertex.
///
/// resolve() returns a body only when it is provably the intersection of the definition's
/// half-spaces: each vertex solved from its three planes, those independent, and strictly inside
/// every other plane of the definition by a margin far above the clipping tolerance. Then each
/// solved vertex is a vertex of the new intersection, and for each two of its planes the one
/// other vertex on both is at the end of the edge they span (no plane can cut that segment: it
/// holds both ends strictly); the remembered vertices are closed under those edges, and a
/// polytope's vertex graph is connected, so they are all its vertices. No tolerance is traded
/// for speed: a structure that no longer fits returns nothing and the caller clips afresh.
///
/// The vertices are solved with their three planes in an order fixed by the planes' values, so
/// a body resolved from a remembered structure and the same body clipped afresh and resolved by
/// its own structure are equal to the last bit. (A body too near a degenerate configuration to
/// be resolved by its own structure is not remembered: the caller clips it every time.)
class ConvexBodyStructure {
public:
    /// Remembers `body` as the intersection of `definition`'s half-spaces; each face must be a
    /// copy of one of those planes. False, and nothing remembered, for an empty body, a face not
    /// in the definition, a vertex on more (or fewer) than three faces — a body whose corners are
    /// not all simple — or a definition of 255 planes or more.
    bool remember(const ConvexBody& body, std::span<const Plane> definition);
    /// Whether a structure is held.
    bool holds() const { return !m_vertices.empty(); }
    /// The intersection of `definition`'s half-spaces, re-solved from the remembered structure
    /// (the definition's planes in the order remember() saw them), or nothing when that
    /// structure no longer describes it.
    std::optional<ConvexBody> resolve(std::span<const Plane> definition) const;
    /// Forgets the structure.
    void clear();

private:
    static constexpr uint8_t kNone = 0xff;
    SmallVector<uint8_t, ConvexBody::kMaxFaces> m_faces; // face f is definition[m_faces[f]]
    SmallVector<uint64_t, 48> m_vertices;                // each vertex's three faces, one bit each
    SmallVector<uint8_t, 80> m_faceOf;                   // per definition plane: the face it is, or kNone
    SmallVector<uint8_t, 80> m_sameAs; // per definition plane not a face: the face it equalled, or kNone
};

/// A few structures, for a caller that builds more than one body a frame (two views, say):
/// resolve() tries the last that fitted first, then the others in turn from the one after it.
class ConvexBodyStructures {
public:
    static constexpr size_t kCapacity = 4; ///< bodies remembered
    /// The first remembered structure that resolves `definition`, from the last that fitted;
    /// nothing if none does.
    std::optional<ConvexBody> resolve(std::span<const Plane> definition);
    /// Remembers `body` in place of the oldest structure; its resolved self (the canonical
    /// vertices) if it could be remembered, else `body` as it is.
    ConvexBody remember(ConvexBody body, std::span<const Plane> definition);

private:
    ConvexBodyStructure m_structures[kCapacity];
    size_t m_last = 0;   // where resolve() starts: the last that fitted
    size_t m_oldest = 0; // where remember() writes
};

} // namespace shadowkit::core
