// Shadow caster culling by visible receivers (core/receiver_mask.h) on the GPU side: a
// compute pass over the camera's depth pre-pass marks every visible pixel in a small mask
// per shadow map; the masks come back to the CPU (a few KB), where the shadow passes' culling
// asks them which casters can shadow anything seen — or, for GPU-driven culling, stay on the
// GPU, dilated there, for its compute passes to ask.
#pragma once

#include "gl_object.h"
#include "render_targets.h"
#include "stopwatch.h"

#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/visibility/receiver_mask.h"

#include <memory>
#include <vector>

namespace shadowkit::gl {

inline constexpr int kReceiverMaskSize = 128; // texels per side of every mask

class ReceiverMasks {
public:
    static core::Result<std::unique_ptr<ReceiverMasks>> create();

    // One mask per shadow view of `setup`, from the view depths in `camera`'s pre-pass.
    // `dilationTexels`: how far from its own texel a receiver's lookup reads, in map texels
    // (filter footprint, normal offset).
    const std::vector<visibility::ReceiverMask>& build(const CameraDepthTarget& target,
                                                       const core::PerspectiveCamera& camera,
                                                       const core::ShadowSetup& setup, double dilationTexels);
    // The same masks left on the GPU for GPU-driven culling (gpu_culling.h), dilated there:
    // dilatedMasks() holds each map's kReceiverMaskSize² texels in receiver_mask.comp's
    // encoding, one map after another, then one flag per map (1: keep every caster). Nothing
    // is read back.
    void markOnGpu(const CameraDepthTarget& target, const core::PerspectiveCamera& camera,
                   const core::ShadowSetup& setup, double dilationTexels);
    const Buffer& dilatedMasks() const { return m_dilated; }
    // Time the last build() or markOnGpu() spent in GL: the compute passes and the read-back
    // (which waits for them). The rest is the masks' own CPU cost (decoding, dilation, pyramid).
    const CpuTimes& glTimes() const { return m_gl; }

private:
    ReceiverMasks() = default;
    // The marking pass into m_texels (not waited for).
    void mark(const CameraDepthTarget& target, const core::PerspectiveCamera& camera, const core::ShadowSetup& setup);
    // Mask texels a receiver's lookup reaches: the reach in map texels scaled to the mask, plus one
    // for the texel a receiver lands in at the edge.
    static int dilationFor(const core::ShadowSetup& setup, double dilationTexels);
    Program m_program, m_dilateProgram;
    Buffer m_uniforms, m_texels, m_scratch, m_dilated;
    size_t m_texelCapacity = 0;
    std::vector<uint32_t> m_readBack;
    std::vector<visibility::ReceiverMask> m_masks;
    CpuTimes m_gl;
};

} // namespace shadowkit::gl
