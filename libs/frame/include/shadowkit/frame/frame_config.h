// What a frame is drawn with, typed: everything `render`'s options say except what each
// frame brings (camera, sun, image size, the view's lamps: scene::ResolvedView) and the scene
// box (the renderer's). One FrameConfig drives the command line, the viewer, Python and the
// `--state` files alike (they parse into it); frame::FrameDriver draws frames with it.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/error_driven.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/setup_hysteresis.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/render_settings.h"
#include "shadowkit/scene/views.h"

#include <optional>
#include <variant>
#include <vector>

namespace shadowkit::frame {

// Bias values the user set. What is left unset follows core::recommendedBias for the frame's
// technique, depth layout and filter — which --technique auto may change from frame to frame,
// so the bias is resolved per frame (resolve), never baked into the configuration.
struct BiasOverrides {
    std::optional<double> slope, constant, normalOffset; // texels, as core::BiasSettings
    std::optional<double> normalOffsetFootprint;         // texel footprints, as core::BiasSettings
    std::optional<core::CasterCull> cull;
    std::optional<bool> receiverPlane;
    std::optional<bool> offsetGuard;

    bool any() const {
        return slope || constant || normalOffset || normalOffsetFootprint || cull || receiverPlane || offsetGuard;
    }
    // The bias of a frame of `inputs` drawn with `filter`: nullopt with nothing overridden
    // (the renderer then takes the recommendation itself: gl::biasFor).
    std::optional<core::BiasSettings> resolve(const core::ShadowSetupInputs& inputs,
                                              const core::FilterSettings& filter) const;
    // The values set within core::BiasSettings' ranges (the recommendation always is).
    core::Status validate() const;
};

// A fog density override: >= 0 per metre and finite; the error names "fog".
core::Status validateFog(std::optional<double> fogDensity);

using LocalLight = std::variant<core::PointLight, core::SpotLight>;

struct FrameConfig {
    // The family, map size and parameters; its camera, light, scene box and (unless given)
    // visible depth are each frame's.
    core::ShadowSetupInputs technique;
    // Filter, blur, culling, levels of detail, local pass and bias, debug views. Its image
    // size, sun switch and bias are each frame's (the view's, and `bias`); its fog is the
    // view's unless `fogDensity` is set.
    gl::RenderSettings render;
    BiasOverrides bias;
    std::optional<double> fogDensity; // 1/m; unset: the view's (scene::ResolvedView::fogDensity)
    // Measure the visible view-depth range from the frame before its set-up (a camera
    // pre-pass): LiSPSM's n and the cascades' splits (ShadowSetupInputs::visibleDepth).
    bool visibleDepthFromFrame = false;
    // --technique auto: the family and parameters chosen each frame from the receivers in
    // view (core::AutoChooser), within this budget; `technique` then gives only the base
    // parameters the search starts from.
    std::optional<core::AutoOptions> automatic;
    // --stabilize for warped maps: texel lattices held across frames (core::SetupHysteresis).
    std::optional<core::HysteresisOptions> heldLattices;
    // Spot and point lights besides the view's own, and their maps' size.
    std::vector<LocalLight> lights;
    int localMapSize = 1024; // texels, each spot map and cube face

    // Checks what does not depend on a frame (options of the technique, the auto search, the
    // hysteresis, the render settings); errors name the field ("lispsm.weight", "blur.radius").
    core::Status check() const;
};

// The set-up a FrameDriver's first frame computes for `inputs` (a frame's technique inputs,
// camera and light and box filled in): held lattices' first fit, or a fresh set-up. No GL: what
// `shadowkit setup` prints, so its matrices are the ones `render` draws.
core::Result<core::ShadowSetup> firstSetup(const FrameConfig& config, const core::ShadowSetupInputs& inputs);

// The spot and point lights of a frame: the view's, then the configuration's, set up for the
// view's camera over the scene box. Errors name "lights" (too many, or a bad light).
core::Result<core::LocalLighting> localLightingFor(const FrameConfig& config, const scene::ResolvedView& view,
                                                   const core::Aabb& wsSceneBounds);

} // namespace shadowkit::frame
