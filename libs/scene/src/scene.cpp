#include "shadowkit/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowkit::scene {

void Mesh::computeBounds() {
    osBounds = {};
    for (const Vertex& v : vertices) osBounds.extend(core::Vec3(v.position));
}

core::Aabb Scene::wsBounds() const {
    const core::Aabb local = localBounds();
    return local.isEmpty() ? local : core::Aabb::fromMinMax(local.min + wsOrigin, local.max + wsOrigin);
}

core::Aabb Scene::localBounds() const {
    core::Aabb bounds;
    for (const MeshBatch& batch : batches) {
        const core::Aabb& os = meshes[batch.mesh].osBounds;
        for (const glm::mat4& m : batch.worldFromObject) bounds.extend(core::transformBounds(core::Mat4(m), os));
    }
    return bounds;
}

std::vector<core::Aabb> Scene::instanceBounds() const {
    std::vector<core::Aabb> boxes;
    boxes.reserve(instanceCount());
    for (const MeshBatch& batch : batches) {
        const core::Aabb& os = meshes[batch.mesh].osBounds;
        for (const glm::mat4& m : batch.worldFromObject) boxes.push_back(core::transformBounds(core::Mat4(m), os));
    }
    return boxes;
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const MeshBatch& batch : batches) n += meshes[batch.mesh].triangleCount() * batch.worldFromObject.size();
    return n;
}

uint32_t Scene::globalIndex(InstanceRef ref) const {
    SK_ASSERT(ref.batch < batches.size() && ref.instance < batches[ref.batch].worldFromObject.size(),
              "Scene::globalIndex(): no such instance");
    size_t first = 0;
    for (uint32_t b = 0; b < ref.batch; ++b) first += batches[b].worldFromObject.size();
    return static_cast<uint32_t>(first + ref.instance);
}

std::optional<InstanceRef> Scene::locate(uint32_t global) const {
    size_t first = 0;
    for (uint32_t b = 0; b < batches.size(); ++b) {
        const size_t count = batches[b].worldFromObject.size();
        if (global < first + count) return InstanceRef{b, static_cast<uint32_t>(global - first)};
        first += count;
    }
    return std::nullopt;
}

size_t Scene::instanceCount() const {
    size_t n = 0;
    for (const MeshBatch& batch : batches) n += batch.worldFromObject.size();
    return n;
}

bool MeshBatch::mirrored() const {
    return std::any_of(worldFromObject.begin(), worldFromObject.end(),
                       [](const glm::mat4& m) { return glm::determinant(glm::mat3(m)) < 0.0f; });
}

bool Scene::seenFromFrontOnly(size_t batch) const {
    if (batch >= batches.size()) return false;
    const Material* material = materialOf(meshes[batches[batch].mesh]);
    return !(material && material->doubleSided) && !batches[batch].mirrored();
}

bool Scene::deforms(uint32_t mesh) const {
    return std::any_of(deformations.begin(), deformations.end(), [&](const MeshDeformation& d) {
        return d.batch < batches.size() && batches[d.batch].mesh == mesh;
    });
}

void Scene::replaceBatches(std::vector<MeshBatch> kept, std::span<const uint32_t> batchAt) {
    SK_ASSERT(batchAt.size() == batches.size(), "Scene::replaceBatches(): one place for every batch");
    std::vector<Mesh> drawn;
    std::vector<uint32_t> meshAt(meshes.size(), UINT32_MAX);
    for (MeshBatch& batch : kept) {
        if (meshAt[batch.mesh] == UINT32_MAX) {
            meshAt[batch.mesh] = uint32_t(drawn.size());
            drawn.push_back(std::move(meshes[batch.mesh]));
        }
        batch.mesh = meshAt[batch.mesh];
    }
    const auto follow = [&](uint32_t& batch, const char* what) {
        SK_ASSERT(batch < batchAt.size() && batchAt[batch] != UINT32_MAX, what);
        batch = batchAt[batch];
    };
    for (Track& track : tracks) follow(track.batch, "Scene::replaceBatches(): a track's batch is gone");
    for (MeshDeformation& deformation : deformations)
        follow(deformation.batch, "Scene::replaceBatches(): a deformed batch is gone");
    meshes = std::move(drawn);
    batches = std::move(kept);
}

double Scene::groundHeightAt(double x, double z) const {
    if (terrain) return terrain->heightAt(x, z);
    // Loaded scenes: the highest upward-facing surface straight below the sky at (x, z),
    // found by testing the vertical line against every triangle of the instances whose
    // bounds contain it. A terrain mesh in a glTF file thus places the eye over the
    // terrain, not under it. Runs once per view resolution, not per frame.
    double best = -std::numeric_limits<double>::infinity();
    for (const MeshBatch& batch : batches) {
        if (batch.dynamic) continue; // moving objects are not ground (a mover would climb itself)
        const Mesh& mesh = meshes[batch.mesh];
        for (const glm::mat4& m : batch.worldFromObject) {
            const core::Aabb box = core::transformBounds(core::Mat4(m), mesh.osBounds);
            if (x < box.min.x || x > box.max.x || z < box.min.z || z > box.max.z || box.max.y <= best) continue;
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                const glm::dvec3 a(m * glm::vec4(mesh.vertices[mesh.indices[i]].position, 1.0f));
                const glm::dvec3 b(m * glm::vec4(mesh.vertices[mesh.indices[i + 1]].position, 1.0f));
                const glm::dvec3 c(m * glm::vec4(mesh.vertices[mesh.indices[i + 2]].position, 1.0f));
                // Barycentric coordinates of (x, z) in the triangle's xz projection. The face
                // normal's y is −det, so up-facing triangles have det < 0 (NaN-safe test).
                const double det = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
                if (!(det < -1e-12)) continue; // degenerate or facing down
                const double u = ((x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z)) / det;
                const double v = ((b.x - a.x) * (z - a.z) - (x - a.x) * (b.z - a.z)) / det;
                if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
                best = std::max(best, a.y + u * (b.y - a.y) + v * (c.y - a.y));
            }
        }
    }
    if (std::isfinite(best)) return best;
    const core::Aabb bounds = localBounds();
    return bounds.isEmpty() ? 0.0 : bounds.min.y;
}

double Heightfield::sample(int ix, int iz) const {
    ix = std::clamp(ix, 0, resolution);
    iz = std::clamp(iz, 0, resolution);
    return heights[static_cast<size_t>(iz) * static_cast<size_t>(resolution + 1) + static_cast<size_t>(ix)];
}

double Heightfield::heightAt(double x, double z) const {
    const double gx = std::clamp((x + 0.5 * size) / spacing(), 0.0, double(resolution));
    const double gz = std::clamp((z + 0.5 * size) / spacing(), 0.0, double(resolution));
    const int ix = std::min(static_cast<int>(gx), resolution - 1);
    const int iz = std::min(static_cast<int>(gz), resolution - 1);
    const double fx = gx - ix, fz = gz - iz;
    // Matches the triangle split of the terrain mesh (diagonal from (0,0) to (1,1)),
    // so objects placed with it sit exactly on the rendered surface.
    const double h00 = sample(ix, iz), h10 = sample(ix + 1, iz), h01 = sample(ix, iz + 1), h11 = sample(ix + 1, iz + 1);
    if (fx >= fz) return h00 + fx * (h10 - h00) + fz * (h11 - h10);
    return h00 + fz * (h01 - h00) + fx * (h11 - h01);
}

} // namespace shadowkit::scene
