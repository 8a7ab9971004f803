// Per-pass visibility: which instances of each batch a pass draws. The camera pass keeps
// the instances whose box meets the view frustum; each shadow map keeps those meeting its
// clip volume extended towards the light (no near plane: the pass clamps depth, so casters
// between the light and the map's near plane still cast). Lists of batch-local instance
// indices for every pass of a frame go into one shader-storage buffer that the vertex
// shaders index through (SK_VISIBLE_BINDING, uniform instanceOffset).
#pragma once

#include "gl_object.h"
#include "stopwatch.h"

#include "shadowkit/scene/mesh_lod.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/visibility/instance_hierarchy.h"
#include "shadowkit/visibility/receiver_mask.h"

#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace shadowkit::gl {

// Levels drawn per mesh (scene::LodOptions::maxLevels): the full mesh and up to four coarser, as
// the leafy trees' 32-, 16-, 8- and 4-slab clouds.
inline constexpr size_t kMaxLodLevels = 5;

// The levels built for `mesh` of `scene` (Renderer::create): an alpha-tested mesh keeps its one
// level unless it brings its own (leaf cards, clouds): a simplifier moves positions under fixed
// uvs (and the shadow chain's vertex clustering joins vertices of different cards), so a
// simplified card would no longer show the leaf. A simplified chain keeps the four levels every
// blob-forest figure was measured with; a mesh's own levels take up to kMaxLodLevels.
scene::LodOptions lodOptionsOf(const scene::Scene& scene, const scene::Mesh& mesh);

// glDrawElementsIndirect's command: index count, instance count, first index, base vertex, base instance.
inline constexpr size_t kIndirectCommandWords = 5;

// A list entry (a word of PassList::indices): the batch-local instance index in the low
// kListIndexBits bits. An instance crossing into a coarser level of detail (LodChoice::fadeBand)
// is in both levels' lists, each entry with the coarser level's share of the pixels in 128ths in
// bits 24–30, and bit 31 set in the coarser level's: the fragment stages keep the pixels whose
// dither threshold lies below the share in the coarser level and the others in the finer one
// (visible.glsl, material.glsl), so the two draws together cover each pixel once.
inline constexpr uint32_t kListIndexBits = 24;
inline constexpr uint32_t kListIndexMask = (1u << kListIndexBits) - 1u;
inline constexpr uint32_t kFadeSteps = 128;         // the share's resolution
inline constexpr uint32_t kFadeIncoming = 1u << 31; // the coarser level's entry
inline constexpr uint32_t instanceOfEntry(uint32_t entry) { return entry & kListIndexMask; }

// One pass's instances: for each batch and level of detail, a range of `indices` holding
// batch-local instance indices (list entries, above) in increasing order (the order a full draw
// would use, so culling changes no pixel). `offset` is where `indices` starts in the frame's buffer.
struct PassList {
    std::vector<uint32_t> indices;
    std::vector<uint32_t> first, count; // [batch * kMaxLodLevels + level], into `indices`
    uint32_t offset = 0;
    bool shadow = false; // levels from the shadow chains (MeshLods::shadow)
    // The buffer `indices` live in on the GPU, bound at SK_VISIBLE_BINDING to draw (0: the
    // one bound). A list GPU culling writes (gpu_culling.h) has no `indices` on the CPU: each
    // range holds up to `count` entries, and the number drawn is in its glDrawElementsIndirect
    // command, the `indirect`-th + batch * kMaxLodLevels + level of `commands`.
    GLuint buffer = 0;
    GLuint commands = 0;
    int64_t indirect = -1;
    // The order the pass draws its batches in (every batch index once), empty for index order.
    // Depth-only passes draw nearest first: what is covered is then rejected, not written.
    std::vector<uint32_t> batchOrder;
    size_t instances() const { return indices.size(); }
};

// How a pass picks levels of detail: the coarsest level whose geometric error, projected at
// the instance's centre, stays within every bound: `maxError` units of the pass's own map
// (pixels for the camera, texels for a shadow map; one NDC unit is `unitsPerNdc`), and
// for shadow maps also `cameraMaxError` pixels of the camera, since a caster's shadow lies
// near it and a texel of a uniform map can cover dozens of pixels there.
struct LodProjection {
    core::Mat4 clipFromWorld{1.0};
    double unitsPerNdc = 1.0;
    double maxError = 0.5;
};
struct LodChoice {
    LodProjection pass;
    std::optional<LodProjection> camera; // shadow passes
    bool shadow = false;
    // Levels that keep coverage (scene::LodLevel::keepsCoverage) may err this many times more
    // than both bounds allow (RenderSettings::lodFoliageScale).
    double coverageScale = 1.0;
    // An instance crosses into a coarser level that keeps coverage over this fraction of the
    // level's bound: where its allowed error is a fraction a ∈ [1 − fadeBand, 1) of the bound the
    // level needs, it is drawn at both levels, the coarser one taking the share
    // (a − (1 − fadeBand)) / fadeBand of its pixels. 0: levels switch at the bound. From
    // RenderSettings::lodFade, centred on the switch by pass_lists.cpp's lodChoiceOf.
    double fadeBand = 0.0;
};

// The coarser level's share of the pixels, in kFadeSteps (0: not crossing), for an instance
// allowed `allowed` of error where the coarser level errs `coarserError` (in the same units):
// 0 up to allowed = (1 − fadeBand) × coarserError, rising linearly to all but the last step just
// below allowed = coarserError, where the pass takes the coarser level outright. The GPU's
// culling pass computes the same in double precision (gpu_cull.comp, fadeOf).
uint32_t fadeStepsOf(double allowed, double coarserError, double fadeBand);

class Visibility {
public:
    Visibility(const scene::Scene& scene, std::span<const scene::MeshLods> lods);

    const core::Aabb& bounds() const { return m_hierarchy.bounds(); } // in the scene's coordinates
    const visibility::InstanceHierarchy& hierarchy() const { return m_hierarchy; }
    // The global index of each batch's first instance, and the instance count last.
    std::span<const uint32_t> batchFirst() const { return m_batchFirst; }

    // The instances the half-spaces may see (every instance when `cull` is false), each at
    // the level `lod` picks (the full mesh without one).
    // With a receiver mask, only the instances it says may shadow a visible receiver.
    void collect(std::span<const visibility::HalfSpace> volume, bool cull, const LodChoice* lod, PassList& out,
                 const visibility::ReceiverMask* receivers = nullptr);
    // The same for a given set of global instance indices (any order, no repeats), e.g. what
    // occlusion culling drew: the list comes out in instance order like collect()'s.
    void fromItems(std::span<const uint32_t> items, const LodChoice* lod, PassList& out);
    // A list the GPU culled with `lod` (its ranges are capacities, GpuCulling): the ranges of the
    // levels none of its instances can take emptied, so that they are not drawn — when the level
    // depends on an instance's scale alone (an affine map, no camera bound: a virtual page's),
    // else nothing changes.
    void emptyLevelsNoneTakes(PassList& list, const LodChoice* lod) const;
    // An instance moved: its new world box, refitted into the hierarchy up to the root.
    void move(uint32_t globalInstance, const core::Aabb& wsBox) { m_hierarchy.update(globalInstance, wsBox); }
    // After a frame's moves: rebuilds the hierarchy when the refits have made it
    // kRebuildDegradation times as costly to query as built (movers stretch their leaves
    // across the world). True when it did: node indices changed.
    bool rebuildIfDegraded();
    static constexpr double kRebuildDegradation = 1.25;
    // Assigns offsets and uploads every list of the frame into one buffer, bound at
    // SK_VISIBLE_BINDING.
    void upload(std::span<PassList* const> lists);
    // Time spent choosing levels, building lists and uploading them (every pass's work,
    // culled or not) since the last call; resets it.
    CpuTimes takeListTimes() { return std::exchange(m_listTimes, {}); }

private:
    // m_scratch (increasing global indices) → `out`, by batch and level.
    void build(const LodChoice* lod, PassList& out);
    // m_scratch = `items` (distinct global indices) in increasing order, through a bitmap
    // over every instance: O(n / 64 + items), cheaper than sorting.
    void sortIntoScratch(std::span<const uint32_t> items);

    visibility::InstanceHierarchy m_hierarchy; // items in global instance order (Scene order)
    std::vector<uint32_t> m_batchFirst;        // global index of each batch's first instance
    // Per global instance: its uniform scale and mesh; a level's world error is the mesh's
    // object error for that level times the scale.
    std::vector<float> m_instanceScale;
    std::vector<uint32_t> m_instanceMesh;
    // What a pass compares of a level (scene::LodLevel): its error in object metres, and whether
    // it keeps coverage (judged against LodChoice::coverageScale times the bound).
    struct LevelBound {
        float objectError = 0.0f;
        bool keepsCoverage = false;
    };
    std::vector<std::vector<LevelBound>> m_cameraLevels, m_shadowLevels; // per mesh, per level
    // The coarsest level of `levels` whose error is within `allowed` (object metres; levels that
    // keep coverage within coverageScale times it): the level rule of build() and gpu_cull.comp.
    static uint8_t levelWithin(const std::vector<LevelBound>& levels, double allowed, double coverageScale);
    struct ScaleRange {
        float smallest = 1.0f, largest = 1.0f;
    };
    std::vector<ScaleRange> m_batchScale;    // per batch: its instances' scales
    std::vector<uint8_t> m_levels;           // level per visible instance, reused every pass
    std::vector<uint8_t> m_fades;            // its crossing into the next level (fadeStepsOf), reused
    std::vector<uint32_t> m_slots, m_cursor; // counting-sort scratch, reused every pass
    std::vector<uint64_t> m_visibleBits;     // one bit per instance, reused every pass
    std::vector<uint32_t> m_scratch;         // query result, reused every pass
    std::vector<uint32_t> m_staging;         // the frame's concatenated lists
    Buffer m_buffer;
    size_t m_capacity = 0; // in indices
    CpuTimes m_listTimes;
};

} // namespace shadowkit::gl
