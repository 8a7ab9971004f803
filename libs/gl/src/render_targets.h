// Off-screen render targets: the shadow map, the shaded colour image and the
// evaluation buffers, each with its read-back.
#pragma once

#include "gl_object.h"

#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/scene/image.h"

namespace shadowkit::gl {

core::Status checkComplete(const Framebuffer& fbo, const char* what);

// Depth texture array (one layer per shadow map) + framebuffer of the shadow pass,
// compare mode on for sampler2DArrayShadow.
struct ShadowTarget {
    Texture depth;
    Framebuffer framebuffer;
    int size = 0, layers = 0;

    ShadowTarget(int texels, int layerCount);
    // Allocates one, or says why the driver could not: out of memory (an environment error
    // naming map_size), or a framebuffer it cannot complete.
    static core::Result<ShadowTarget> create(int texels, int layerCount);
    void attachLayer(int layer) const;
    // Every layer at once (a layered framebuffer): a draw picks its layer (gl_Layer), a clear
    // clears them all.
    void attachAllLayers() const;
    // The layers side by side: near the light bright, cleared texels black, each layer's
    // used depth range stretched.
    scene::Image readAsGreys() const;
};

// A depth texture array's layers side by side as greys (ShadowTarget::readAsGreys).
scene::Image readDepthAsGreys(const Texture& depth, int width, int height, int layers);

struct ColorTarget {
    Texture color, depth;
    Framebuffer framebuffer;
    int width = 0, height = 0;

    ColorTarget(int w, int h);
    scene::Image read() const; // top row first
};

// The camera depth pre-pass of occlusion culling: depth for the queries, view depth (metres,
// 0 where nothing was drawn) for the receiver mask.
struct CameraDepthTarget {
    Texture viewDepth, depth;
    Framebuffer framebuffer;
    int width = 0, height = 0;

    CameraDepthTarget(int w, int h);
    void clear() const;
};

// Two single-channel float images for the eye-space blur, used in turn as source and target.
struct MaskPingPong {
    Texture images[2];
    Framebuffer framebuffers[2];
    int width = 0, height = 0;

    MaskPingPong(int w, int h);
    std::vector<float> read(int index) const; // top row first
};

// Multiple render targets written by eval.frag, read back as core::RasterBuffers.
struct EvalTarget {
    Texture shadowTerm, surfaceId, viewDepth, normal, texel, texelFromPixel, depth;
    Framebuffer framebuffer;
    int width = 0, height = 0;

    EvalTarget(int w, int h);
    void clearColors() const;                 // nothing drawn: lit, no surface; the depth is the pass's (CameraPasses)
    core::RasterBuffers read() const;         // top row first
    std::vector<float> readViewDepth() const; // metres, 0 where nothing was drawn
};

// The shaded eval pass's framebuffer: the eval target's six buffers at attachments 0–5, the
// colour target's picture at 6 and its depth, so one pass leaves both targets as the eval and
// main passes drawn apart would (CameraPasses::evalAndMainPass). Both of one size.
Framebuffer evalAndColorFramebuffer(const EvalTarget& eval, const ColorTarget& color);

} // namespace shadowkit::gl
