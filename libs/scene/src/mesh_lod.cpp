// Levels of detail with meshoptimizer.
//
// Based on: Garland & Heckbert 1997's quadric error metric as meshoptimizer implements it
// (meshopt_simplify; full citations in docs/references.md). The camera chain
// simplifies the mesh as it is, so seams between vertices that share a position but not a
// normal or colour stay closed and shading stays right. The shadow chain welds vertices by
// position (meshopt_generateShadowIndexBuffer) and takes, per level, whichever of the
// quadric simplifier and the topology-free "sloppy" one (vertex clustering) gets closer to
// the target within the same error bound: a depth map sees positions only, and holes or
// merged layers do not matter to it below the error. Sloppy is what reduces the conifers,
// whose open cone layers stop the quadric simplifier at 187 of 228 triangles.
#include "shadowkit/scene/mesh_lod.h"

#include "shadowkit/scene/closed_surface.h"

#include <meshoptimizer.h>

#include <algorithm>

namespace shadowkit::scene {
namespace {

void appendChain(const Mesh& mesh, const std::vector<uint32_t>& base, const LodOptions& o, float scale, bool sloppy,
                 MeshLods& out, std::vector<LodLevel>& chain) {
    chain.push_back({static_cast<uint32_t>(out.indices.size()), static_cast<uint32_t>(base.size()), 0.0f});
    out.indices.insert(out.indices.end(), base.begin(), base.end());
    if (mesh.triangleCount() > o.maxTriangles) return;
    std::vector<uint32_t> current = base, next(base.size());
    for (int level = 1; level < o.maxLevels; ++level) {
        const size_t target = static_cast<size_t>(static_cast<float>(current.size()) * o.reduction) / 3 * 3;
        float error = 0.0f;
        // Each level simplifies the original (not the previous level), so errors do not
        // accumulate and the error reported is against the real surface.
        const float* positions = &mesh.vertices[0].position.x;
        size_t count = meshopt_simplify(next.data(), base.data(), base.size(), positions, mesh.vertices.size(),
                                        sizeof(Vertex), target, o.maxRelativeError, 0, &error);
        if (sloppy) { // whichever of the two gets closer to the target within the bound
            std::vector<uint32_t> clustered(base.size());
            float clusteredError = 0.0f;
            const size_t clusteredCount =
                meshopt_simplifySloppy(clustered.data(), base.data(), base.size(), positions, mesh.vertices.size(),
                                       sizeof(Vertex), target, o.maxRelativeError, &clusteredError);
            if (clusteredCount > 0 && clusteredCount < count && clusteredError <= o.maxRelativeError) {
                next.swap(clustered);
                count = clusteredCount;
                error = clusteredError;
            }
        }
        if (count == 0 || static_cast<double>(count) > 0.8 * static_cast<double>(current.size())) break;
        current.assign(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(count));
        chain.push_back({static_cast<uint32_t>(out.indices.size()), static_cast<uint32_t>(count), error * scale});
        out.indices.insert(out.indices.end(), current.begin(), current.end());
    }
}

// Which shadow levels bound solids: the full mesh may be closed and a clustered level opened.
void markClosedLevels(const Mesh& mesh, MeshLods& lods) {
    for (LodLevel& level : lods.shadow)
        level.closed = boundsSolid(mesh, std::span(lods.indices).subspan(level.firstIndex, level.indexCount));
}

} // namespace

MeshLods buildLods(const Mesh& mesh, const LodOptions& o) {
    MeshLods out;
    if (mesh.indices.empty() || mesh.vertices.empty()) {
        out.camera.push_back({});
        out.shadow.push_back({});
        return out;
    }
    if (!mesh.authoredLods.empty()) { // the mesh's own levels, each for the passes it names
        out.camera.push_back({0, static_cast<uint32_t>(mesh.indices.size()), 0.0f});
        out.shadow = out.camera;
        out.indices = mesh.indices;
        for (const AuthoredLod& level : mesh.authoredLods) {
            SK_ASSERT(level.impostor.framesPerSide == 0 || level.passes == LodPasses::Shadows,
                      "buildLods(): an impostor's level is drawn by the shadow passes alone");
            const bool camera =
                level.passes != LodPasses::Shadows && static_cast<int>(out.camera.size()) < o.maxAuthoredLevels;
            const bool shadow =
                level.passes != LodPasses::Camera && static_cast<int>(out.shadow.size()) < o.maxAuthoredLevels;
            if (!camera && !shadow) continue;
            const LodLevel built{static_cast<uint32_t>(out.indices.size()),
                                 static_cast<uint32_t>(level.indices.size()),
                                 level.objectError,
                                 false,
                                 level.keepsCoverage,
                                 level.texture,
                                 level.impostor};
            if (camera) out.camera.push_back(built);
            if (shadow) out.shadow.push_back(built);
            out.indices.insert(out.indices.end(), level.indices.begin(), level.indices.end());
        }
        markClosedLevels(mesh, out);
        return out;
    }
    const float scale = meshopt_simplifyScale(&mesh.vertices[0].position.x, mesh.vertices.size(), sizeof(Vertex));
    appendChain(mesh, mesh.indices, o, scale, false, out, out.camera);
    if (mesh.triangleCount() > o.maxTriangles) { // one level: both passes draw the same triangles
        out.shadow = out.camera;
        markClosedLevels(mesh, out);
        return out;
    }
    std::vector<uint32_t> welded(mesh.indices.size());
    meshopt_generateShadowIndexBuffer(welded.data(), mesh.indices.data(), mesh.indices.size(),
                                      &mesh.vertices[0].position, mesh.vertices.size(), sizeof(glm::vec3),
                                      sizeof(Vertex));
    appendChain(mesh, welded, o, scale, true, out, out.shadow);
    markClosedLevels(mesh, out);
    return out;
}

} // namespace shadowkit::scene
