// A scene uploaded to the GPU: one vertex array per mesh, one instance buffer per batch.
#pragma once

#include "gl_object.h"
#include "visibility.h"

#include "shadowkit/scene/scene.h"

#include <vector>

namespace shadowkit::gl {

struct DrawStats {
    size_t instances = 0;
    size_t triangles = 0;
    size_t drawCalls = 0;
};

class GpuScene {
public:
    explicit GpuScene(const scene::Scene& scene);

    // One glDrawElementsInstanced per batch with instances in `list` (uploaded by
    // Visibility::upload); the vertex shaders read the transform of
    // visibleInstances[instanceOffset + gl_InstanceID] from the batch's buffer at
    // kInstancesBinding. With setInstanceBase the bound program's `instanceBase` uniform
    // receives the batch's first global instance index (Scene order), the surface identity
    // of the evaluation.
    DrawStats draw(const PassList& list, bool setInstanceBase = false) const;

private:
    struct GpuMesh {
        Buffer vertices, indices;
        VertexArray vertexArray;
        GLsizei indexCount = 0;
    };
    struct GpuBatch {
        size_t mesh = 0;
        Buffer instances;
        GLuint firstInstance = 0; // global index over all batches
        size_t index = 0;         // in Scene::batches (PassList's per-batch ranges)
    };
    std::vector<GpuMesh> m_meshes;
    std::vector<GpuBatch> m_batches;
};

} // namespace shadowkit::gl
