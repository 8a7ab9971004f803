// Small procedural meshes (unit sized; instances scale and place them).
#pragma once

#include "shadowkit/scene/scene.h"

namespace shadowkit::scene {

// Appends to `mesh`, transformed by objectFromPart. Each uses smooth normals on curved
// sides and flat caps.
void addCylinder(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
                 const glm::vec3& albedo);
// Cone with its base disc at y = 0 and apex at y = height (base closed).
void addCone(Mesh& mesh, const glm::mat4& objectFromPart, int segments, float radius, float height,
             const glm::vec3& albedo);
// Geodesic sphere: an icosahedron subdivided `subdivisions` times (20·4^s triangles).
void addIcosphere(Mesh& mesh, const glm::mat4& objectFromPart, int subdivisions, float radius, const glm::vec3& albedo);
// Axis-aligned box with flat faces.
void addBox(Mesh& mesh, const glm::mat4& objectFromPart, const glm::vec3& halfExtent, const glm::vec3& albedo);

} // namespace shadowkit::scene
