#include "gpu_scene.h"

#include "uniforms.h"

#include <cstddef>

namespace shadowkit::gl {

GpuScene::GpuScene(const scene::Scene& scene) {
    for (const scene::Mesh& mesh : scene.meshes) {
        GpuMesh gpu;
        gpu.vertices = createBuffer(mesh.vertices.data(), mesh.vertices.size() * sizeof(scene::Vertex));
        gpu.indices = createBuffer(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
        gpu.indexCount = static_cast<GLsizei>(mesh.indices.size());
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
                                 createBuffer(batch.worldFromObject.data(), batch.worldFromObject.size() * sizeof(glm::mat4)),
                                 firstInstance, b});
        firstInstance += count;
    }
}

DrawStats GpuScene::draw(const PassList& list, bool setInstanceBase) const {
    DrawStats stats;
    for (const GpuBatch& batch : m_batches) {
        const uint32_t count = list.count[batch.index];
        if (count == 0) continue;
        const GpuMesh& mesh = m_meshes[batch.mesh];
        if (setInstanceBase) glUniform1ui(kInstanceBaseLocation, batch.firstInstance);
        glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[batch.index]);
        glBindVertexArray(mesh.vertexArray.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstancesBinding, batch.instances.id());
        glDrawElementsInstanced(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(count));
        stats.instances += count;
        stats.triangles += static_cast<size_t>(mesh.indexCount / 3) * count;
        ++stats.drawCalls;
    }
    glBindVertexArray(0);
    return stats;
}

} // namespace shadowkit::gl
