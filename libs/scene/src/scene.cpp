#include "shadowkit/scene/scene.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {

void Mesh::computeBounds() {
    osBounds = {};
    for (const Vertex& v : vertices) osBounds.extend(core::Vec3(v.position));
}

core::Aabb Scene::wsBounds() const {
    core::Aabb bounds;
    for (const MeshBatch& batch : batches) {
        const core::Aabb& os = meshes[batch.mesh].osBounds;
        for (const glm::mat4& m : batch.worldFromObject) bounds.extend(core::transformBounds(core::Mat4(m), os));
    }
    return bounds;
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const MeshBatch& batch : batches) n += meshes[batch.mesh].triangleCount() * batch.worldFromObject.size();
    return n;
}

size_t Scene::instanceCount() const {
    size_t n = 0;
    for (const MeshBatch& batch : batches) n += batch.worldFromObject.size();
    return n;
}

double Scene::groundHeightAt(double x, double z) const {
    if (terrain) return terrain->heightAt(x, z);
    const core::Aabb b = wsBounds();
    return b.isEmpty() ? 0.0 : b.min.y;
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
