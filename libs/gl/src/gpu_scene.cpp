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
        // Large levels reordered into spatial clusters (a range shared by both chains once).
        std::vector<uint32_t> indices = lod.indices;
        std::vector<std::pair<uint32_t, std::vector<scene::TriangleCluster>>> done;
        auto clustersOf = [&](const std::vector<scene::LodLevel>& chain) {
            std::vector<std::vector<scene::TriangleCluster>> out;
            for (size_t l = 0; l < std::min(chain.size(), kMaxLodLevels); ++l) {
                const scene::LodLevel& level = chain[l];
                if (level.indexCount / 3 < kClusterMinTriangles) {
                    out.emplace_back();
                    continue;
                }
                const auto same =
                    std::find_if(done.begin(), done.end(), [&](const auto& d) { return d.first == level.firstIndex; });
                if (same != done.end()) {
                    out.push_back(same->second);
                    continue;
                }
                out.push_back(scene::clusterTriangles(mesh,
                                                      std::span(indices).subspan(level.firstIndex, level.indexCount),
                                                      level.firstIndex, static_cast<uint32_t>(kClusterTriangles)));
                done.emplace_back(level.firstIndex, out.back());
            }
            return out;
        };
        gpu.cameraClusters = clustersOf(lod.camera);
        gpu.shadowClusters = clustersOf(lod.shadow);
        gpu.indices = createBuffer(indices.data(), std::max<size_t>(indices.size(), 1) * sizeof(uint32_t));
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
        if (count > 0 && !scene.meshes[batch.mesh].indices.empty()) {
            m_batches.push_back({batch.mesh,
                                 createBuffer(batch.worldFromObject.data(),
                                              batch.worldFromObject.size() * sizeof(glm::mat4), batch.dynamic),
                                 firstInstance,
                                 b,
                                 {}});
            const GpuMesh& mesh = m_meshes[batch.mesh];
            const auto clustered = [](const auto& levels) {
                return std::any_of(levels.begin(), levels.end(), [](const auto& c) { return !c.empty(); });
            };
            if (clustered(mesh.cameraClusters) || clustered(mesh.shadowClusters))
                m_batches.back().worldFromObject = batch.worldFromObject;
        }
        firstInstance += count;
    }
}

void GpuScene::updateBatch(const scene::Scene& scene, size_t sceneBatch) {
    for (GpuBatch& batch : m_batches) {
        if (batch.index != sceneBatch) continue;
        const std::vector<glm::mat4>& transforms = scene.batches[sceneBatch].worldFromObject;
        if (!batch.worldFromObject.empty()) batch.worldFromObject = transforms;
        glNamedBufferSubData(batch.instances.id(), 0, static_cast<GLsizeiptr>(transforms.size() * sizeof(glm::mat4)),
                             transforms.data());
    }
}

DrawStats GpuScene::draw(const PassList& list, bool setInstanceBase, int replicas) const {
    return drawBatches(list, setInstanceBase, replicas, nullptr);
}

DrawStats GpuScene::draw(const PassList& list, std::span<const visibility::HalfSpace> volume) const {
    return drawBatches(list, false, 1, &volume);
}

DrawStats GpuScene::drawBatches(const PassList& list, bool setInstanceBase, int replicas,
                                const std::span<const visibility::HalfSpace>* volume) const {
    DrawStats stats;
    if (list.buffer != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, list.buffer);
    if (list.indirect >= 0) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, list.commands);
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
            const Range& range = levels[level];
            const auto& clusterLevels = list.shadow ? mesh.shadowClusters : mesh.cameraClusters;
            if (volume && list.indirect < 0 && level < clusterLevels.size() && !clusterLevels[level].empty()) {
                // Each instance alone, each run of clusters meeting the volume in one draw.
                const std::vector<scene::TriangleCluster>& clusters = clusterLevels[level];
                for (uint32_t k = 0; k < count; ++k) {
                    const core::Mat4 worldFromObject(batch.worldFromObject[list.indices[list.first[slot] + k]]);
                    glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[slot] + k);
                    size_t run = 0, runIndices = 0;
                    auto flush = [&](size_t end) {
                        if (runIndices == 0) return;
                        glDrawElementsInstanced(
                            GL_TRIANGLES, static_cast<GLsizei>(runIndices), GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(clusters[run].firstIndex * sizeof(uint32_t)), 1);
                        stats.triangles += runIndices / 3;
                        ++stats.drawCalls;
                        runIndices = 0;
                        run = end;
                    };
                    for (size_t c = 0; c < clusters.size(); ++c) {
                        if (visibility::isOutside(*volume,
                                                  core::transformBounds(worldFromObject, clusters[c].osBounds))) {
                            flush(c + 1);
                            continue;
                        }
                        if (runIndices == 0) run = c;
                        runIndices += clusters[c].indexCount;
                    }
                    flush(clusters.size());
                    ++stats.instances;
                }
                continue;
            }
            glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[slot]);
            // Camera passes move simplified receivers' shadow lookups by their error (main.vert).
            if (setInstanceBase) glUniform1f(kLodErrorLocation, range.objectError);
            if (list.indirect >= 0) {
                // The command holds the level's range and the instances the GPU kept (up to
                // `count`): what is drawn is known to the GPU only (GpuCulling::submitted).
                const size_t command = static_cast<size_t>(list.indirect) + slot;
                glDrawElementsIndirect(
                    GL_TRIANGLES, GL_UNSIGNED_INT,
                    reinterpret_cast<const void*>(command * kIndirectCommandWords * sizeof(uint32_t)));
                ++stats.drawCalls;
                continue;
            }
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
