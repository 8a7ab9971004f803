#include "gpu_culling.h"

#include "camera_programs.h"
#include "gl_shaders.h"
#include "program.h"
#include "shadowkit/gl/read_backs.h"
#include "uniforms.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstddef>
#include <string>

namespace shadowkit::gl {
namespace {

// std430 mirrors of gpu_cull.comp's structs.
struct GpuInstance {
    glm::dvec4 minScale;
    glm::dvec4 max;
};
struct GpuBatchInfo {
    uint32_t first, count, cameraLevels, shadowLevels, firstChunk, chunkCount, clustered, pad1;
};
struct GpuLevel {
    float cameraError, shadowError;
    uint32_t cameraIndexCount, cameraFirstIndex, shadowIndexCount, shadowFirstIndex;
    uint32_t keepsCoverage; // bit 0: the camera level keeps coverage, bit 1: the shadow level (gpu_cull.comp)
    uint32_t pad1;
};
static_assert(sizeof(GpuInstance) == 64 && sizeof(GpuBatchInfo) == 32 && sizeof(GpuLevel) == 32);

// `bytes` of `source` from `offset`, read through a copy. Reading the culling's own buffers
// back (glGetNamedBufferSubData on them) made NVIDIA's driver (580) move them to host memory —
// its performance warning names the indirect commands and the lists. `bench` read the levels'
// work after each view, and on an H200 (2026-11-29) every later view of a run spent 3–300 ms of
// CPU a frame in its culling where the first spent 0.2–0.7: by that pattern, each frame then
// waited for the GPU before writing them. A copy on the GPU into a buffer made for it leaves
// them where they are (not yet measured there).
void readThroughCopy(GLuint source, size_t offset, size_t bytes, void* out) {
    const Buffer staging = createBuffer(nullptr, bytes);
    glCopyNamedBufferSubData(source, staging.id(), GLintptr(offset), 0, GLsizeiptr(bytes));
    readBuffer(staging.id(), 0, GLsizeiptr(bytes), out);
}

constexpr size_t kCommandWords = kIndirectCommandWords;
constexpr size_t kMaxPlanes = 6; // gpu_cull.comp's planes[]: a clip volume's or a box's

GpuInstance gpuInstance(const core::Aabb& box, float scale) {
    return {glm::dvec4(box.min, double(scale)), glm::dvec4(box.max, 0.0)};
}

GLint uniform(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

} // namespace

// gpu_cull.comp's Pass: std430 rounds it up to its 32-byte alignment (dvec4).
struct GpuCulling::GpuPass {
    glm::dvec4 planes[kMaxPlanes];
    glm::dmat4 passClipFromWorld;
    double passUnitsPerNdc, passMaxError;
    int32_t planeCount;
    uint32_t pad[3];
};

GpuCulling::GpuPass GpuCulling::gpuPass(std::span<const visibility::HalfSpace> volume,
                                        const LodProjection* projection) {
    static_assert(sizeof(GpuPass) == 352 && offsetof(GpuPass, passClipFromWorld) == 192 &&
                  offsetof(GpuPass, planeCount) == 336);
    GpuPass pass{};
    assert(volume.size() <= kMaxPlanes); // clip volumes and boxes have at most six
    const size_t planeCount = std::min(volume.size(), kMaxPlanes);
    std::copy_n(volume.begin(), planeCount, pass.planes);
    pass.planeCount = int32_t(planeCount);
    if (projection) {
        pass.passClipFromWorld = projection->clipFromWorld;
        pass.passUnitsPerNdc = projection->unitsPerNdc;
        pass.passMaxError = projection->maxError;
    }
    return pass;
}

std::unique_ptr<GpuCulling> GpuCulling::create(const scene::Scene& scene, std::span<const scene::MeshLods> lods,
                                               const GpuScene& gpuScene) {
    auto culling = std::unique_ptr<GpuCulling>(new GpuCulling(gpuScene));
    // Per instance its box and scale, per batch its chunks of kCullGroup and levels.
    std::vector<GpuInstance> instances;
    std::vector<glm::uvec4> chunks;
    std::vector<GpuBatchInfo> batches;
    std::vector<GpuLevel> levels;
    const std::vector<core::Aabb> boxes = scene.instanceBounds();
    uint32_t first = 0;
    for (const scene::MeshBatch& batch : scene.batches) {
        const auto count = static_cast<uint32_t>(batch.worldFromObject.size());
        const scene::MeshLods& lod = lods[batch.mesh];
        GpuBatchInfo info{first,
                          count,
                          static_cast<uint32_t>(std::min(lod.camera.size(), kMaxLodLevels)),
                          static_cast<uint32_t>(std::min(lod.shadow.size(), kMaxLodLevels)),
                          static_cast<uint32_t>(chunks.size()),
                          0,
                          gpuScene.drawsByClusters(batches.size()) ? 1u : 0u, // this batch's, in the scene
                          0};
        // A batch kept out of every pass (clear glass) gets no chunks: its instances are never
        // listed, so the lists count what is drawn.
        const uint32_t culled = gpuScene.keptOut(batches.size()) ? 0 : count;
        for (uint32_t k = 0; k < culled; k += kCullGroup)
            chunks.emplace_back(batches.size(), first + k, std::min<uint32_t>(kCullGroup, culled - k), k);
        info.chunkCount = static_cast<uint32_t>(chunks.size()) - info.firstChunk;
        for (size_t l = 0; l < kMaxLodLevels; ++l) {
            GpuLevel level{};
            if (l < info.cameraLevels)
                level.cameraError = lod.camera[l].objectError, level.cameraIndexCount = lod.camera[l].indexCount,
                level.cameraFirstIndex = lod.camera[l].firstIndex,
                level.keepsCoverage |= lod.camera[l].keepsCoverage ? 1u : 0u;
            if (l < info.shadowLevels)
                level.shadowError = lod.shadow[l].objectError, level.shadowIndexCount = lod.shadow[l].indexCount,
                level.shadowFirstIndex = lod.shadow[l].firstIndex,
                level.keepsCoverage |= lod.shadow[l].keepsCoverage ? 2u : 0u;
            levels.push_back(level);
        }
        for (uint32_t i = 0; i < count; ++i) {
            const float scale = glm::length(glm::vec3(batch.worldFromObject[i][0])); // as Visibility's
            culling->m_scales.push_back(scale);
            instances.push_back(gpuInstance(boxes[first + i], scale));
        }
        culling->m_batchFirst.push_back(first);
        culling->m_batchSize.push_back(count);
        culling->m_cameraLevels.push_back(info.cameraLevels);
        culling->m_shadowLevels.push_back(info.shadowLevels);
        batches.push_back(info);
        first += count;
    }
    culling->m_instanceCount = first;
    culling->m_chunkCount = chunks.size();
    culling->m_batchCount = batches.size();
    // A buffer of size 0 cannot be bound: one element at least.
    auto upload = [](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        return v.empty() ? createBuffer(nullptr, sizeof(T)) : createBuffer(v.data(), v.size() * sizeof(T), true);
    };
    culling->m_instances = upload(instances);
    culling->m_chunks = upload(chunks);
    culling->m_batches = upload(batches);
    culling->m_levels = upload(levels);
    const size_t perInstance = std::max<size_t>(culling->m_instanceCount, 1) * sizeof(uint32_t);
    culling->m_flags = createBuffer(nullptr, perInstance);
    // The ranks and chunk sums grow with the passes a dispatch culls at once (run).
    culling->forget();
    return culling;
}

core::Status GpuCulling::buildPrograms() {
    if (m_depthPrograms.plain.id() != 0) return core::Ok{};
    using namespace shaders;
    for (int stage = 0; stage < 3; ++stage) {
        const std::string define = "#define SK_CULL_STAGE " + std::to_string(stage + 1) + "\n";
        auto program = buildComputeProgram("GPU culling, stage " + std::to_string(stage + 1), {define, kGpuCullComp});
        if (!program) return program.errorInfo();
        m_stages[stage] = std::move(program).value();
    }
    // The scene's sizes, the same for every dispatch.
    for (const Program& stage : m_stages) {
        glProgramUniform1ui(stage.id(), uniform(stage.id(), "instanceCount"), GLuint(m_instanceCount));
        glProgramUniform1ui(stage.id(), uniform(stage.id(), "chunkCount"), GLuint(m_chunkCount));
    }
    glProgramUniform1ui(m_stages[1].id(), uniform(m_stages[1].id(), "batchCount"), GLuint(m_batchCount));
    auto pyramid = buildComputeProgram("GPU culling's depth pyramid", {kDepthPyramidComp});
    if (!pyramid) return pyramid.errorInfo();
    m_pyramidProgram = std::move(pyramid).value();
    auto depth = buildCameraDepthPrePass("GPU culling's depth pre-pass");
    if (!depth) return depth.errorInfo();
    m_depthPrograms = std::move(depth).value();
    return core::Ok{};
}

void GpuCulling::move(uint32_t globalInstance, const core::Aabb& box) {
    const GpuInstance instance = gpuInstance(box, m_scales[globalInstance]);
    uploadToBuffer(m_instances.id(), GLintptr(globalInstance * sizeof(GpuInstance)), sizeof instance, &instance);
}

void GpuCulling::forget() {
    const uint32_t zero = 0;
    glClearNamedBufferData(m_flags.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

size_t GpuCulling::passesWithinBudget() const {
    return std::max<size_t>(1, kListBudgetBytes / (regionWords() * sizeof(uint32_t)));
}

void GpuCulling::beginFrame(size_t passes) {
    if (passes <= m_passCapacity) return;
    // Twice the last capacity, so that a growing frame reallocates rarely, within the budget.
    m_passCapacity = std::max(passes, std::min(2 * m_passCapacity, passesWithinBudget()));
    const size_t region = regionWords();
    m_lists = createBuffer(nullptr, m_passCapacity * region * sizeof(uint32_t));
    const size_t commands = std::max<size_t>(m_batchCount, 1) * kMaxLodLevels * m_passCapacity;
    m_commandWords = commands * kCommandWords;
    m_commands = createBuffer(nullptr, m_commandWords * sizeof(uint32_t));
    m_passes = createBuffer(nullptr, m_passCapacity * sizeof(GpuPass));
}

void GpuCulling::cull(size_t pass, std::span<const visibility::HalfSpace> volume, const LodChoice* lod, Phase phase,
                      PassList& out, const GpuReceiverMask* mask, uint32_t replicas, bool leaveClustered) {
    const Stopwatch inGl;
    const GLuint p = m_stages[0].id();
    glProgramUniform1i(p, uniform(p, "phase"), static_cast<GLint>(phase));
    glProgramUniform1i(p, uniform(p, "maskOn"), mask ? 1 : 0);
    if (mask) {
        const int texels = kReceiverMaskSize * kReceiverMaskSize;
        glProgramUniform1i(p, uniform(p, "maskSize"), kReceiverMaskSize);
        glProgramUniform1i(p, uniform(p, "maskBase"), mask->map * texels);
        glProgramUniform1i(p, uniform(p, "maskFlag"), mask->mapCount * texels + mask->map);
        glProgramUniformMatrix4dv(p, uniform(p, "maskClipFromWorld"), 1, GL_FALSE, &mask->clipFromWorld[0][0]);
        glProgramUniform1i(p, uniform(p, "maskLinear"), mask->linearDepthFromWorld ? 1 : 0);
        if (mask->linearDepthFromWorld)
            glProgramUniform4dv(p, uniform(p, "maskLinearDepthFromWorld"), 1, &mask->linearDepthFromWorld->x);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDilatedMaskBinding, mask->buffer);
    }
    const bool occlusion = phase == Phase::NewlyVisible || phase == Phase::Visible;
    if (occlusion) {
        glProgramUniform1i(p, uniform(p, "pyramidLevels"), m_pyramidLevels);
        glProgramUniform4iv(p, uniform(p, "pyramidLevel"), m_pyramidLevels, &m_pyramidLayout[0].x);
        glProgramUniform2i(p, uniform(p, "viewport"), m_viewport.x, m_viewport.y);
        glProgramUniformMatrix4fv(p, uniform(p, "clipFromWorld"), 1, GL_FALSE, &m_cameraClipFromWorld[0][0]);
        glProgramUniform3fv(p, uniform(p, "wsEye"), 1, &m_wsEye.x);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullStageBinding, m_pyramid.id());
    }
    const GpuPass one = gpuPass(volume, lod ? &lod->pass : nullptr);
    run(pass, std::span(&one, 1), lod, leaveClustered, replicas, std::span(&out, 1));
    m_gl += inGl.elapsed();
}

void GpuCulling::cullPasses(size_t firstPass, std::span<const PassVolume> passes, const LodChoice* lod,
                            bool leaveClustered, std::span<PassList> out) {
    if (passes.empty()) return;
    const Stopwatch inGl;
    const GLuint p = m_stages[0].id();
    glProgramUniform1i(p, uniform(p, "phase"), static_cast<GLint>(Phase::All));
    glProgramUniform1i(p, uniform(p, "maskOn"), 0);
    std::vector<GpuPass> each;
    for (const PassVolume& pass : passes) each.push_back(gpuPass(pass.volume, lod ? &pass.projection : nullptr));
    run(firstPass, each, lod, leaveClustered, 1, out);
    m_gl += inGl.elapsed();
}

void GpuCulling::run(size_t firstPass, std::span<const GpuPass> passes, const LodChoice* lod, bool leaveClustered,
                     uint32_t replicas, std::span<PassList> out) {
    // Each pass's volume and projection at its index; the scratch for as many passes at once.
    uploadToBuffer(m_passes.id(), GLintptr(firstPass * sizeof(GpuPass)), GLsizeiptr(passes.size() * sizeof(GpuPass)),
                   passes.data());
    if (passes.size() > m_scratchPasses) {
        m_scratchPasses = passes.size();
        m_ranks = createBuffer(nullptr, m_scratchPasses * std::max<size_t>(m_instanceCount, 1) * sizeof(uint32_t));
        m_chunkSums = createBuffer(nullptr, m_scratchPasses * std::max<size_t>(m_chunkCount, 1) * kMaxLodLevels *
                                                sizeof(uint32_t));
    }
    const GLuint p = m_stages[0].id();
    glProgramUniform1i(p, uniform(p, "leaveClustered"), leaveClustered ? 1 : 0);
    const bool shadowChain = lod && lod->shadow;
    glProgramUniform1i(p, uniform(p, "lodOn"), lod ? 1 : 0);
    glProgramUniform1i(p, uniform(p, "shadowChain"), shadowChain ? 1 : 0);
    if (lod) {
        glProgramUniform1d(p, uniform(p, "coverageScale"), lod->coverageScale);
        glProgramUniform1d(p, uniform(p, "fadeBand"), lod->fadeBand);
        glProgramUniform1i(p, uniform(p, "cameraBound"), lod->camera ? 1 : 0);
        if (lod->camera) {
            glProgramUniformMatrix4dv(p, uniform(p, "cameraClipFromWorld"), 1, GL_FALSE,
                                      &lod->camera->clipFromWorld[0][0]);
            glProgramUniform1d(p, uniform(p, "cameraUnitsPerNdc"), lod->camera->unitsPerNdc);
            glProgramUniform1d(p, uniform(p, "cameraMaxError"), lod->camera->maxError);
        }
    }
    for (const Program& stage : m_stages)
        glProgramUniform1ui(stage.id(), uniform(stage.id(), "firstPass"), GLuint(firstPass));
    glUseProgram(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullInstancesBinding, m_instances.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullChunksBinding, m_chunks.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullBatchesBinding, m_batches.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullLevelsBinding, m_levels.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullFlagsBinding, m_flags.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullRanksBinding, m_ranks.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullChunkSumsBinding, m_chunkSums.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullPassesBinding, m_passes.id());
    const auto passCount = GLuint(passes.size());
    dispatchCompute(GLuint(m_chunkCount), passCount, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    // Stage 2: offsets and commands; stage 3: the lists.
    const GLuint offsets = m_stages[1].id(), scatter = m_stages[2].id();
    glProgramUniform1i(offsets, uniform(offsets, "shadowChain"), shadowChain ? 1 : 0);
    glProgramUniform1ui(offsets, uniform(offsets, "replicas"), replicas);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullStageBinding, m_commands.id());
    glUseProgram(offsets);
    dispatchCompute(GLuint((kMaxLodLevels * m_batchCount + 63) / 64), passCount, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullStageBinding, m_lists.id());
    glUseProgram(scatter);
    dispatchCompute(GLuint(m_chunkCount), passCount, 1);
    // The draws read the lists in vertex shaders and the commands as indirect arguments.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    for (size_t i = 0; i < out.size(); ++i) describe(firstPass + i, shadowChain, out[i]);
}

void GpuCulling::describe(size_t pass, bool shadowChain, PassList& out) const {
    // Each batch's kMaxLodLevels levels get a region of its instance count each: the CPU knows where
    // every list lies without knowing how long it is.
    out.indices.clear();
    out.shadow = shadowChain;
    out.first.assign(m_batchCount * kMaxLodLevels, 0);
    out.count.assign(m_batchCount * kMaxLodLevels, 0);
    for (size_t b = 0; b < m_batchCount; ++b) {
        const uint32_t levels = shadowChain ? m_shadowLevels[b] : m_cameraLevels[b];
        for (uint32_t l = 0; l < levels; ++l) {
            out.first[b * kMaxLodLevels + l] = uint32_t(kMaxLodLevels) * m_batchFirst[b] + l * m_batchSize[b];
            out.count[b * kMaxLodLevels + l] = m_batchSize[b];
        }
    }
    out.offset = uint32_t(pass * kMaxLodLevels * m_instanceCount);
    out.buffer = m_lists.id();
    out.commands = m_commands.id();
    out.indirect = int64_t(pass * m_batchCount * kMaxLodLevels);
}

void GpuCulling::buildPyramid(const CameraDepthTarget& target) {
    // Level 0 a power of two a side (levels then halve exactly), at least half the pixels.
    const int width = int(std::bit_ceil(unsigned(target.width + 1) / 2u));
    const int height = int(std::bit_ceil(unsigned(target.height + 1) / 2u));
    if (width != m_pyramidWidth || height != m_pyramidHeight) {
        m_pyramidWidth = width, m_pyramidHeight = height;
        m_pyramidLevels = std::bit_width(unsigned(std::max(width, height)));
        size_t texels = 0;
        for (int level = 0; level < m_pyramidLevels; ++level) {
            m_pyramidLayout[size_t(level)] = {std::max(1, width >> level), std::max(1, height >> level), int(texels),
                                              0};
            texels += size_t(m_pyramidLayout[size_t(level)].x) * size_t(m_pyramidLayout[size_t(level)].y);
        }
        m_pyramid = createBuffer(nullptr, texels * sizeof(float));
    }
    const GLuint p = m_pyramidProgram.id();
    glUseProgram(p);
    glBindTextureUnit(kCullPyramidUnit, target.depth.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullStageBinding, m_pyramid.id());
    glm::ivec4 source(target.width, target.height, 0, 0);
    for (int level = 0; level < m_pyramidLevels; ++level) {
        const glm::ivec4 at = m_pyramidLayout[size_t(level)];
        glProgramUniform1i(p, uniform(p, "fromDepth"), level == 0 ? 1 : 0);
        glProgramUniform2i(p, uniform(p, "sourceSize"), source.x, source.y);
        glProgramUniform2i(p, uniform(p, "targetSize"), at.x, at.y);
        glProgramUniform1i(p, uniform(p, "sourceOffset"), source.z);
        glProgramUniform1i(p, uniform(p, "targetOffset"), at.z);
        dispatchCompute(GLuint(at.x + 7) / 8, GLuint(at.y + 7) / 8, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        source = at;
    }
}

void GpuCulling::camera(const core::PerspectiveCamera& camera, const LodChoice* lod, CameraDepthTarget& target,
                        PassList& out, const PassList* clustered) {
    const core::Mat4 clipFromWorld = camera.clipFromWorld();
    const std::vector<visibility::HalfSpace> frustum = visibility::clipVolume(clipFromWorld);
    m_cameraClipFromWorld = glm::mat4(clipFromWorld);
    m_wsEye = glm::vec3(camera.wsEye);
    m_viewport = {target.width, target.height};
    auto drawDepth = [&](const PassList& list, std::span<const visibility::HalfSpace> volume) {
        const Stopwatch inGl;
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, target.width, target.height);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        m_scene.draw(list, m_depthPrograms.passPrograms(), volume); // a GPU list ignores the volume
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        m_gl += inGl.elapsed();
    };
    const bool leaveClustered = clustered != nullptr;
    cull(0, frustum, lod, Phase::LastVisible, m_early, nullptr, 1, leaveClustered);
    target.clear();
    // The terrain, the first occluder of any view, in the depth the pyramid is built from; first,
    // as the lists' batch order draws it, so that where a box standing on it ties in depth the
    // pre-pass keeps the same surface as a list drawn in batch order.
    if (clustered) drawDepth(*clustered, frustum);
    drawDepth(m_early, {});
    const Stopwatch pyramidTime;
    buildPyramid(target);
    m_gl += pyramidTime.elapsed();
    cull(1, frustum, lod, Phase::NewlyVisible, m_late, nullptr, 1, leaveClustered);
    drawDepth(m_late, {});
    cull(2, frustum, lod, Phase::Visible, out, nullptr, 1, leaveClustered);
}

DrawStats GpuCulling::drawnBy(std::span<const uint32_t> commands, int64_t indirect, std::span<const uint32_t> count) {
    DrawStats drawn;
    const uint32_t* command = commands.data() + size_t(indirect) * kCommandWords;
    for (size_t slot = 0; slot < count.size(); ++slot) {
        if (count[slot] == 0) continue;
        const uint32_t indexCount = command[slot * kCommandWords], instances = command[slot * kCommandWords + 1];
        drawn.instances += instances;
        drawn.triangles += size_t(indexCount / 3) * instances;
    }
    return drawn;
}

std::vector<DrawStats> GpuCulling::submitted(std::span<const PassList* const> lists) const {
    std::vector<DrawStats> drawn(lists.size());
    if (lists.empty()) return drawn;
    detail::countReadBack(); // every list's commands after one wait
    std::vector<uint32_t> commands(m_commandWords);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    readThroughCopy(m_commands.id(), 0, commands.size() * sizeof(uint32_t), commands.data());
    for (size_t i = 0; i < lists.size(); ++i) drawn[i] = drawnBy(commands, lists[i]->indirect, lists[i]->count);
    return drawn;
}

DrawStats GpuCulling::submitted(const PassList& list) const {
    const PassList* one[] = {&list};
    return submitted(one).front();
}

DrawStats GpuCulling::submitted(std::span<const PassList> lists) const {
    std::vector<const PassList*> each;
    for (const PassList& list : lists) each.push_back(&list);
    DrawStats sum;
    for (const DrawStats& drawn : submitted(each)) sum += drawn;
    return sum;
}

GpuReceiverMask GpuReceiverMask::of(const ReceiverMasks& masks, const core::ShadowSetup& setup, size_t view) {
    const bool linear = setup.depthLayout == core::DepthLayout::Linear;
    return {masks.dilatedMasks().id(), int(view), int(setup.views.size()), setup.views[view].clipFromWorld,
            linear ? std::optional(setup.views[view].linearDepthFromWorld) : std::nullopt};
}

PassList GpuCulling::read(const PassList& list) const {
    detail::countReadBack(); // the commands and the lists after one wait
    const size_t slots = m_batchCount * kMaxLodLevels;
    std::vector<uint32_t> commands(slots * kCommandWords), region(kMaxLodLevels * m_instanceCount);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    readThroughCopy(m_commands.id(), size_t(list.indirect) * kCommandWords * sizeof(uint32_t),
                    commands.size() * sizeof(uint32_t), commands.data());
    readThroughCopy(m_lists.id(), size_t(list.offset) * sizeof(uint32_t), region.size() * sizeof(uint32_t),
                    region.data());
    PassList cpu;
    cpu.shadow = list.shadow;
    cpu.first.assign(slots, 0);
    cpu.count.assign(slots, 0);
    for (size_t slot = 0; slot < slots; ++slot) {
        const uint32_t instances = list.count[slot] == 0 ? 0 : commands[slot * kCommandWords + 1];
        cpu.first[slot] = uint32_t(cpu.indices.size());
        cpu.count[slot] = instances;
        cpu.indices.insert(cpu.indices.end(), region.begin() + list.first[slot],
                           region.begin() + list.first[slot] + instances);
    }
    return cpu;
}

} // namespace shadowkit::gl
