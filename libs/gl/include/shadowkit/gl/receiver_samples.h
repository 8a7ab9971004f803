// Visible receivers for the sampling model (core/sampling_error.h), read back from the GPU:
// what an engine has anyway in its depth and normal buffers, here drawn at a low resolution.
#pragma once

#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/render_settings.h"

#include <cstddef>

namespace shadowkit::gl {

class Renderer;

struct ReceiverSampling {
    int width = 160; // pixels across of the read-back (at most the frame's); its height keeps the frame's aspect
    size_t maxSamples = 4096; // receivers kept, spread evenly over those facing the light
};

// `camera`'s view drawn at ReceiverSampling::width with `settings` (its culling and level of
// detail; filters, blur and receiver masks off) and its per-pixel buffers read back: depth and
// normals for the receivers, and the drawn view-depth range (Renderer::renderSurfaceBuffers: no
// shadow pass is drawn). `shadowSetup` only picks the eval pass's variant and is checked: the
// caller picks the cheapest it has (frame::FrameDriver's is a `standard` map of 64² texels).
core::Result<core::RasterBuffers> readReceivers(Renderer& renderer, const core::PerspectiveCamera& camera,
                                                const core::DirectionalLight& light,
                                                const core::ShadowSetup& shadowSetup, const RenderSettings& settings,
                                                const ReceiverSampling& sampling = {});

} // namespace shadowkit::gl
