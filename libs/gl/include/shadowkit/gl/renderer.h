// Renders a scene with a shadow set-up: the shadow-map depth pass, then the shaded
// camera view, into off-screen targets that can be read back as images.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <memory>

namespace shadowkit::gl {

struct RenderSettings {
    int width = 1280, height = 720; // output pixels, [1, GL_MAX_TEXTURE_SIZE]
    int shadowMapSize = 2048;       // texels per side, [16, GL_MAX_TEXTURE_SIZE]
    // Depth bias of the shadow pass through glPolygonOffset(slope, constant). Seed 000
    // reports 2.0 / 4.0 as its working values; default here the same.
    float biasSlope = 2.0f;         // factor × max depth slope, [0, 100]
    float biasConstant = 4.0f;      // units of minimum resolvable depth, [0, 1e6]
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
    // compares with ray-traced truth (shadow term, surface identity, depth, normal,
    // shadow texel coordinates and their screen derivatives).
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
