#include "gpu_scene.h"

#include "program.h"
#include "uniforms.h"

#include "shadowkit/core/caster_facing.h"
#include "shadowkit/scene/texture_mips.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>

namespace shadowkit::gl {

// main.vert's lodObjectErrors[] takes a uniform location a level: they must not reach the next ones.
static_assert(kLodErrorLocation + static_cast<int>(kMaxLodLevels) <= kPageBaseLocation);

namespace {

// A simplified surface lies up to its error off the true one on one side or the other, and would
// shadow itself against a map holding the true one: its lookup moves that far towards the light.
// A level that keeps coverage (cards, billboard clouds) is no offset surface but the leaves moved
// within their slabs, as many above the plane as below it; moving its lookup out of the canopy
// lit what the leaves above shade (`eval --forest leafy --view aerial`, 1280 × 720: TSM 11.16 →
// 11.03 % wrong without the move, the virtual clipmap 10.24 → 9.98; twice the move 11.40 and
// 10.51).
std::vector<GpuScene::Range> rangesOf(const std::vector<scene::LodLevel>& chain) {
    std::vector<GpuScene::Range> ranges;
    for (size_t l = 0; l < std::min(chain.size(), kMaxLodLevels); ++l)
        ranges.push_back({static_cast<GLsizei>(chain[l].indexCount), chain[l].firstIndex * sizeof(uint32_t),
                          chain[l].keepsCoverage ? 0.0f : chain[l].objectError, chain[l].closed, chain[l].texture,
                          chain[l].impostor});
    return ranges;
}

// The runs of consecutive clusters whose boxes, placed by worldFromObject, meet `volume`, in
// order: run(firstIndex, indexCount) for each (a large mesh's part a pass sees, drawn as few index
// ranges as its clusters allow).
template <class Run>
void forEachRunMeeting(std::span<const scene::TriangleCluster> clusters, const core::Mat4& worldFromObject,
                       std::span<const visibility::HalfSpace> volume, Run&& run) {
    uint32_t first = 0, count = 0;
    for (const scene::TriangleCluster& cluster : clusters) {
        if (visibility::isOutside(volume, core::transformBounds(worldFromObject, cluster.osBounds))) {
            if (count > 0) run(first, count);
            count = 0;
            continue;
        }
        if (count == 0) first = cluster.firstIndex;
        count += cluster.indexCount;
    }
    if (count > 0) run(first, count);
}

// Per vertex, the longest edge of the triangles `indices` (every level's) make of it, in object
// metres, a little long against rounding: the bound of the depth passes that write their depth
// (depth_pass.glsl's skConservativeClipZ, local_depth.glsl's skLocalConservativeClipZ). One float
// a vertex (at least one: a buffer may not be empty).
std::vector<float> longestEdges(std::span<const scene::Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<float> edges(std::max<size_t>(vertices.size(), 1), 0.0f);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        if (std::max({a, b, c}) >= vertices.size()) continue;
        const glm::vec3 pa = vertices[a].position, pb = vertices[b].position, pc = vertices[c].position;
        const float longest = 1.001f * std::max({glm::length(pb - pa), glm::length(pc - pb), glm::length(pa - pc)});
        for (const uint32_t v : {a, b, c}) edges[v] = std::max(edges[v], longest);
    }
    return edges;
}

// Whether some level of a chain draws by clusters (a large mesh's).
bool anyClusters(const std::vector<std::vector<scene::TriangleCluster>>& levels) {
    return std::any_of(levels.begin(), levels.end(), [](const auto& clusters) { return !clusters.empty(); });
}

GLenum glWrap(scene::TextureWrap wrap) {
    return wrap == scene::TextureWrap::ClampToEdge      ? GL_CLAMP_TO_EDGE
           : wrap == scene::TextureWrap::MirroredRepeat ? GL_MIRRORED_REPEAT
                                                        : GL_REPEAT;
}

// A texture with its whole mip chain: coverage-keeping for alpha-tested use (the cutoff of the
// first alpha-tested material that samples it), plain box-filtered otherwise. Minified through
// the nearest level, bilinear within it, whatever the file's sampler asks: blending two levels
// (trilinear) mixes two patterns each scaled to the right coverage into one that is not — a
// sparse canopy thins again — and costs llvmpipe a second bilinear lookup in every pass.
// `texture`, its image as level 0 and `below` as the levels under it (none without mipmaps).
Texture uploadTexture(const scene::Texture& texture, const std::vector<scene::Image>& below) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    Texture gl(id);
    glTextureStorage2D(id, static_cast<GLsizei>(1 + below.size()), GL_SRGB8_ALPHA8, texture.image.width,
                       texture.image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t level = 0; level <= below.size(); ++level) {
        const scene::Image& image = level == 0 ? texture.image : below[level - 1];
        glTextureSubImage2D(id, static_cast<GLint>(level), 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                            image.rgba.data());
        detail::countUpload(static_cast<int64_t>(image.rgba.size()));
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(glWrap(texture.wrapS)));
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(glWrap(texture.wrapT)));
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, texture.nearest ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, texture.mipmaps ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR);
    return gl;
}

} // namespace

void setLightFacingFront(const core::Mat4& clipFromWorld, const core::Vec3& wsTowardsLight) {
    glFrontFace(core::lightFacingWinding(clipFromWorld, wsTowardsLight) == core::Winding::Clockwise ? GL_CW : GL_CCW);
}

GpuScene::GpuScene(const scene::Scene& scene, std::span<const scene::MeshLods> lods)
    : m_levelsInOneDraw(vertexStagesReadDrawParameters()) {
    std::vector<scene::MipChainRequest> chains;
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        std::optional<float> cutoff;
        for (const scene::Material& m : scene.materials)
            if (m.alphaTested() && m.baseColorTexture == static_cast<int32_t>(t)) {
                cutoff = m.alphaCutoff;
                break;
            }
        // A level's own texture (a billboard cloud's) is alpha-tested as its mesh's material is.
        for (size_t m = 0; m < scene.meshes.size() && m < lods.size() && !cutoff; ++m) {
            const scene::Material* material = scene.materialOf(scene.meshes[m]);
            if (!material || !material->alphaTested()) continue;
            for (const auto* chain : {&lods[m].camera, &lods[m].shadow})
                for (const scene::LodLevel& level : *chain)
                    if (level.texture == static_cast<int32_t>(t)) cutoff = material->alphaCutoff;
        }
        chains.push_back({&scene.textures[t].image, cutoff, scene.textures[t].mipmaps});
    }
    scene::forEachMipChain(chains, [&](size_t t, const std::vector<scene::Image>& below) {
        m_textures.push_back(uploadTexture(scene.textures[t], below));
    });
    scene::Texture white;
    white.image = scene::Image(1, 1);
    white.image.rgba = {255, 255, 255, 255};
    white.mipmaps = false;
    m_white = uploadTexture(white, {});
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const scene::Mesh& mesh = scene.meshes[m];
        const scene::MeshLods& lod = lods[m];
        GpuMesh gpu;
        // A mesh the file's animations deform is uploaded again in every frame that poses it
        // (reshapeMesh), and keeps no clusters: their boxes would hold only its first pose.
        const bool deformed = scene.deforms(uint32_t(m));
        gpu.vertices = createBuffer(mesh.vertices.data(), mesh.vertices.size() * sizeof(scene::Vertex), deformed);
        // Large levels reordered into spatial clusters (a range shared by both chains once).
        std::vector<uint32_t> indices = lod.indices;
        std::vector<std::pair<uint32_t, std::vector<scene::TriangleCluster>>> done;
        auto clustersOf = [&](const std::vector<scene::LodLevel>& chain) {
            std::vector<std::vector<scene::TriangleCluster>> out;
            for (size_t l = 0; l < std::min(chain.size(), kMaxLodLevels); ++l) {
                const scene::LodLevel& level = chain[l];
                if (level.indexCount / 3 < kClusterMinTriangles || deformed) {
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
        const std::vector<float> edges = longestEdges(mesh.vertices, indices);
        gpu.longestEdges = createBuffer(edges.data(), edges.size() * sizeof(float), deformed);
        if (deformed) gpu.deformedIndices = indices;
        gpu.camera = rangesOf(lod.camera);
        gpu.shadow = rangesOf(lod.shadow);
        GLuint vao = 0;
        glCreateVertexArrays(1, &vao);
        gpu.vertexArray = VertexArray(vao);
        glVertexArrayVertexBuffer(vao, 0, gpu.vertices.id(), 0, sizeof(scene::Vertex));
        glVertexArrayElementBuffer(vao, gpu.indices.id());
        // position, normal, albedo, uv (main.vert's and material.glsl's locations)
        const GLuint offsets[4] = {offsetof(scene::Vertex, position), offsetof(scene::Vertex, normal),
                                   offsetof(scene::Vertex, albedo), offsetof(scene::Vertex, uv)};
        for (GLuint attrib = 0; attrib < 4; ++attrib) {
            glEnableVertexArrayAttrib(vao, attrib);
            glVertexArrayAttribFormat(vao, attrib, attrib == 3 ? 2 : 3, GL_FLOAT, GL_FALSE, offsets[attrib]);
            glVertexArrayAttribBinding(vao, attrib, 0);
        }
        // The longest edges, from a buffer of their own (the linear depth pass's alone).
        glVertexArrayVertexBuffer(vao, kEdgeBufferBinding, gpu.longestEdges.id(), 0, sizeof(float));
        glEnableVertexArrayAttrib(vao, kEdgeAttribute);
        glVertexArrayAttribFormat(vao, kEdgeAttribute, 1, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, kEdgeAttribute, kEdgeBufferBinding);
        m_meshes.push_back(std::move(gpu));
    }
    GLuint firstInstance = 0;
    m_batchAt.assign(scene.batches.size(), -1);
    // A material the alpha test cuts away whole (clear glass) is kept out with the batches
    // that have nothing to draw: no pass would write a fragment of it (scene::coversNothing).
    std::vector<uint8_t> coversNothing(scene.materials.size());
    for (size_t m = 0; m < scene.materials.size(); ++m)
        coversNothing[m] = scene::coversNothing(scene.materials[m], scene.textures);
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const scene::MeshBatch& batch = scene.batches[b];
        const auto count = static_cast<GLuint>(batch.worldFromObject.size());
        const int32_t materialIndex = scene.meshes[batch.mesh].material;
        const bool cutAway = materialIndex >= 0 && size_t(materialIndex) < coversNothing.size() &&
                             coversNothing[size_t(materialIndex)] != 0;
        if (count > 0 && !scene.meshes[batch.mesh].indices.empty() && !cutAway) {
            GpuMaterial material;
            if (const scene::Material* m = scene.materialOf(scene.meshes[batch.mesh])) {
                const int32_t t = m->baseColorTexture;
                material.alphaTested = m->alphaTested();
                material.doubleSided = m->doubleSided;
                material.textured = t >= 0 && static_cast<size_t>(t) < m_textures.size();
                material.texture = material.textured ? m_textures[static_cast<size_t>(t)].id() : m_white.id();
                material.baseAlpha = m->baseColorFactor.a;
                material.alphaCutoff = m->alphaTested() ? m->alphaCutoff : -1.0f;
            }
            m_batchAt[b] = int32_t(m_batches.size());
            m_batches.push_back({batch.mesh,
                                 material,
                                 createBuffer(batch.worldFromObject.data(),
                                              batch.worldFromObject.size() * sizeof(glm::mat4), batch.dynamic),
                                 firstInstance,
                                 b,
                                 batch.mirrored(),
                                 {}});
            const GpuMesh& mesh = m_meshes[batch.mesh];
            if (anyClusters(mesh.cameraClusters) || anyClusters(mesh.shadowClusters))
                m_batches.back().worldFromObject = batch.worldFromObject;
        }
        firstInstance += count;
    }
}

void GpuScene::updateBatch(const scene::Scene& scene, size_t sceneBatch) {
    for (GpuBatch& batch : m_batches) {
        if (batch.index != sceneBatch) continue;
        const std::vector<glm::mat4>& transforms = scene.batches[sceneBatch].worldFromObject;
        batch.mirrored = scene.batches[sceneBatch].mirrored();
        if (!batch.worldFromObject.empty()) batch.worldFromObject = transforms;
        uploadToBuffer(batch.instances.id(), 0, static_cast<GLsizeiptr>(transforms.size() * sizeof(glm::mat4)),
                       transforms.data());
    }
}

void GpuScene::reshapeMesh(const scene::Scene& scene, size_t mesh) {
    const std::vector<scene::Vertex>& vertices = scene.meshes[mesh].vertices;
    uploadToBuffer(m_meshes[mesh].vertices.id(), 0, static_cast<GLsizeiptr>(vertices.size() * sizeof(scene::Vertex)),
                   vertices.data());
    const std::vector<float> edges = longestEdges(vertices, m_meshes[mesh].deformedIndices);
    uploadToBuffer(m_meshes[mesh].longestEdges.id(), 0, static_cast<GLsizeiptr>(edges.size() * sizeof(float)),
                   edges.data());
}

DrawStats GpuScene::draw(const PassList& list, const PassPrograms& programs, bool setInstanceBase, int replicas) const {
    return drawBatches(list, programs, setInstanceBase, replicas, nullptr);
}

DrawStats GpuScene::draw(const PassList& list, const PassPrograms& programs,
                         std::span<const visibility::HalfSpace> volume, bool setInstanceBase, int replicas) const {
    return drawBatches(list, programs, setInstanceBase, replicas, &volume);
}

bool GpuScene::drawsByClusters(size_t sceneBatch) const {
    if (sceneBatch >= m_batchAt.size() || m_batchAt[sceneBatch] < 0) return false;
    const GpuMesh& mesh = m_meshes[m_batches[size_t(m_batchAt[sceneBatch])].mesh];
    return anyClusters(mesh.cameraClusters) || anyClusters(mesh.shadowClusters);
}

bool GpuScene::alphaTested(size_t sceneBatch) const {
    return sceneBatch < m_batchAt.size() && m_batchAt[sceneBatch] >= 0 &&
           m_batches[size_t(m_batchAt[sceneBatch])].material.alphaTested;
}

DrawStats CasterLists::draw(const GpuScene& scene, size_t view, const PassPrograms& programs,
                            const std::vector<visibility::HalfSpace>* volume, int replicas) const {
    DrawStats stats;
    if (view < culled.size() && culled[view].indirect >= 0) stats += scene.draw(culled[view], programs);
    stats += volume ? scene.draw(lists[view], programs, *volume, false, replicas)
                    : scene.draw(lists[view], programs, false, replicas);
    return stats;
}

DrawStats GpuScene::drawTogether(std::span<const PassList> lists, const PassPrograms& programs) const {
    // One list would draw as draw() does, a draw's index naming its level or run, not its pass.
    SK_ASSERT(lists.size() > 1, "GpuScene::drawTogether(): two passes or more");
    return drawBatches(lists.front(), programs, false, 1, nullptr, {lists, {}});
}

DrawStats GpuScene::drawTogether(std::span<const PassList> lists, const PassPrograms& programs,
                                 std::span<const std::vector<visibility::HalfSpace>> volumes) const {
    const bool cpuListsInOneOrder = std::ranges::all_of(
        lists, [&](const PassList& l) { return l.indirect < 0 && l.batchOrder == lists.front().batchOrder; });
    SK_ASSERT(lists.size() > 1 && cpuListsInOneOrder && volumes.size() == lists.size(),
              "GpuScene::drawTogether(): two CPU lists or more in one batch order, a volume each");
    return drawBatches(lists.front(), programs, false, 1, nullptr, {lists, volumes});
}

DrawStats GpuScene::drawBatches(const PassList& list, const PassPrograms& programs, bool setInstanceBase, int replicas,
                                const std::span<const visibility::HalfSpace>* volume, Together together) const {
    DrawStats stats;
    if (list.buffer != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, list.buffer);
    if (list.indirect >= 0) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, list.commands);
    const bool culling = glIsEnabled(GL_CULL_FACE) == GL_TRUE;
    auto usesMaterial = [&](const GpuBatch& batch) {
        return programs.material != 0 && (batch.material.alphaTested || (programs.colour && batch.material.textured));
    };
    GLuint bound = 0;
    // Scene batch `index` (one kept out — no instances, no triangles — has no GpuBatch), when it
    // is of the kind `sweep` asks for (any when unset) and of the batches the programs take.
    auto drawIndex = [&](uint32_t index, std::optional<bool> sweep) {
        const int32_t at = m_batchAt[index];
        if (at < 0) return;
        const GpuBatch& batch = m_batches[size_t(at)];
        const bool material = usesMaterial(batch);
        if (sweep && material != *sweep) return;
        if (programs.batches != PassPrograms::Batches::All &&
            batch.material.alphaTested != (programs.batches == PassPrograms::Batches::AlphaTested))
            return;
        if (const GLuint program = material ? programs.material : programs.plain; program != bound) {
            glUseProgram(program);
            bound = program;
        }
        if (material) {
            glBindTextureUnit(kBaseColorUnit, batch.material.texture);
            glUniform1f(kBaseAlphaLocation, batch.material.baseAlpha);
            glUniform1f(kAlphaCutoffLocation, batch.material.alphaCutoff);
        }
        stats += drawBatch(batch, list, programs, culling, material, setInstanceBase, replicas, volume, together);
    };
    // A list that names its order (the sun's maps and pages: nearest the sun first) is drawn in
    // it, switching programs where a batch needs the other: drawn after the terrain under it, an
    // alpha-tested canopy would overwrite every texel it covers. Otherwise the opaque batches
    // first, then the alpha-tested ones: one switch.
    if (!list.batchOrder.empty()) {
        for (const uint32_t index : list.batchOrder) drawIndex(index, std::nullopt);
    } else {
        for (const bool sweep : {false, true})
            for (uint32_t index = 0; index < m_batchAt.size(); ++index) drawIndex(index, sweep);
    }
    glBindVertexArray(0);
    return stats;
}

DrawStats GpuScene::drawBatch(const GpuBatch& batch, const PassList& list, const PassPrograms& programs, bool culling,
                              bool materialBound, bool setInstanceBase, int replicas,
                              const std::span<const visibility::HalfSpace>* volume, Together together) const {
    DrawStats stats;
    const GpuMesh& mesh = m_meshes[batch.mesh];
    const std::vector<Range>& levels = list.shadow ? mesh.shadow : mesh.camera;
    // Passes drawn together: a level is drawn where any of them may hold instances of it.
    auto instancesAt = [&](size_t level) {
        const size_t slot = batch.index * kMaxLodLevels + level;
        if (together.lists.size() < 2) return list.count[slot];
        return std::ranges::any_of(together.lists, [&](const PassList& l) { return l.count[slot] > 0; }) ? 1u : 0u;
    };
    // What a level's draw sets apart from its batch: both sides where culling could lose a face the
    // light or camera meets first; a texture of its own (a billboard cloud's) in place of the
    // material's; an impostor's card, which the shadow passes' vertex stages turn to their light
    // (impostor.glsl; no camera chain holds one). Levels that agree can share a draw (their
    // lookup offsets go as an array).
    struct LevelState {
        bool twoSided = false;
        GLuint texture = 0; // 0: the material's
        scene::ImpostorCard impostor{};
        bool operator==(const LevelState&) const = default;
    };
    auto stateOf = [&](size_t level) {
        const Range& range = levels[level];
        LevelState state;
        state.twoSided =
            culling && (batch.material.doubleSided || batch.mirrored || (programs.cullClosedOnly && !range.closed));
        if (materialBound && range.texture >= 0 && size_t(range.texture) < m_textures.size())
            state.texture = m_textures[size_t(range.texture)].id();
        state.impostor = range.impostor;
        return state;
    };
    // A GPU-culled list's levels are drawn together where the vertex stages read each command's
    // base instance (program.h): a run of consecutive levels with instances and the same state is
    // one glMultiDrawElementsIndirect over their commands, which lie one after the other.
    // Passes drawn together take one level a call (their commands are a stride apart).
    const bool levelsTogether = list.indirect >= 0 && m_levelsInOneDraw && together.lists.size() < 2;
    bool bound = false;
    for (size_t level = 0; level < levels.size();) {
        if (instancesAt(level) == 0) {
            ++level;
            continue;
        }
        if (!bound) {
            if (setInstanceBase) glUniform1ui(kInstanceBaseLocation, batch.firstInstance);
            glBindVertexArray(mesh.vertexArray.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstancesBinding, batch.instances.id());
            bound = true;
        }
        const LevelState state = stateOf(level);
        size_t end = level + 1;
        while (levelsTogether && end < levels.size() && instancesAt(end) > 0 && stateOf(end) == state) ++end;
        if (state.twoSided) glDisable(GL_CULL_FACE);
        if (state.texture) glBindTextureUnit(kBaseColorUnit, state.texture);
        const scene::ImpostorCard& card = state.impostor;
        if (card.framesPerSide > 0) {
            glUniform4f(kImpostorSphereLocation, card.osCentre.x, card.osCentre.y, card.osCentre.z, card.osRadius);
            glUniform2i(kImpostorGridLocation, card.framesPerSide, card.texelsPerFrame);
        }
        if (together.lists.size() > 1 && list.indirect < 0)
            stats += drawLevelTogether(batch, together, level, levels[level]);
        else if (together.lists.size() > 1)
            stats += drawLevels(batch, list, levels, level, end, setInstanceBase, together.lists.size(),
                                together.lists[1].indirect - together.lists[0].indirect);
        else if (list.indirect >= 0)
            stats += drawLevels(batch, list, levels, level, end, setInstanceBase);
        else
            stats += drawLevel(batch, list, level, levels[level], setInstanceBase, replicas, volume);
        if (card.framesPerSide > 0) glUniform2i(kImpostorGridLocation, 0, 0);
        if (state.texture) glBindTextureUnit(kBaseColorUnit, batch.material.texture);
        if (state.twoSided) glEnable(GL_CULL_FACE);
        level = end;
    }
    return stats;
}

void GpuScene::addLevelWork(const PassList& drawn, std::span<LevelWork> work) const {
    for (const GpuBatch& batch : m_batches) {
        const std::vector<Range>& ranges = drawn.shadow ? m_meshes[batch.mesh].shadow : m_meshes[batch.mesh].camera;
        for (size_t level = 0; level < ranges.size() && level < work.size(); ++level) {
            const size_t slot = batch.index * kMaxLodLevels + level;
            const size_t instances = slot < drawn.count.size() ? drawn.count[slot] : 0;
            const size_t triangles = instances * size_t(ranges[level].indexCount / 3);
            work[level].instances += instances;
            work[level].triangles += triangles;
            if (!batch.material.alphaTested) continue;
            work[level].alphaTestedInstances += instances;
            work[level].alphaTestedTriangles += triangles;
        }
    }
}

DrawStats GpuScene::drawLevel(const GpuBatch& batch, const PassList& list, size_t level, const Range& range,
                              bool setInstanceBase, int replicas,
                              const std::span<const visibility::HalfSpace>* volume) const {
    DrawStats stats;
    const GpuMesh& mesh = m_meshes[batch.mesh];
    const size_t slot = batch.index * kMaxLodLevels + level;
    const uint32_t count = list.count[slot];
    const auto& clusterLevels = list.shadow ? mesh.shadowClusters : mesh.cameraClusters;
    if (volume && level < clusterLevels.size() && !clusterLevels[level].empty()) {
        // Each instance alone, its runs of clusters meeting the volume in one glMultiDrawElements
        // (one draw of several index ranges; gl_InstanceID 0 and base instance 0, so the uniform
        // names the entry).
        std::vector<GLsizei>& runCounts = m_runCounts;
        std::vector<const void*>& runStarts = m_runStarts;
        if (setInstanceBase) glUniform1f(kLodErrorLocation, range.lookupOffset);
        for (uint32_t k = 0; k < count; ++k) {
            const core::Mat4 worldFromObject(
                batch.worldFromObject[instanceOfEntry(list.indices[list.first[slot] + k])]);
            runCounts.clear(), runStarts.clear();
            forEachRunMeeting(clusterLevels[level], worldFromObject, *volume, [&](uint32_t first, uint32_t indices) {
                runStarts.push_back(reinterpret_cast<const void*>(first * sizeof(uint32_t)));
                runCounts.push_back(static_cast<GLsizei>(indices));
                stats.triangles += size_t(indices / 3) * size_t(replicas);
            });
            if (!runCounts.empty()) {
                glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[slot] + k);
                if (replicas == 1 && !setInstanceBase) {
                    glMultiDrawElements(GL_TRIANGLES, runCounts.data(), GL_UNSIGNED_INT, runStarts.data(),
                                        static_cast<GLsizei>(runCounts.size()));
                    ++stats.drawCalls;
                } else {
                    // A draw a run: the camera programs read the level's error by the draw's index
                    // (main.vert's lodObjectErrors[gl_DrawID], set for index 0 above), which a
                    // multi-draw's later runs would take past it; replicated, copies gl_InstanceID
                    // 0 .. replicas - 1 of the entry (gl_InstanceID / replicas = 0).
                    for (size_t run = 0; run < runCounts.size(); ++run)
                        glDrawElementsInstanced(GL_TRIANGLES, runCounts[run], GL_UNSIGNED_INT, runStarts[run],
                                                replicas);
                    stats.drawCalls += runCounts.size();
                }
            }
            stats.instances += size_t(replicas);
        }
        return stats;
    }
    // Camera passes move simplified receivers' shadow lookups by their error (main.vert).
    if (setInstanceBase) glUniform1f(kLodErrorLocation, range.lookupOffset);
    glUniform1ui(kInstanceOffsetLocation, list.offset + list.first[slot]);
    glDrawElementsInstanced(GL_TRIANGLES, range.indexCount, GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(range.byteOffset), static_cast<GLsizei>(count) * replicas);
    stats.instances += static_cast<size_t>(count) * static_cast<size_t>(replicas);
    stats.triangles += static_cast<size_t>(range.indexCount / 3) * count * static_cast<size_t>(replicas);
    ++stats.drawCalls;
    return stats;
}

DrawStats GpuScene::drawLevels(const GpuBatch& batch, const PassList& list, std::span<const Range> levels, size_t first,
                               size_t end, bool setInstanceBase, size_t passes, int64_t passStride) const {
    // The commands hold each level's range and the instances the GPU kept (up to `count`): what is
    // drawn is known to the GPU only (GpuCulling::submitted). Where vertex stages read the base
    // instance, the commands carry each level's place in the lists; else a draw holds one level,
    // whose place the uniform gives.
    const size_t firstSlot = batch.index * kMaxLodLevels + first;
    glUniform1ui(kInstanceOffsetLocation, m_levelsInOneDraw ? 0u : list.offset + list.first[firstSlot]);
    if (setInstanceBase) {
        // Camera passes move simplified receivers' shadow lookups by their error, each draw of a
        // multi-draw its own level's (main.vert).
        std::array<float, kMaxLodLevels> errors{};
        for (size_t level = first; level < end; ++level) errors[level - first] = levels[level].lookupOffset;
        glUniform1fv(kLodErrorLocation, static_cast<GLsizei>(end - first), errors.data());
    }
    const size_t command = static_cast<size_t>(list.indirect) + firstSlot;
    const auto* at = reinterpret_cast<const void*>(command * kIndirectCommandWords * sizeof(uint32_t));
    if (passes > 1)
        glMultiDrawElementsIndirect(
            GL_TRIANGLES, GL_UNSIGNED_INT, at, static_cast<GLsizei>(passes),
            static_cast<GLsizei>(passStride * int64_t(kIndirectCommandWords * sizeof(uint32_t))));
    else if (end == first + 1)
        glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, at);
    else
        glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, at, static_cast<GLsizei>(end - first), 0);
    return DrawStats{.drawCalls = 1};
}

DrawStats GpuScene::drawLevelTogether(const GpuBatch& batch, const Together& together, size_t level,
                                      const Range& range) const {
    // A command per pass (its level's instances at once) or, by clusters, per pass, instance and
    // run of clusters meeting that pass's volume, as drawLevel draws them pass by pass; its base
    // instance the entry's place in the frame's lists (instanceOffset 0), the pass in a table.
    DrawStats stats;
    const GpuMesh& mesh = m_meshes[batch.mesh];
    const size_t slot = batch.index * kMaxLodLevels + level;
    const auto& clusterLevels = together.lists.front().shadow ? mesh.shadowClusters : mesh.cameraClusters;
    const bool byClusters = level < clusterLevels.size() && !clusterLevels[level].empty();
    m_togetherCommands.clear(), m_togetherPasses.clear();
    auto command = [&](uint32_t indexCount, uint32_t instances, uint32_t firstIndex, uint32_t entry, size_t pass) {
        m_togetherCommands.insert(m_togetherCommands.end(), {indexCount, instances, firstIndex, 0u, entry});
        m_togetherPasses.push_back(static_cast<uint32_t>(pass));
    };
    for (size_t pass = 0; pass < together.lists.size(); ++pass) {
        const PassList& list = together.lists[pass];
        const uint32_t count = list.count[slot];
        const uint32_t entries = list.offset + list.first[slot];
        if (count == 0) continue;
        if (!byClusters) {
            command(static_cast<uint32_t>(range.indexCount), count,
                    static_cast<uint32_t>(range.byteOffset / sizeof(uint32_t)), entries, pass);
            stats.instances += count;
            stats.triangles += static_cast<size_t>(range.indexCount / 3) * count;
            continue;
        }
        for (uint32_t k = 0; k < count; ++k) {
            const core::Mat4 worldFromObject(
                batch.worldFromObject[instanceOfEntry(list.indices[list.first[slot] + k])]);
            forEachRunMeeting(clusterLevels[level], worldFromObject, together.volumes[pass],
                              [&](uint32_t first, uint32_t indices) {
                                  command(indices, 1, first, entries + k, pass);
                                  stats.triangles += indices / 3;
                              });
            ++stats.instances;
        }
    }
    if (m_togetherPasses.empty()) return stats;
    const size_t draws = m_togetherPasses.size();
    if (m_togetherCapacity < draws) {
        m_togetherCapacity = std::max(draws, 2 * m_togetherCapacity);
        m_togetherCommandBuffer = createBuffer(nullptr, m_togetherCapacity * kIndirectCommandWords * sizeof(uint32_t));
        m_togetherPassBuffer = createBuffer(nullptr, m_togetherCapacity * sizeof(uint32_t));
    }
    uploadToBuffer(m_togetherCommandBuffer.id(), 0, GLsizeiptr(m_togetherCommands.size() * sizeof(uint32_t)),
                   m_togetherCommands.data());
    uploadToBuffer(m_togetherPassBuffer.id(), 0, GLsizeiptr(draws * sizeof(uint32_t)), m_togetherPasses.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDrawPagesBinding, m_togetherPassBuffer.id());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_togetherCommandBuffer.id());
    glUniform1ui(kInstanceOffsetLocation, 0u);
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(draws), 0);
    ++stats.drawCalls;
    return stats;
}

} // namespace shadowkit::gl
