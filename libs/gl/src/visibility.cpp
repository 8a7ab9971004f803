#include "visibility.h"

#include "uniforms.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <functional>

namespace shadowkit::gl {
namespace {

// NDC units per world metre at `ws` through a projective map: the largest column of
// d(ndc.xy)/d(ws) = (M_i.xy − ndc.xy · M_i.w) / w over the world axes i (the map may
// stretch one axis more than another). Infinite at or behind the projection centre.
double ndcPerMetre(const core::Mat4& clipFromWorld, const core::Vec3& ws) {
    const core::Vec4 c = clipFromWorld * core::Vec4(ws, 1.0);
    if (!(c.w > 1e-9)) return INFINITY;
    const core::Vec2 ndc = core::Vec2(c) / c.w;
    double largest = 0.0;
    for (int i = 0; i < 3; ++i) {
        const core::Vec4 column = clipFromWorld[i];
        largest = std::max(largest, glm::length((core::Vec2(column) - ndc * column.w) / c.w));
    }
    return largest;
}

// Whether the map is affine (its w row 0, 0, 0, 1: an orthographic map, a virtual page's): a metre
// then spans the same NDC everywhere, ndcPerMetre's w being 1 exactly at every point.
bool affine(const core::Mat4& clipFromWorld) {
    return clipFromWorld[0][3] == 0.0 && clipFromWorld[1][3] == 0.0 && clipFromWorld[2][3] == 0.0 &&
           clipFromWorld[3][3] == 1.0;
}

} // namespace

scene::LodOptions lodOptionsOf(const scene::Scene& scene, const scene::Mesh& mesh) {
    const scene::Material* material = scene.materialOf(mesh);
    const bool keepWhole = material && material->alphaTested() && mesh.authoredLods.empty();
    return {.maxLevels = keepWhole ? 1 : 4, .maxAuthoredLevels = static_cast<int>(kMaxLodLevels)};
}

uint32_t fadeStepsOf(double allowed, double coarserError, double fadeBand) {
    if (!(fadeBand > 0.0) || !(coarserError > 0.0)) return 0;
    const double share = (allowed / coarserError - (1.0 - fadeBand)) / fadeBand;
    if (!(share > 0.0)) return 0;
    return static_cast<uint32_t>(std::min(std::floor(share * kFadeSteps), double(kFadeSteps - 1)));
}

Visibility::Visibility(const scene::Scene& scene, std::span<const scene::MeshLods> lods)
    : m_hierarchy(scene.instanceBounds()) {
    uint32_t first = 0;
    for (const scene::MeshBatch& batch : scene.batches) {
        // Checked by Renderer::create: list entries keep kListIndexBits for the index.
        assert(batch.worldFromObject.size() <= kListIndexMask + size_t{1});
        m_batchFirst.push_back(first);
        first += static_cast<uint32_t>(batch.worldFromObject.size());
        for (const glm::mat4& m : batch.worldFromObject) {
            m_instanceScale.push_back(glm::length(glm::vec3(m[0]))); // rigid + uniform scale
            m_instanceMesh.push_back(batch.mesh);
        }
    }
    m_batchFirst.push_back(first); // end of the last batch
    for (size_t b = 0; b + 1 < m_batchFirst.size(); ++b) {
        const auto scales = std::span(m_instanceScale).subspan(m_batchFirst[b], m_batchFirst[b + 1] - m_batchFirst[b]);
        if (!scales.empty())
            m_batchScale.push_back({*std::ranges::min_element(scales), *std::ranges::max_element(scales)});
        else
            m_batchScale.push_back({1.0f, 1.0f});
    }
    for (const scene::MeshLods& mesh : lods) {
        for (const auto& [chain, bounds] :
             {std::pair{&mesh.camera, &m_cameraLevels}, {&mesh.shadow, &m_shadowLevels}}) {
            std::vector<LevelBound>& levels = bounds->emplace_back();
            for (size_t l = 0; l < std::min(chain->size(), kMaxLodLevels); ++l)
                levels.push_back({(*chain)[l].objectError, (*chain)[l].keepsCoverage});
        }
    }
}

void Visibility::sortIntoScratch(std::span<const uint32_t> items) {
    // All bits are set before m_scratch is rewritten, so `items` may be m_scratch itself.
    m_visibleBits.assign((m_hierarchy.size() + 63) / 64, 0);
    for (const uint32_t i : items) m_visibleBits[i / 64] |= uint64_t{1} << (i % 64);
    m_scratch.clear();
    for (size_t word = 0; word < m_visibleBits.size(); ++word)
        for (uint64_t bits = m_visibleBits[word]; bits != 0; bits &= bits - 1)
            m_scratch.push_back(static_cast<uint32_t>(64 * word + static_cast<size_t>(std::countr_zero(bits))));
}

void Visibility::fromItems(std::span<const uint32_t> items, const LodChoice* lod, PassList& out) {
    // Already increasing (a virtual page's few clustered meshes): no pass over every instance.
    if (std::ranges::adjacent_find(items, std::greater_equal<>()) == items.end())
        m_scratch.assign(items.begin(), items.end());
    else
        sortIntoScratch(items);
    build(lod, out);
}

void Visibility::collect(std::span<const visibility::HalfSpace> volume, bool cull, const LodChoice* lod, PassList& out,
                         const visibility::ReceiverMask* receivers) {
    m_scratch.clear();
    if (cull) {
        // The hierarchy answers in tree order; a bitmap over every instance puts the answer
        // back in instance order in O(n / 64 + visible), cheaper than sorting it.
        if (receivers)
            m_hierarchy.query(
                volume, [receivers](const core::Aabb& box) { return receivers->mayShadow(box); }, m_scratch);
        else
            m_hierarchy.query(volume, m_scratch);
        sortIntoScratch(m_scratch);
    } else {
        m_scratch.resize(m_hierarchy.size());
        for (uint32_t i = 0; i < m_scratch.size(); ++i) m_scratch[i] = i;
    }
    build(lod, out);
}

void Visibility::build(const LodChoice* lod, PassList& out) {
    const Stopwatch time;
    // The level of each instance: the coarsest whose world error (object error × scale),
    // in the pass's units, stays within the bound.
    m_levels.assign(m_scratch.size(), 0);
    m_fades.assign(m_scratch.size(), 0);
    if (lod) {
        const auto& chains = lod->shadow ? m_shadowLevels : m_cameraLevels;
        for (size_t k = 0; k < m_scratch.size(); ++k) {
            const uint32_t global = m_scratch[k];
            const std::vector<LevelBound>& levels = chains[m_instanceMesh[global]];
            if (levels.size() < 2) continue;
            const core::Vec3 centre = m_hierarchy.itemBounds(global).center();
            auto allowedBy = [&](const LodProjection& p) { // in object metres
                return p.maxError / (p.unitsPerNdc * ndcPerMetre(p.clipFromWorld, centre) * m_instanceScale[global]);
            };
            double allowed = allowedBy(lod->pass);
            if (lod->camera) allowed = std::min(allowed, allowedBy(*lod->camera));
            // Levels that keep coverage may err coverageScale times more (the GPU's levelOf alike).
            auto boundOf = [&](const LevelBound& l) {
                return l.keepsCoverage ? allowed * lod->coverageScale : allowed;
            };
            const uint8_t level = levelWithin(levels, allowed, lod->coverageScale);
            m_levels[k] = level;
            // Crossing into the next level only where it keeps coverage: the leaves' levels are
            // alpha-tested, so their fragment stages can drop the other level's pixels.
            if (level + 1u < levels.size() && levels[level + 1u].keepsCoverage)
                m_fades[k] = static_cast<uint8_t>(
                    fadeStepsOf(boundOf(levels[level + 1u]), double(levels[level + 1u].objectError), lod->fadeBand));
        }
    }
    // Global indices are sorted and batches are consecutive global ranges: a counting sort
    // by (batch, level) keeps each list in increasing instance order.
    const size_t batches = m_batchFirst.size() - 1;
    out.shadow = lod && lod->shadow;
    out.indirect = -1; // a list of the CPU's, drawn from its counts (and the last frame's may have been the GPU's)
    out.commands = 0;
    out.first.assign(batches * kMaxLodLevels, 0);
    out.count.assign(batches * kMaxLodLevels, 0);
    std::vector<uint32_t>& slotOf = m_slots;
    slotOf.resize(m_scratch.size());
    size_t batch = 0, entries = 0;
    for (size_t k = 0; k < m_scratch.size(); ++k) {
        while (m_scratch[k] >= m_batchFirst[batch + 1]) ++batch;
        slotOf[k] = static_cast<uint32_t>(batch * kMaxLodLevels + m_levels[k]);
        ++out.count[slotOf[k]];
        if (m_fades[k] != 0) ++out.count[slotOf[k] + 1]; // and in the next level's list
        entries += m_fades[k] != 0 ? 2 : 1;
    }
    uint32_t running = 0;
    for (size_t slot = 0; slot < out.count.size(); ++slot) {
        out.first[slot] = running;
        running += out.count[slot];
    }
    out.indices.resize(entries);
    std::vector<uint32_t>& cursor = m_cursor;
    cursor.assign(out.first.begin(), out.first.end());
    batch = 0;
    for (size_t k = 0; k < m_scratch.size(); ++k) {
        while (m_scratch[k] >= m_batchFirst[batch + 1]) ++batch;
        const uint32_t local = m_scratch[k] - m_batchFirst[batch];
        const uint32_t fade = uint32_t(m_fades[k]) << kListIndexBits;
        out.indices[cursor[slotOf[k]]++] = local | fade;
        if (fade != 0) out.indices[cursor[slotOf[k] + 1]++] = local | fade | kFadeIncoming;
    }
    m_listTimes += time.elapsed();
}

uint8_t Visibility::levelWithin(const std::vector<LevelBound>& levels, double allowed, double coverageScale) {
    uint8_t level = 0;
    while (level + 1u < levels.size()) {
        const LevelBound& next = levels[level + 1u];
        if (!(double(next.objectError) <= (next.keepsCoverage ? allowed * coverageScale : allowed))) break;
        ++level;
    }
    return level;
}

void Visibility::emptyLevelsNoneTakes(PassList& list, const LodChoice* lod) const {
    // Through an affine map without a camera bound an instance's allowed error is the map's bound
    // over its scale alone, the same arithmetic as build()'s; the level only grows with it. So a
    // batch's instances take the levels between those of its largest and its smallest scale (and
    // the next, crossing into it).
    if (lod && (lod->camera || !affine(lod->pass.clipFromWorld))) return;
    const auto& chains = list.shadow ? m_shadowLevels : m_cameraLevels;
    const double npm = lod ? ndcPerMetre(lod->pass.clipFromWorld, core::Vec3(0.0)) : 0.0;
    for (size_t b = 0; b + 1 < m_batchFirst.size(); ++b) {
        size_t first = 0, last = 0;
        if (lod && m_batchFirst[b + 1] > m_batchFirst[b]) {
            const std::vector<LevelBound>& levels = chains[m_instanceMesh[m_batchFirst[b]]];
            const auto allowedAt = [&](float scale) {
                return lod->pass.maxError / (lod->pass.unitsPerNdc * npm * double(scale));
            };
            if (levels.size() >= 2) {
                first = levelWithin(levels, allowedAt(m_batchScale[b].largest), lod->coverageScale);
                last = levelWithin(levels, allowedAt(m_batchScale[b].smallest), lod->coverageScale);
                if (lod->fadeBand > 0.0 && last + 1 < levels.size()) ++last;
            }
        }
        for (size_t level = 0; level < kMaxLodLevels && b * kMaxLodLevels + level < list.count.size(); ++level)
            if (level < first || level > last) list.count[b * kMaxLodLevels + level] = 0;
    }
}

void Visibility::upload(std::span<PassList* const> lists) {
    const Stopwatch time;
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
    uploadToBuffer(m_buffer.id(), 0, static_cast<GLsizeiptr>(m_staging.size() * sizeof(uint32_t)), m_staging.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, m_buffer.id());
    for (PassList* list : lists) list->buffer = m_buffer.id();
    m_listTimes += time.elapsed();
}

bool Visibility::rebuildIfDegraded() {
    if (m_hierarchy.degradation() <= kRebuildDegradation) return false;
    m_hierarchy.rebuild();
    return true;
}

} // namespace shadowkit::gl
