// Standard and focused uniform shadow maps.
//
// Based on: Williams, "Casting curved shadows on curved surfaces" (1978) for the map
// itself; focusing as in Brabec et al. 2002 and Wimmer et al. 2004 §3.3 / Scherzer 2005 §4.1 (fit the
// light's orthographic frustum to the focus body B instead of the whole scene).
// The light frame's up vector is the view direction projected perpendicular to the
// light, so the map's y axis runs along view depth — the frame LiSPSM warps in (Wimmer et al. 2004
// §3.4). When the view is (anti-)parallel to the light that projection vanishes and the
// camera's up vector is used; see makeLightFrame.
#include "shadowkit/core/uniform_shadow_map.h"

#include "shadowkit/core/focus_body.h"
#include "shadowkit/core/light_frame.h"

namespace shadowkit::core {
namespace {

ShadowView orthographicView(const LightFrame& frame, std::span<const Vec3> wsPoints) {
    ShadowView view;
    view.lightFromWorld = frame.lightFromWorld;
    view.clipFromLight = fitOrthographic(frame.lightFromWorld, wsPoints);
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    return view;
}

ShadowView sceneBoxView(const ShadowSetupInputs& inputs) {
    const Aabb box = sceneBoxForFocus(inputs.wsSceneBounds);
    // North first: for a sun in the sky this makes map +Y point north, like a map.
    const LightFrame frame = makeLightFrame(inputs.light.wsDirection, box.center(), {Vec3(0, 0, -1)});
    const auto corners = box.corners();
    return orthographicView(frame, corners);
}

} // namespace

ShadowSetup computeStandardShadowMap(const ShadowSetupInputs& inputs) {
    ShadowSetup setup;
    setup.technique = Technique::Standard;
    setup.views.push_back(sceneBoxView(inputs));
    return setup;
}

ShadowSetup computeFocusedShadowMap(const ShadowSetupInputs& inputs) {
    return computeFocusedShadowMap(inputs, computeFocusBody(inputs.camera, inputs.light, inputs.wsSceneBounds));
}

ShadowSetup computeFocusedShadowMap(const ShadowSetupInputs& inputs, const ConvexBody& body) {
    ShadowSetup setup;
    setup.technique = Technique::Focused;
    setup.body = body;
    if (setup.body.isEmpty()) {
        setup.fallbacks.emplace_back(
            "empty focus body (the view frustum misses the scene box): fitted the whole scene box");
        setup.views.push_back(sceneBoxView(inputs));
        return setup;
    }
    const PerspectiveCamera& cam = inputs.camera;
    const LightFrame frame = makeLightFrame(inputs.light.wsDirection, cam.wsEye, {cam.wsDirection, cam.wsUp});
    if (frame.upCandidateUsed != 0)
        setup.fallbacks.emplace_back("view parallel to the light: light frame oriented by the camera's up vector");
    const ConvexBody::Points points = setup.body.vertices();
    setup.views.push_back(orthographicView(frame, points));
    return setup;
}

} // namespace shadowkit::core
