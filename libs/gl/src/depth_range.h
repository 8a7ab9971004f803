// The view-depth range of what the camera sees, reduced on the GPU from the camera's depth
// pre-pass (depth_range.comp): two numbers come back instead of a frame of depths. For
// ShadowSetupInputs::visibleDepth — LiSPSM's n (Scherzer 2005 §4.4) and the cascades' splits.
// The reduction is issued after a pre-pass and read when asked: a running application asks
// at the start of the next frame, when the GPU has long finished, so nothing waits.
#pragma once

#include "gl_object.h"
#include "program.h"
#include "render_targets.h"

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"

#include <memory>
#include <optional>

namespace shadowkit::gl {

class DepthRangeReduction {
public:
    static core::Result<std::unique_ptr<DepthRangeReduction>> create();

    // Queues the reduction of `target`'s view depths.
    void reduce(const CameraDepthTarget& target);
    // [nearest, farthest] of the last reduce(); nullopt when nothing was drawn or nothing
    // was reduced. Reads 8 bytes back (waits for the GPU if it has not finished them).
    std::optional<core::Vec2> read();
    // No range for this frame (it made no pre-pass): read() answers nullopt.
    void forget() {
        m_pending = false;
        m_last.reset();
    }

private:
    DepthRangeReduction() = default;
    Program m_program;
    Buffer m_range;
    bool m_pending = false;
    std::optional<core::Vec2> m_last;
};

} // namespace shadowkit::gl
