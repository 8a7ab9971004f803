// A deformed mesh posed at time t (the formulas: deformation.h).
#include "shadowkit/scene/deformation.h"

#include "shadowkit/core/conventions.h"
#include "shadowkit/scene/scene.h"

#include "scene_formats.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {

std::vector<glm::dvec3> MeshDeformation::posedPositions(double t, std::vector<glm::dvec3>& normals,
                                                        std::vector<bool>* mirrored) const {
    const size_t n = bindPositions.size();
    std::vector<glm::dvec3> positions(n);
    normals.assign(n, glm::dvec3(0.0));
    for (size_t v = 0; v < n; ++v) {
        positions[v] = glm::dvec3(bindPositions[v]);
        if (v < bindNormals.size()) normals[v] = glm::dvec3(bindNormals[v]);
    }
    // Morph targets, each at its weight now.
    for (size_t k = 0; k < targets.size(); ++k) {
        const double w = k < weightKeys.size() && weightKeys[k] ? weightKeys[k]->at(t, false).x
                         : k < weights.size()                   ? weights[k]
                                                                : 0.0;
        if (w == 0.0 || !std::isfinite(w)) continue;
        const MorphTarget& target = targets[k];
        for (size_t v = 0; v < std::min(n, target.positions.size()); ++v)
            positions[v] += w * glm::dvec3(target.positions[v]);
        for (size_t v = 0; v < std::min(n, target.normals.size()); ++v) normals[v] += w * glm::dvec3(target.normals[v]);
    }
    if (mirrored) mirrored->assign(n, false);
    if (skinned()) {
        std::vector<glm::dmat4> joint(joints.size());
        for (size_t j = 0; j < joints.size(); ++j)
            joint[j] = joints[j].sceneFromObjectAt(t) * (j < inverseBind.size() ? inverseBind[j] : glm::dmat4(1.0));
        // Vertex by vertex, independent: on every core (a character of 100,000 vertices is a few
        // milliseconds on one). `mirrored` is a vector<bool>, whose bits neighbours share: set after.
        std::vector<uint8_t> flips(mirrored ? n : 0, 0);
        const size_t skinnedCount = std::min(n, firstInfluence.empty() ? 0 : firstInfluence.size() - 1);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, skinnedCount, 1024), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t v = r.begin(); v < r.end(); ++v) {
                if (firstInfluence[v] == firstInfluence[v + 1]) continue; // unweighted: as bound
                glm::dmat4 blend(0.0);
                for (uint32_t i = firstInfluence[v]; i < firstInfluence[v + 1]; ++i)
                    blend += influences[i].weight * joint[influences[i].joint];
                positions[v] = glm::dvec3(blend * glm::dvec4(positions[v], 1.0));
                // Normals by the inverse transpose, as its cofactor matrix: det(L) · L⁻ᵀ, whose
                // columns are the cross products of L's (no division; the sign kept, the length
                // normalised below).
                const glm::dvec3 a(blend[0]), b(blend[1]), c(blend[2]);
                const glm::dvec3 bc = glm::cross(b, c);
                const double det = glm::dot(a, bc);
                if (!flips.empty() && det < 0.0) flips[v] = 1;
                if (std::abs(det) > 1e-12)
                    normals[v] =
                        (det < 0.0 ? -1.0 : 1.0) * glm::dmat3(bc, glm::cross(c, a), glm::cross(a, b)) * normals[v];
            }
        });
        for (size_t v = 0; v < flips.size(); ++v)
            if (flips[v]) (*mirrored)[v] = true;
    }
    for (glm::dvec3& normal : normals)
        if (const double length = glm::length(normal); length > 0.0 && std::isfinite(length)) normal /= length;
    return positions;
}

void MeshDeformation::poseInto(Mesh& mesh, double t) const {
    std::vector<glm::dvec3> normals;
    const std::vector<glm::dvec3> positions = posedPositions(t, normals);
    writePose(mesh, positions, normals);
}

void MeshDeformation::writePose(Mesh& mesh, std::span<const glm::dvec3> positions,
                                std::span<const glm::dvec3> normals) const {
    const glm::dmat3 turn(meshFromPosed); // rigid: normals turn as positions do
    for (size_t v = 0; v < std::min(positions.size(), mesh.vertices.size()); ++v) {
        const glm::dvec3 p = glm::dvec3(meshFromPosed * glm::dvec4(positions[v], 1.0));
        if (!core::isFinite(p)) continue;
        mesh.vertices[v].position = glm::vec3(p);
        if (v < normals.size() && glm::length(normals[v]) > 0.0) mesh.vertices[v].normal = glm::vec3(turn * normals[v]);
    }
    if (normalsFromFaces) formats::computeNormals(mesh); // the posed faces' own
    mesh.computeBounds();
}

} // namespace shadowkit::scene
