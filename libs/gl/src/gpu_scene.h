// A scene uploaded to the GPU: one vertex array per mesh, one instance buffer per batch.
#pragma once

#include "gl_object.h"

#include "shadowkit/scene/scene.h"

#include <vector>

namespace shadowkit::gl {

struct DrawStats {
    size_t triangles = 0;
    size_t drawCalls = 0;
};

class GpuScene {
public:
    explicit GpuScene(const scene::Scene& scene);

    // One glDrawElementsInstanced per batch, instance transforms read from the
    // shader-storage buffer at binding kInstancesBinding by gl_InstanceID. With
    // setInstanceBase the bound program's `instanceBase` uniform receives the batch's
    // first global instance index (Scene order), the surface identity of the evaluation.
    DrawStats drawAll(bool setInstanceBase = false) const;

private:
    struct GpuMesh {
        Buffer vertices, indices;
        VertexArray vertexArray;
        GLsizei indexCount = 0;
    };
    struct GpuBatch {
        size_t mesh = 0;
        Buffer instances;
        GLsizei instanceCount = 0;
        GLuint firstInstance = 0; // global index over all batches
    };
    std::vector<GpuMesh> m_meshes;
    std::vector<GpuBatch> m_batches;
};

} // namespace shadowkit::gl
