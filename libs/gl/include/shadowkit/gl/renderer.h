// Renders a scene with a shadow set-up: the shadow-map depth pass, then the shaded
// camera view, into off-screen targets that can be read back as images.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <memory>

namespace shadowkit::gl {

enum class ShadowFilter {
    Hard,    // one depth comparison (what the evaluation's truth is compared with by default)
    Pcf2,    // hardware 2x2 percentage-closer filtering (GL_LINEAR compare; seed 000's filter)
    PcfGrid, // N x N comparisons one texel apart, averaged
    Poisson, // N comparisons on a Poisson disk, rotated per pixel
};

struct FilterSettings {
    ShadowFilter kind = ShadowFilter::Hard;
    int taps = 1;               // PcfGrid: N of N x N, [1, 9]; Poisson: samples, [1, 32]
    float radiusTexels = 1.5f;  // Poisson disk radius in texels, (0, 16]
};

// Eye-space, depth-dependent blur of the shadow mask (seed 000 §4.3).
struct BlurSettings {
    int iterations = 0;          // passes of a 3x3 kernel: 0 (off), 1, 2, 4, 8, 16 ... [0, 64]
    float radiusPixels = 1.5f;   // tap distance at view depth 0; (0, 16]
    // Radius at view depth z: radiusPixels / (1 + falloff · z): strong near the viewer,
    // weak far away (seed 000: "near the viewer, the shadow map is blurred more").
    float depthFalloff = 0.05f;  // 1/m, [0, 10]
    // Taps whose view depth differs from the centre's by more than this fraction are
    // ignored: the blur does not bleed across depth discontinuities.
    float depthThreshold = 0.02f; // (0, 1]
};

struct RenderSettings {
    int width = 1280, height = 720; // output pixels, [1, GL_MAX_TEXTURE_SIZE]
    int shadowMapSize = 2048;       // texels per side, [16, GL_MAX_TEXTURE_SIZE]
    core::BiasSettings bias;        // depth bias of the shadow pass and lookup
    FilterSettings filter;
    BlurSettings blur;
    float fogDensity = 0.002f;      // 1/m of exponential fog (seed 000 used fog); 0 = none
    bool cascadeColors = false;     // tint each cascade's range (seed 002, Figure 3-2)
};

struct PassStats {
    double gpuMilliseconds = 0.0; // GL timer query (GL_TIME_ELAPSED)
    size_t triangles = 0;         // submitted
    size_t drawCalls = 0;
};

struct FrameStats {
    PassStats shadow, main;
};

class Renderer {
public:
    // Uploads the scene and builds the programs; needs a current Context.
    static core::Result<std::unique_ptr<Renderer>> create(const scene::Scene& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Validates the settings against the driver's limits, then draws.
    core::Result<FrameStats> render(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                    const core::ShadowSetup& setup, const RenderSettings& settings);

    // The shadow pass, then instead of shading, the per-pixel buffers the evaluation
    // compares with ray-traced truth (shadow term — filtered and blurred as the settings
    // say —, surface identity, depth, normal, shadow texel coordinates and their screen
    // derivatives).
    core::Result<core::RasterBuffers> renderEvalBuffers(const core::PerspectiveCamera& camera,
                                                        const core::DirectionalLight& light,
                                                        const core::ShadowSetup& setup, const RenderSettings& settings);

    // The last rendered frame (top row first).
    scene::Image readColor() const;
    // The last shadow maps as greys, side by side: near the light is bright, empty texels black.
    scene::Image readShadowMap() const;

private:
    Renderer();
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace shadowkit::gl
