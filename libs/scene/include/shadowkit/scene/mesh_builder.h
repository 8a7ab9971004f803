// Small procedural meshes (unit sized; instances scale and place them).
#pragma once

#include "shadowkit/scene/scene.h"

#include <span>
#include <vector>

namespace shadowkit::scene {

// Appends to `mesh`, transformed by objectFromPart. Each uses smooth normals on curved
// sides and flat caps, and each is a closed solid (scene/closed_surface.h): a depth pass may
// cull its faces turned away from the light.
void addCylinder(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
                 const glm::vec3& albedo);
// Cone with its base disc at y = 0 and apex at y = height (base closed).
void addCone(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
             const glm::vec3& albedo);
// Geodesic sphere: an icosahedron subdivided `subdivisions` times (20·4^s triangles).
void addIcosphere(Mesh& mesh, const glm::mat4& objectFromPart, int subdivisions, float radius, const glm::vec3& albedo);
// Axis-aligned box with flat faces.
void addBox(Mesh& mesh, const glm::mat4& objectFromPart, const glm::vec3& halfExtent, const glm::vec3& albedo);
// A card: the quad x, y in [-½, ½] × [0, 1] of the part's space (scale it to the card's size),
// facing +z, two triangles. Its uvs span `uvMin` at the bottom-left corner to `uvMax` at the
// top-right — a leaf's cell of a texture atlas, top rows first (v grows downwards, glTF's
// convention, so uvMin.y is usually the larger). Cards are drawn double-sided by their material.
void addCard(Mesh& mesh, const glm::mat4& objectFromPart, glm::vec2 uvMin, glm::vec2 uvMax, const glm::vec3& albedo);

// Reorders `indices`, quads of two triangles (six indices each: cards, billboard-cloud planes)
// into `vertices`, highest centroid first, each quad's indices kept as they were. A shadow pass
// under a sun above the horizon then meets a canopy's upper leaves before the ones they hide and
// its depth test rejects those, instead of each being written and then overwritten: the leafy
// forest's shadow pass wrote 2.4 samples per map texel on its low-sun views in the order the
// cards grew, 1.9 this way. No pass's pixels depend on the order (the depth test keeps the
// nearest). Precondition: indices.size() is a multiple of 6.
void orderQuadsHighestFirst(std::span<const Vertex> vertices, std::vector<uint32_t>& indices);

} // namespace shadowkit::scene
