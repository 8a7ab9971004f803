// Which way is up in a loaded file. shadowkit's world is y-up, as glTF is (glTF 2.0 §3.4); an
// OBJ says nothing, and CAD, GIS and photogrammetry exports often write z up — a terrain tile in
// easting, northing and height. Loaded y-up, such a file stands on its side: the sun of every
// view lights it from the side and its ground is a wall. LoadOptions::up turns it; and a y-up
// load that looks z-up says so, since no picture of a model on its side says why.
#include "scene_formats.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace shadowkit::scene::formats {

namespace {

// (x, y, z) → (x, z, −y): −90° about x. Columns, as glm stores them.
const glm::mat4 kYUpFromZUp(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0),
                            glm::vec4(0, 0, 0, 1));

} // namespace

void turnZUpToYUp(Scene& scene) {
    // The meshes turn too, not only their placements (M' = R · M · Rᵀ over p' = R · p): what
    // works in a mesh's own space — the simplifier, the clusters, a cloud's planes, the leaves'
    // highest-first order — sees the mesh upright, as in a y-up file. Every entry of R · M · Rᵀ
    // and of R · p is ± one entry of M or p: exact in float, as the origin's turn is in double.
    const glm::mat3 turn(kYUpFromZUp);
    for (Mesh& mesh : scene.meshes) {
        for (Vertex& v : mesh.vertices) v.position = turn * v.position, v.normal = turn * v.normal;
        mesh.computeBounds();
    }
    const glm::mat4 back = glm::transpose(kYUpFromZUp);
    for (MeshBatch& batch : scene.batches)
        for (glm::mat4& worldFromObject : batch.worldFromObject) worldFromObject = kYUpFromZUp * worldFromObject * back;
    scene.wsOrigin = core::Vec3(scene.wsOrigin.x, scene.wsOrigin.z, -scene.wsOrigin.y);
    const glm::dmat3 dturn(turn); // the file's cameras and lights, in double
    for (FileCamera& c : scene.cameras)
        c.localEye = dturn * c.localEye, c.localForward = dturn * c.localForward, c.localUp = dturn * c.localUp;
    for (FileLight& l : scene.lights)
        l.localPosition = dturn * l.localPosition, l.localDirection = dturn * l.localDirection;
    // A deformed mesh's poses turn as its vertices did: R · p.
    for (MeshDeformation& deformation : scene.deformations)
        deformation.meshFromPosed = glm::dmat4(kYUpFromZUp) * deformation.meshFromPosed;
    // A keyframed instance's motion turns as its placement does: R · (S · F(t) · N) · Rᵀ.
    for (Track& track : scene.tracks)
        if (track.keyframed) {
            track.keyframed->sceneFromRoot = glm::dmat4(kYUpFromZUp) * track.keyframed->sceneFromRoot;
            track.keyframed->nodeFromObject *= glm::dmat4(back);
        }
}

std::optional<std::string> zUpWarning(const Scene& scene) {
    // The scene's net area vector, Σ over triangles of (b − a) × (c − a) / 2 placed in the scene:
    // a closed surface's is 0, a ground's is its area along its up. Per mesh in object space,
    // then per instance through the cofactor matrix (how a linear map moves area vectors:
    // det(M) · M^−T). The total area, each triangle's magnitude, scales by |det|^(2/3).
    glm::dvec3 net(0.0);
    double total = 0.0;
    for (const MeshBatch& batch : scene.batches) {
        const Mesh& mesh = scene.meshes[batch.mesh];
        glm::dvec3 objectNet(0.0);
        double objectArea = 0.0;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const glm::dvec3 a(mesh.vertices[mesh.indices[t]].position), b(mesh.vertices[mesh.indices[t + 1]].position),
                c(mesh.vertices[mesh.indices[t + 2]].position);
            const glm::dvec3 area = 0.5 * glm::cross(b - a, c - a);
            objectNet += area;
            objectArea += glm::length(area);
        }
        for (const glm::mat4& worldFromObject : batch.worldFromObject) {
            const glm::dmat3 linear(worldFromObject);
            const double det = glm::determinant(linear);
            if (!(std::abs(det) > 0.0)) continue;
            net += det * glm::transpose(glm::inverse(linear)) * objectNet;
            total += std::pow(std::abs(det), 2.0 / 3.0) * objectArea;
        }
    }
    // Most of its net area facing +z and hardly any facing up: a ground written z-up.
    if (!(total > 0.0) || !(net.z > 0.2 * total) || !(net.z > 4.0 * std::abs(net.y))) return std::nullopt;
    char share[16];
    std::snprintf(share, sizeof share, "%.0f %%", 100.0 * net.z / total);
    return std::string("its ground faces +z (net ") + share +
           " of its area), as a z-up file's would; if z is its up, load it so (LoadOptions::up, --scene-up z)";
}

} // namespace shadowkit::scene::formats
