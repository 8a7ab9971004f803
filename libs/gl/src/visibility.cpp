#include "visibility.h"

#include "uniforms.h"

#include <algorithm>

namespace shadowkit::gl {
namespace {

std::vector<core::Aabb> instanceBoxes(const scene::Scene& scene) {
    std::vector<core::Aabb> boxes;
    boxes.reserve(scene.instanceCount());
    for (const scene::MeshBatch& batch : scene.batches) {
        const core::Aabb& os = scene.meshes[batch.mesh].osBounds;
        for (const glm::mat4& m : batch.worldFromObject) boxes.push_back(core::transformBounds(core::Mat4(m), os));
    }
    return boxes;
}

} // namespace

Visibility::Visibility(const scene::Scene& scene) : m_hierarchy(instanceBoxes(scene)) {
    uint32_t first = 0;
    for (const scene::MeshBatch& batch : scene.batches) {
        m_batchFirst.push_back(first);
        first += static_cast<uint32_t>(batch.worldFromObject.size());
    }
    m_batchFirst.push_back(first); // end of the last batch
}

void Visibility::collect(std::span<const core::HalfSpace> volume, bool cull, PassList& out) {
    m_scratch.clear();
    if (cull) {
        m_hierarchy.query(volume, m_scratch);
        std::sort(m_scratch.begin(), m_scratch.end());
    } else {
        m_scratch.resize(m_hierarchy.size());
        for (uint32_t i = 0; i < m_scratch.size(); ++i) m_scratch[i] = i;
    }
    // Global indices are sorted, and batches are consecutive global ranges: one pass splits
    // them into batch-local lists.
    const size_t batches = m_batchFirst.size() - 1;
    out.indices.clear();
    out.first.assign(batches, 0);
    out.count.assign(batches, 0);
    size_t batch = 0;
    for (const uint32_t global : m_scratch) {
        while (global >= m_batchFirst[batch + 1]) ++batch;
        if (out.count[batch] == 0) out.first[batch] = static_cast<uint32_t>(out.indices.size());
        ++out.count[batch];
        out.indices.push_back(global - m_batchFirst[batch]);
    }
}

void Visibility::upload(std::span<PassList* const> lists) {
    m_staging.clear();
    for (PassList* list : lists) {
        list->offset = static_cast<uint32_t>(m_staging.size());
        m_staging.insert(m_staging.end(), list->indices.begin(), list->indices.end());
    }
    if (m_staging.empty()) m_staging.push_back(0); // a buffer of size 0 cannot be bound
    if (m_staging.size() > m_capacity) {
        m_capacity = std::max(m_staging.size(), 2 * m_capacity);
        m_buffer = createBuffer(nullptr, m_capacity * sizeof(uint32_t));
    }
    glNamedBufferSubData(m_buffer.id(), 0, static_cast<GLsizeiptr>(m_staging.size() * sizeof(uint32_t)), m_staging.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, m_buffer.id());
}

} // namespace shadowkit::gl
