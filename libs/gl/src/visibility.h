// Per-pass visibility: which instances of each batch a pass draws. The camera pass keeps
// the instances whose box meets the view frustum; each shadow map keeps those meeting its
// clip volume extended towards the light (no near plane: the pass clamps depth, so casters
// between the light and the map's near plane still cast). Lists of batch-local instance
// indices for every pass of a frame go into one shader-storage buffer that the vertex
// shaders index through (SK_VISIBLE_BINDING, uniform instanceOffset).
#pragma once

#include "gl_object.h"

#include "shadowkit/core/instance_hierarchy.h"
#include "shadowkit/scene/scene.h"

#include <span>
#include <vector>

namespace shadowkit::gl {

// One pass's instances: for each batch, a range of `indices` holding batch-local instance
// indices in increasing order (the order a full draw would use, so culling changes no
// pixel). `offset` is where `indices` starts in the frame's buffer.
struct PassList {
    std::vector<uint32_t> indices;
    std::vector<uint32_t> first, count; // per batch, into `indices`
    uint32_t offset = 0;
    size_t instances() const { return indices.size(); }
};

class Visibility {
public:
    explicit Visibility(const scene::Scene& scene);

    const core::Aabb& wsBounds() const { return m_hierarchy.bounds(); }

    // The instances the half-spaces may see (every instance when `cull` is false).
    void collect(std::span<const core::HalfSpace> volume, bool cull, PassList& out);
    // Assigns offsets and uploads every list of the frame into one buffer, bound at
    // SK_VISIBLE_BINDING.
    void upload(std::span<PassList* const> lists);

private:
    core::InstanceHierarchy m_hierarchy;    // items in global instance order (Scene order)
    std::vector<uint32_t> m_batchFirst;     // global index of each batch's first instance
    std::vector<uint32_t> m_scratch;        // query result, reused every pass
    std::vector<uint32_t> m_staging;        // the frame's concatenated lists
    Buffer m_buffer;
    size_t m_capacity = 0; // in indices
};

} // namespace shadowkit::gl
