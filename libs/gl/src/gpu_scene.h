// A scene uploaded to the GPU: one vertex array per mesh, one instance buffer per batch.
#pragma once

#include "gl_object.h"
#include "visibility.h"

#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/scene/mesh_clusters.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/visibility/instance_hierarchy.h"

#include <span>
#include <string_view>
#include <vector>

namespace shadowkit::gl {

// The programs a pass draws the scene with: a plain one and its SK_MATERIAL variant
// (material.glsl), built from the same sources with kMaterialVariant[1] in front of each
// stage. Batches whose material is alpha-tested draw with `material`, which samples the
// base colour texture and discards what alpha does not cover; so do textured batches in a
// pass that shades colour. Every other batch draws with `plain`: a depth-only pass over
// opaque casters reads no texture and keeps its early depth test.
struct PassPrograms {
    GLuint plain = 0;
    GLuint material = 0; // 0: every batch with `plain` (a pass that draws no materials)
    bool colour = false; // the pass shades colour (main pass): textures matter to opaque batches too
    // With face culling enabled: only levels known closed are culled (core::CasterCull::BackOfClosed),
    // open ones draw both sides. Otherwise every batch but a double-sided one is culled.
    bool cullClosedOnly = false;
    // Which batches the pass draws, by material: all of them, or with --foliage-opacity the sun's
    // depth pass the opaque ones and its opacity passes the alpha-tested ones (opacity_layers.h).
    enum class Batches { All, Opaque, AlphaTested } batches = Batches::All;
};
inline constexpr std::string_view kMaterialVariant[2] = {"", "#define SK_MATERIAL 1\n"};

// A pass's two programs, owned.
struct ProgramPair {
    Program plain, material;
    PassPrograms passPrograms(bool colour = false) const { return {plain.id(), material.id(), colour}; }
};

struct DrawStats {
    size_t instances = 0;
    size_t triangles = 0;
    size_t drawCalls = 0;
    DrawStats& operator+=(const DrawStats& o) {
        instances += o.instances, triangles += o.triangles, drawCalls += o.drawCalls;
        return *this;
    }
};

class GpuScene;

// Each view's casters in a pass of several views (maps or virtual pages): `lists` one a view,
// and `culled`, empty or one a view, what the GPU culled of the view's other casters
// (GpuCulling::cull with leaveClustered: every batch but those drawing by clusters; a list
// without commands: none). A virtual page on the GPU-driven path is both: its clustered meshes
// culled on the CPU, to the clusters meeting the page.
struct CasterLists {
    std::span<const PassList> lists, culled;
    // View i's casters with `programs`: the culled first (the trees, nearer the sun than the
    // terrain under them), then its list's, large meshes by the clusters meeting `volume` when
    // one is given (GpuScene::draw); `replicas` copies of each of the list's instances (the
    // culled commands hold their own).
    DrawStats draw(const GpuScene& scene, size_t view, const PassPrograms& programs,
                   const std::vector<visibility::HalfSpace>* volume, int replicas = 1) const;
};

// glFrontFace for a depth pass into the map of `clipFromWorld`: the winding the faces turned
// towards the sun show there (core/caster_facing.h), so that culling GL_BACK leaves out the
// faces turned away from it under any warp. The pass restores GL_CCW when it ends.
void setLightFacingFront(const core::Mat4& clipFromWorld, const core::Vec3& wsTowardsLight);

class GpuScene {
public:
    // `lods[m]` holds mesh m's index buffer with every level of detail (scene::buildLods).
    GpuScene(const scene::Scene& scene, std::span<const scene::MeshLods> lods);

    // One glDrawElementsInstanced per batch and level with instances in `list` (uploaded by
    // Visibility::upload), or for a GPU-culled list one indirect draw per batch and run of levels
    // drawn alike (drawBatch); the vertex shaders read the transform of
    // visibleInstances[instanceOffset + base instance + gl_InstanceID] from the batch's buffer at
    // kInstancesBinding. With setInstanceBase the bound program's `instanceBase` uniform
    // receives the batch's first global instance index (Scene order), the surface identity
    // of the evaluation. `replicas` > 1 draws every instance that many times in a row
    // (gl_InstanceID / replicas is the list entry): the layered cube pass's faces.
    // With face culling enabled, batches whose material is double-sided draw with it off, and
    // so do mirrored batches (an instance whose transform has a negative determinant: its
    // winding is reversed) and, where `programs` asks, levels not known closed (the state is
    // restored after each). Plain batches first, then the material ones.
    DrawStats draw(const PassList& list, const PassPrograms& programs, bool setInstanceBase = false,
                   int replicas = 1) const;
    // The same, where a large mesh's instance (kClusterMinTriangles or more at its level) draws
    // only its triangle clusters whose boxes meet `volume`: a pass that sees a small part of a
    // kilometre of terrain (a virtual map's page) draws that part. The same pixels as draw():
    // the clusters left out lie wholly outside the pass's volume. `setInstanceBase` and `replicas`
    // as above (a replicated instance's runs: a draw of that many copies each).
    DrawStats draw(const PassList& list, const PassPrograms& programs, std::span<const visibility::HalfSpace> volume,
                   bool setInstanceBase = false, int replicas = 1) const;
    static constexpr size_t kClusterMinTriangles = 16384, kClusterTriangles = 2048;
    // Several passes' (two or more) GPU-culled lists at once, their commands one stride apart (consecutive
    // passes of GpuCulling::cullPasses): each batch's level in one multi-draw over the passes, the
    // draw's index naming the pass to `programs` (virtual pages: depth.vert's SK_PAGES). Only where
    // vertex stages read the draw parameters (program.h).
    DrawStats drawTogether(std::span<const PassList> lists, const PassPrograms& programs) const;
    // Several passes' (two or more) CPU lists at once, all in one batch order, a large mesh's instance in each by
    // its clusters meeting that pass's volume (`volumes`, one a list): each batch's level in one
    // multi-draw over commands built here, one per pass and instance (per run of clusters for a
    // clustered one), the pass of each draw in a table at kDrawPagesBinding (depth.vert's SK_PAGES,
    // pagePerDraw 2). Each pass gets the draws and order draw() with its volume gives it. Only
    // where vertex stages read the draw parameters.
    DrawStats drawTogether(std::span<const PassList> lists, const PassPrograms& programs,
                           std::span<const std::vector<visibility::HalfSpace>> volumes) const;
    // Whether Scene::batches[sceneBatch]'s mesh draws by clusters at some level of either chain,
    // so that the overload above may draw only a part of it.
    bool drawsByClusters(size_t sceneBatch) const;
    // Whether Scene::batches[sceneBatch]'s material is alpha-tested (leaves).
    bool alphaTested(size_t sceneBatch) const;
    // Whether Scene::batches[sceneBatch] is kept out of every pass: no instances, no triangles, or
    // a material the alpha test cuts away whole (scene::coversNothing).
    bool keptOut(size_t sceneBatch) const { return sceneBatch >= m_batchAt.size() || m_batchAt[sceneBatch] < 0; }

    // A drawn list's instances and whole levels' triangles, added to `work` (kMaxLodLevels
    // entries) at each level, the alpha-tested batches' also apart (Renderer::workByLevel).
    void addLevelWork(const PassList& drawn, std::span<LevelWork> work) const;
    // Uploads the transforms of Scene::batches[sceneBatch] again (a dynamic batch, whose
    // instances moved; other batches' buffers are immutable).
    void updateBatch(const scene::Scene& scene, size_t sceneBatch);
    // Uploads the vertices of Scene::meshes[mesh] again (one the file's animations deform:
    // Scene::deforms, whose buffer was made updatable; its vertex count unchanged).
    void reshapeMesh(const scene::Scene& scene, size_t mesh);

    // One level of detail in a mesh's index buffer.
    struct Range {
        GLsizei indexCount = 0;
        size_t byteOffset = 0;
        // How far, in object metres, a receiver drawn at this level moves its shadow lookup
        // towards the light (shadow_lookup.glsl, receiverLookup): a simplified surface's error
        // (scene::LodLevel::objectError), 0 for a level that keeps coverage (rangesOf).
        float lookupOffset = 0.0f;
        bool closed = false;            // scene::LodLevel::closed
        int32_t texture = -1;           // scene::LodLevel::texture: its own base colour, else the material's
        scene::ImpostorCard impostor{}; // scene::LodLevel::impostor: a card the vertex stage turns
    };

private:
    struct GpuMesh {
        Buffer vertices, indices; // indices: every level of both chains
        VertexArray vertexArray;
        std::vector<Range> camera, shadow; // per level, at most kMaxLodLevels
        // Per level of each chain: its triangles' spatial clusters (empty below kClusterMinTriangles).
        std::vector<std::vector<scene::TriangleCluster>> cameraClusters, shadowClusters;
        // Per vertex, the longest edge of the triangles it belongs to, in every level; again after
        // each reshape: the bound of the depth passes that write their depth (osLongestEdge of
        // depth.vert and local_depth_layer.vert, kEdgeAttribute).
        Buffer longestEdges;
        std::vector<uint32_t> deformedIndices; // a deformed mesh's `indices`, for its edges in each pose
    };
    // A mesh's material as its draws need it (scene::Material).
    struct GpuMaterial {
        bool alphaTested = false, doubleSided = false;
        GLuint texture = 0; // the base colour texture, or the white 1×1 one
        bool textured = false;
        float baseAlpha = 1.0f, alphaCutoff = -1.0f; // uniforms of material.glsl; cutoff < 0: opaque
    };
    struct GpuBatch {
        size_t mesh = 0;
        GpuMaterial material;
        Buffer instances;
        GLuint firstInstance = 0;               // global index over all batches
        size_t index = 0;                       // in Scene::batches (PassList's per-batch ranges)
        bool mirrored = false;                  // an instance's transform has a negative determinant
        std::vector<glm::mat4> worldFromObject; // kept on the CPU for clustered meshes only
    };
    // The passes of drawTogether: empty, or their lists (`list` the first) and, for CPU lists,
    // each one's volume.
    struct Together {
        std::span<const PassList> lists;
        std::span<const std::vector<visibility::HalfSpace>> volumes;
    };
    DrawStats drawBatches(const PassList& list, const PassPrograms& programs, bool setInstanceBase, int replicas,
                          const std::span<const visibility::HalfSpace>* volume, Together together = {}) const;
    // materialBound: the material program is bound (a level's own texture is bound with it).
    DrawStats drawBatch(const GpuBatch& batch, const PassList& list, const PassPrograms& programs, bool culling,
                        bool materialBound, bool setInstanceBase, int replicas,
                        const std::span<const visibility::HalfSpace>* volume, Together together) const;
    // One level of a batch: its instances in a list of the CPU's, one draw (or, by clusters, one an
    // instance: its runs of clusters meeting the volume in one glMultiDrawElements; replicated, a
    // draw of `replicas` copies a run).
    DrawStats drawLevel(const GpuBatch& batch, const PassList& list, size_t level, const Range& range,
                        bool setInstanceBase, int replicas, const std::span<const visibility::HalfSpace>* volume) const;
    // Levels [first, end) of `levels` (a batch's chain) in a GPU-culled list, one draw through their
    // indirect commands (several only where m_levelsInOneDraw), with the state they share set.
    // With `passes` > 1, one level for that many passes, their commands `passStride` commands apart.
    DrawStats drawLevels(const GpuBatch& batch, const PassList& list, std::span<const Range> levels, size_t first,
                         size_t end, bool setInstanceBase, size_t passes = 1, int64_t passStride = 0) const;
    // One level of a batch in several passes' CPU lists (drawTogether's second form), one multi-draw.
    DrawStats drawLevelTogether(const GpuBatch& batch, const Together& together, size_t level,
                                const Range& range) const;
    std::vector<Texture> m_textures; // Scene::textures, mipmapped (scene::buildMipChain)
    Texture m_white;                 // for alpha-tested materials without a texture
    std::vector<GpuMesh> m_meshes;
    std::vector<GpuBatch> m_batches;
    std::vector<int32_t> m_batchAt; // Scene::batches index -> m_batches, -1 for a batch kept out (nothing to draw)
    bool m_levelsInOneDraw = false; // vertexStagesReadDrawParameters() when the scene was made
    // drawLevel's runs of clusters for one glMultiDrawElements, kept so a page's draw allocates nothing.
    mutable std::vector<GLsizei> m_runCounts;
    mutable std::vector<const void*> m_runStarts;
    // drawLevelTogether's commands (five words each, glDrawElementsIndirect's) and the pass of each,
    // on the CPU and where the GPU reads them; the buffers grow to the most a call has drawn.
    mutable std::vector<uint32_t> m_togetherCommands, m_togetherPasses;
    mutable Buffer m_togetherCommandBuffer, m_togetherPassBuffer;
    mutable size_t m_togetherCapacity = 0; // draws the two buffers hold
};

} // namespace shadowkit::gl
