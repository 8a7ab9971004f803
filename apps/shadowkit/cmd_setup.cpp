// shadowkit setup: the shadow matrices as JSON, without any GL. The output is a
// contract for engines and tests (docs/commands.md, "shadowkit setup"): keep the names stable.
#include "commands.h"
#include "frame_config_options.h"
#include "local_light_options.h"
#include "options.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>

namespace shadowkit::app {
namespace {

using nlohmann::json;

struct SetupArgs {
    SceneOptions scene;
    ViewOptions view;
    TechniqueOptions technique;
    BoundsOptions bounds;
    LocalLightOptions lights;
};

json toJson(const core::Vec3& v) { return json::array({v.x, v.y, v.z}); }
json toJson(const core::Mat4& m) {
    json a = json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) a.push_back(m[c][r]); // column-major
    return a;
}

// docs/commands.md's names for each technique's parameters; flags as 0 / 1 numbers, as they
// always were in this contract.
json warpJson(const core::WarpParameters& warp) {
    auto flag = [](bool b) { return b ? 1.0 : 0.0; };
    return std::visit(
        [&](const auto& w) -> json {
            using W = std::decay_t<decltype(w)>;
            if constexpr (std::is_same_v<W, core::LispsmWarp>) {
                json j = {{"gamma_degrees", w.gammaDegrees}, {"uniform", flag(w.uniform)}};
                if (!w.viewParallel) j.update({{"n", w.n}, {"f", w.f}, {"d", w.d}});
                return j;
            } else if constexpr (std::is_same_v<W, core::PsmWarp>) {
                return {{"slide_back", w.slideBack},
                        {"near", w.ppNear},
                        {"far", w.ppFar},
                        {"light_w", w.lightW},
                        {"inverted", flag(w.inverted)}};
            } else if constexpr (std::is_same_v<W, core::TsmWarp>) {
                json j = {{"uniform", flag(w.uniform)}};
                if (!w.uniform)
                    j.update({{"lambda", w.lambda},
                              {"delta", w.delta},
                              {"eta", w.eta},
                              {"ends_ratio", w.endsRatio},
                              {"width_ratio", w.widthRatio}});
                return j;
            } else if constexpr (std::is_same_v<W, core::ClipmapLevel>) {
                // A clipmap level: texels of 2^exponent metres, its window's first page.
                return {{"exponent", w.exponent},
                        {"texel_metres", std::ldexp(1.0, w.exponent)},
                        {"first_page", {w.firstPageX, w.firstPageY}}};
            } else {
                return nullptr; // uniform techniques: no warp
            }
        },
        warp);
}

// A local light's set-up: its maps (one per cube face for a point light, `face` the OpenGL
// face index), each storing the distance to the light over its `light_distance` range.
json localLightJson(const LocalLight& light, const core::ShadowSetup& setup) {
    json j = std::visit(
        [](const auto& l) -> json {
            if constexpr (std::is_same_v<std::decay_t<decltype(l)>, core::SpotLight>)
                return {{"type", "spot"},
                        {"position", toJson(l.wsPosition)},
                        {"direction", toJson(glm::normalize(l.wsDirection))},
                        {"cone_degrees", l.coneDegrees},
                        {"range", l.range}};
            else
                return {{"type", "point"}, {"position", toJson(l.wsPosition)}, {"range", l.range}};
        },
        light);
    j["depth_layout"] = "light_distance";
    j["depth_clamp"] = setup.depthClamp;
    if (setup.lightType == core::LightType::Point) j["skipped_faces"] = setup.skippedFaces;
    json views = json::array();
    for (const core::ShadowView& v : setup.views) {
        json jv = {{"clip_from_world", toJson(v.clipFromWorld)},
                   {"light_from_world", toJson(v.lightFromWorld)},
                   {"clip_from_light", toJson(v.clipFromLight)},
                   {"light_distance", {v.lightDistance.x, v.lightDistance.y}}};
        if (v.face) jv["face"] = *v.face;
        views.push_back(jv);
    }
    j["views"] = views;
    j["fallbacks"] = setup.fallbacks;
    return j;
}

int runSetup(const SetupArgs& args) {
    if (auto s = args.technique.check(/*measuresFrames=*/false); !s) return fail(s.errorInfo());
    if (auto s = args.lights.check(); !s) return fail(s.errorInfo()); // before loading a scene
    if (auto s = args.view.check(); !s) return fail(s.errorInfo());
    auto bounded = args.bounds.resolve(args.scene, args.view);
    if (!bounded) return fail(bounded.errorInfo());
    const core::Aabb& bounds = bounded->wsBounds;
    const scene::ResolvedView* view = &bounded->view;

    auto inputs = args.technique.inputsFor(*view, bounds);
    if (!inputs) return fail(inputs.errorInfo());
    auto config = frameConfigOf(args.technique, RenderOptions{}, LocalLightOptions{});
    if (!config) return fail(config.errorInfo());
    auto setup = frame::firstSetup(*config, *inputs);
    if (!setup) return fail(withFlagName(setup.errorInfo()));

    const core::PerspectiveCamera& cam = view->camera;
    json out;
    out["technique"] = core::techniqueName(setup->technique);
    out["inputs"] = {
        {"camera",
         {{"eye", toJson(cam.wsEye)},
          {"direction", toJson(glm::normalize(cam.wsDirection))},
          {"up", toJson(cam.wsUp)},
          {"fov_y_degrees", cam.fovYDegrees},
          {"aspect", cam.aspect},
          {"near", cam.zNear},
          {"far", cam.zFar}}},
        {"light", {{"type", "directional"}, {"direction", toJson(view->light.wsDirection)}}},
        {"scene_bounds", {{"min", toJson(bounds.min)}, {"max", toJson(bounds.max)}}},
    };
    out["clip_depth"] = "zero_to_one"; // every set-up (core/conventions.h)
    out["depth_clamp"] = setup->depthClamp;
    out["depth_layout"] = setup->depthLayout == core::DepthLayout::Linear ? "linear" : "hyperbolic";
    out["eye_relative_origin"] = toJson(setup->wsEye);
    json views = json::array();
    for (const core::ShadowView& v : setup->views) {
        json jv = {
            {"clip_from_world", toJson(v.clipFromWorld)},
            {"light_from_world", toJson(v.lightFromWorld)},
            {"clip_from_light", toJson(v.clipFromLight)},
            {"linear_depth_from_world",
             {v.linearDepthFromWorld.x, v.linearDepthFromWorld.y, v.linearDepthFromWorld.z, v.linearDepthFromWorld.w}},
            // Camera-relative rendering: the same map for p − eye_relative_origin.
            {"clip_from_eye_relative", toJson(v.clipFromEyeRelative)},
            {"linear_depth_from_eye_relative",
             {v.linearDepthFromEyeRelative.x, v.linearDepthFromEyeRelative.y, v.linearDepthFromEyeRelative.z,
              v.linearDepthFromEyeRelative.w}}};
        if (v.split) jv["split"] = {v.split->x, v.split->y};
        if (json warp = warpJson(v.warp); !warp.is_null()) jv["warp"] = warp;
        views.push_back(jv);
    }
    out["views"] = views;
    json body = json::array();
    for (const core::Vec3& p : setup->body.vertices()) body.push_back(toJson(p));
    out["body"] = body;
    out["fallbacks"] = setup->fallbacks;
    // The view's spot and point lights (views.json), then --light's.
    auto lighting = args.lights.lightingFor(*view, bounds);
    if (!lighting) return fail(withFlagName(lighting.errorInfo()));
    if (!lighting->empty()) {
        json locals = json::array();
        for (size_t i = 0; i < lighting->points.size(); ++i)
            locals.push_back(localLightJson(lighting->points[i], lighting->pointSetups[i]));
        for (size_t i = 0; i < lighting->spots.size(); ++i)
            locals.push_back(localLightJson(lighting->spots[i], lighting->spotSetups[i]));
        out["local_lights"] = locals;
    }
    std::cout << out.dump(2) << "\n";
    return 0;
}

} // namespace

Command addSetupCommand(CLI::App& app) {
    auto args = std::make_shared<SetupArgs>();
    CLI::App* cmd = app.add_subcommand("setup", "Print a technique's shadow matrices as JSON (no GL needed)");
    args->scene.addTo(*cmd);
    args->view.addTo(*cmd);
    args->technique.addTo(*cmd);
    args->bounds.addTo(*cmd);
    args->lights.addTo(*cmd, false);
    return {cmd, [args] { return runSetup(*args); }};
}

} // namespace shadowkit::app
