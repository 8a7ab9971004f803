// The camera's passes: the main pass (shaded colour, main.frag), the eval pass (the per-pixel
// buffers the evaluation compares with truth, eval.frag) and the eye-space blur of the shadow
// term (blur.frag), with the Frame block they all read. The shadow maps they look up are bound
// by their own passes (SunPass::bind, LocalShadowMaps::bind); the lists come from the culling
// planner (pass_lists.h).
#pragma once

#include "camera_programs.h"
#include "gl_object.h"
#include "gpu_scene.h"
#include "pass_samples.h"
#include "pass_timer.h"
#include "render_targets.h"
#include "visibility.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/render_settings.h"

#include <memory>
#include <optional>

namespace shadowkit::gl {

// What a camera pass draws with, in the renderer's (scene) space.
struct CameraView {
    const core::PerspectiveCamera& camera;
    const core::DirectionalLight& light;
    const core::ShadowSetup& setup; // as the lookups read it (SunPass::lookupSetup)
    const RenderSettings& settings;
    const core::BiasSettings& bias; // the frame's (biasFor)
};

class CameraPasses {
public:
    static core::Result<std::unique_ptr<CameraPasses>> create();
    // The programs of this frame's variant (with or without virtual maps' lookup).
    core::Status prepare(bool virtualMaps) { return m_programs.prepare(virtualMaps); }

    // The Frame block for `view` at kFrameBinding (the depth pre-pass reads it too), the raw-depth
    // sampler on every map's depth unit, the depth test on with writes, back faces culled. `readBlurredMask`: the
    // shadow term comes from the blurred mask (mainPass's `blurredMask`).
    void bindFrame(const CameraView& view, bool readBlurredMask) const;
    // Both passes below draw over the camera's depth pre-pass when the frame has one (`prepass`,
    // PassLists::cameraPrepass): its depth copied in, tested GL_LEQUAL with writes off, so each
    // pixel is shaded once, by the surface the pre-pass found nearest, instead of by every
    // fragment that was nearest when it was drawn. The pre-pass holds the depth of the same list
    // drawn with the same vertex shader and alpha test, so the image is the same.
    //
    // `casters` (PassLists::cameraCasters): the camera's one list, or what the GPU culled and the
    // CPU's list of the large clustered meshes beside it.
    //
    // The eval pass into its target (shadow term, surface id, depth, normal, texel coordinates and
    // their derivatives). The frame and the maps bound.
    core::Status evalPass(const GpuScene& scene, const CasterLists& casters, const CameraView& view,
                          const CameraDepthTarget* prepass);
    // The eval pass and the main pass in one, for a frame without the eye-space blur: the eval
    // target's buffers and the colour target's picture to the bit as evalPass() then mainPass()
    // would leave them, for one draw of the camera's view instead of two. Timed and counted as
    // the main pass.
    core::Result<DrawStats> evalAndMainPass(const GpuScene& scene, const CasterLists& casters, const CameraView& view,
                                            const CameraDepthTarget* prepass);
    core::RasterBuffers readEval() const { return m_eval->read(); }
    // Blurs the eval pass's shadow term in eye space; returns the ping-pong index holding it.
    int blurPass(const BlurSettings& blur);
    std::vector<float> readBlurred(int index) const { return m_mask->read(index); }
    // The shaded frame into the colour target, over the sky; `blurredMask` ≥ 0: the blur's
    // result to read the shadow term from. The frame and the maps bound. Timed (timer()) and its
    // samples counted (samples()).
    core::Result<DrawStats> mainPass(const GpuScene& scene, const CasterLists& casters, const CameraView& view,
                                     int blurredMask, const CameraDepthTarget* prepass);
    // The last main pass's GPU time and its work — the samples its depth test passed (written
    // into the image, once per covered pixel over a pre-pass) and the fragments it shaded — as
    // the queries the frame's figures read (gpu_figures.h).
    const PassTimer& timer() const { return m_mainTimer; }
    const PassSamples& samples() const { return m_mainSamples; }

    // Passes above that drew the camera's view (Renderer::cameraViewsDrawn).
    int viewsDrawn() const { return m_viewsDrawn; }

    // The colour target: nullptr before the first frame.
    const ColorTarget* color() const { return m_color ? &*m_color : nullptr; }

private:
    CameraPasses() = default;
    // The targets at this size, made (and checked) when the size changes.
    core::Status evalTarget(int width, int height);
    core::Status colorTarget(int width, int height);
    void clearToSky(const CameraView& view) const; // the colour target's picture
    // The camera's view drawn into the bound framebuffer over its started depth, timed and
    // counted as the main pass (mainPass, evalAndMainPass); the depth state and framebuffer reset.
    DrawStats drawPicture(const GpuScene& scene, const CasterLists& casters, const PassPrograms& programs,
                          const CameraView& view);

    CameraPrograms m_programs;
    Program m_blurProgram;
    Buffer m_frameUniforms, m_blurUniforms;
    VertexArray m_emptyVertexArray; // for the full-screen triangle
    Sampler m_rawDepth;             // the maps' stored depths (PCSS's blocker search)
    std::optional<ColorTarget> m_color;
    std::optional<EvalTarget> m_eval;
    std::optional<Framebuffer> m_evalAndColor; // both targets' textures (evalAndMainPass)
    std::optional<MaskPingPong> m_mask;
    PassTimer m_mainTimer;
    PassSamples m_mainSamples;
    int m_viewsDrawn = 0;
};

} // namespace shadowkit::gl
