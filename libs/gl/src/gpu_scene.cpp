#include "gpu_scene.h"

#include "uniforms.h"

#include <algorithm>
#include <cstddef>

namespace shadowkit::gl {

namespace {

std::vector<GpuScene::Range> rangesOf(const std::vector<scene::LodLevel>& chain) {
    std::vector<GpuScene::Range> ranges;
    for (size_t l = 0; l < std::min(chain.size(), kMaxLodLevels); ++l)
        ranges.push_back(
            {static_cast<GLsizei>(chain[l].indexCount), chain[l].firstIndex * sizeof(uint32_t), chain[l].objectError});
    return ranges;
}

} // namespace

GpuScene::GpuScene(const scene::Scene& scene, std::span<const scene::MeshLods> lods) {
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const scene::Mesh& mesh = scene.meshes[m];
        const scene::MeshLods& lod = lods[m];
        GpuMesh gpu;
        gpu.vertices = createBuffer(mesh.vertices.data(), mesh.vertices.size() * sizeof(scene::Vertex));
        gpu.indices = createBuffer(lod.indices.data(), std::max<size_t>(lod.indices.size(), 1) * sizeof(uint32_t));
        gpu.camera = rangesOf(lod.camera);
        gpu.shadow = rangesOf(lod.shadow);
        GLuint vao = 0;
        glCreateVertexArrays(1, &vao);
        gpu.vertexArray = VertexArray(vao);
        glVertexArrayVertexBuffer(vao, 0, gpu.vertices.id(), 0, sizeof(scene::Vertex));
        glVertexArrayElementBuffer(vao, gpu.indices.id());
        const GLuint offsets[3] = {offsetof(scene::Vertex, position), offsetof(scene::Vertex, normal),
                                   offsetof(scene::Vertex, albedo)};
        for (GLuint attrib = 0; attrib < 3; ++attrib) {
            glEnableVertexArrayAttrib(vao, attrib);
            glVertexArrayAttribFormat(vao, attrib, 3, GL_FLOAT, GL_FALSE, offsets[attrib]);
            glVertexArrayAttribBinding(vao, attrib, 0);
        }
        m_meshes.push_back(std::move(gpu));
    }
    GLuint firstInstance = 0;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const scene::MeshBatch& batch = scene.batches[b];
        const auto count = static_cast<GLuint>(batch.worldFromObject.size());
        if (count > 0 && !scene.meshes[batch.mesh].indices.empty())
            m_batches.push_back({batch.mesh,
                                 createBuffer(batch.worldFromObject.data(),
                                              batch.worldFromObject.size() * sizeof(glm::mat4), batch.dynamic),
                                 firstInstance, b});
        firstInstance += count;
    }
}

void GpuScene::updateBatch(const scene::Scene& scene, size_t sceneBatch) {
    for (const GpuBatch& batch : m_batches) {
        if (batch.index != sceneBatch) continue;
        const std::vector<glm::mat4>& transforms = scene.batches[sceneBatch].worldFromObject;
        glNamedBufferSubData(batch.instances.id(), 0, static_cast<GLsizeiptr>(transforms.size() * sizeof(glm::mat4)),
                             transforms.data());
    }
}

DrawStats GpuScene::draw(const PassList& list, bool setInstanceBase, int replicas) const {
    DrawStats stats;
    for (const GpuBatch& batch : m_batches) {
        const GpuMesh& mesh = m_meshes[batch.mesh];
        const std::vector<Range>& levels = list.shadow ? mesh.shadow : mesh.camera;
        bool bound = false;
        for (size_t level = 0; level < levels.size(); ++level) {
            const size_t slot = batch.index * kMaxLodLevels + level;
            const uint32_t count = list.count[slot];
            if (count == 0) continue;
            if (!bound) {
                if (setInstanceBase) glUniform1ui(kInstanceBaseLocation, batch.firstInstance);
                glBindVertexArray(mesh.vertexArray.id());
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstancesBinding, batch.instances.id());
                bound = true;
            }
            glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[slot]);
            const Range& range = levels[level];
            // Camera passes move simplified receivers' shadow lookups by their error (main.vert).
            if (setInstanceBase) glUniform1f(kLodErrorLocation, range.objectError);
            glDrawElementsInstanced(GL_TRIANGLES, range.indexCount, GL_UNSIGNED_INT,
                                    reinterpret_cast<const void*>(range.byteOffset),
                                    static_cast<GLsizei>(count) * replicas);
            stats.instances += static_cast<size_t>(count) * static_cast<size_t>(replicas);
            stats.triangles += static_cast<size_t>(range.indexCount / 3) * count * static_cast<size_t>(replicas);
            ++stats.drawCalls;
        }
    }
    glBindVertexArray(0);
    return stats;
}

} // namespace shadowkit::gl
