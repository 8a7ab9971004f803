// A scene uploaded to the GPU: one vertex array per mesh, one instance buffer per batch.
#pragma once

#include "gl_object.h"
#include "visibility.h"

#include "shadowkit/scene/mesh_clusters.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/visibility/instance_hierarchy.h"

#include <vector>

namespace shadowkit::gl {

struct DrawStats {
    size_t instances = 0;
    size_t triangles = 0;
    size_t drawCalls = 0;
    DrawStats& operator+=(const DrawStats& o) {
        instances += o.instances, triangles += o.triangles, drawCalls += o.drawCalls;
        return *this;
    }
};

class GpuScene {
public:
    // `lods[m]` holds mesh m's index buffer with every level of detail (scene::buildLods).
    GpuScene(const scene::Scene& scene, std::span<const scene::MeshLods> lods);

    // One glDrawElementsInstanced per batch and level with instances in `list` (uploaded by
    // Visibility::upload); the vertex shaders read the transform of
    // visibleInstances[instanceOffset + gl_InstanceID] from the batch's buffer at
    // kInstancesBinding. With setInstanceBase the bound program's `instanceBase` uniform
    // receives the batch's first global instance index (Scene order), the surface identity
    // of the evaluation. `replicas` > 1 draws every instance that many times in a row
    // (gl_InstanceID / replicas is the list entry): the layered cube pass's faces.
    DrawStats draw(const PassList& list, bool setInstanceBase = false, int replicas = 1) const;
    // The same, where a large mesh's instance (kClusterMinTriangles or more at its level) draws
    // only its triangle clusters whose boxes meet `volume`: a pass that sees a small part of a
    // kilometre of terrain (a virtual map's page) draws that part. The same pixels as draw():
    // the clusters left out lie wholly outside the pass's volume.
    DrawStats draw(const PassList& list, std::span<const visibility::HalfSpace> volume) const;
    static constexpr size_t kClusterMinTriangles = 16384, kClusterTriangles = 2048;
    // Uploads the transforms of Scene::batches[sceneBatch] again (a dynamic batch, whose
    // instances moved; other batches' buffers are immutable).
    void updateBatch(const scene::Scene& scene, size_t sceneBatch);

    // One level of detail in a mesh's index buffer.
    struct Range {
        GLsizei indexCount = 0;
        size_t byteOffset = 0;
        float objectError = 0.0f; // scene::LodLevel::objectError
    };

private:
    struct GpuMesh {
        Buffer vertices, indices; // indices: every level of both chains
        VertexArray vertexArray;
        std::vector<Range> camera, shadow; // per level, at most kMaxLodLevels
        // Per level of each chain: its triangles' spatial clusters (empty below kClusterMinTriangles).
        std::vector<std::vector<scene::TriangleCluster>> cameraClusters, shadowClusters;
    };
    struct GpuBatch {
        size_t mesh = 0;
        Buffer instances;
        GLuint firstInstance = 0;               // global index over all batches
        size_t index = 0;                       // in Scene::batches (PassList's per-batch ranges)
        std::vector<glm::mat4> worldFromObject; // kept on the CPU for clustered meshes only
    };
    DrawStats drawBatches(const PassList& list, bool setInstanceBase, int replicas,
                          const std::span<const visibility::HalfSpace>* volume) const;
    std::vector<GpuMesh> m_meshes;
    std::vector<GpuBatch> m_batches;
};

} // namespace shadowkit::gl
