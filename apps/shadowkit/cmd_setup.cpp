// shadowkit setup: the shadow matrices as JSON, without any GL. The output is a
// contract for engines and tests (README, "shadowkit setup"): keep the names stable.
#include "commands.h"
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
    std::string sceneBounds;
};

json toJson(const core::Vec3& v) { return json::array({v.x, v.y, v.z}); }
json toJson(const core::Mat4& m) {
    json a = json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) a.push_back(m[c][r]); // column-major
    return a;
}

core::Result<core::Aabb> parseBounds(const std::string& text) {
    const auto comma = [&](size_t n) {
        size_t pos = 0;
        for (size_t i = 0; i < n && pos != std::string::npos; ++i) pos = text.find(',', pos + (i ? 1 : 0));
        return pos;
    };
    const size_t third = comma(3);
    if (third == std::string::npos)
        return core::makeError(fmt::format("--scene-bounds: expected minx,miny,minz,maxx,maxy,maxz, got '{}'", text));
    auto lo = parseVec3("--scene-bounds", text.substr(0, third));
    auto hi = parseVec3("--scene-bounds", text.substr(third + 1));
    if (!lo || !hi) return core::makeError(fmt::format("--scene-bounds: expected minx,miny,minz,maxx,maxy,maxz, got '{}'", text));
    if (lo->x > hi->x || lo->y > hi->y || lo->z > hi->z)
        return core::makeError("--scene-bounds: min must not exceed max on any axis");
    return core::Aabb::fromMinMax(*lo, *hi);
}

int runSetup(const SetupArgs& args) {
    auto technique = args.technique.resolve();
    if (!technique) return fail(technique.error());
    // The view needs ground heights: the scene, or for bare bounds an empty scene whose
    // ground is the bottom of the bounds.
    scene::Scene sceneData;
    core::Aabb bounds;
    if (!args.sceneBounds.empty()) {
        auto b = parseBounds(args.sceneBounds);
        if (!b) return fail(b.error());
        bounds = *b;
    } else {
        auto loaded = args.scene.load(false);
        if (!loaded) return fail(loaded.error());
        sceneData = std::move(loaded).value();
        bounds = sceneData.wsBounds();
    }
    auto view = args.view.resolve(sceneData);
    if (!view) return fail(view.error());
    if (!args.sceneBounds.empty() && args.view.eye.empty()) // place the view's eye over the given ground
        view->camera.wsEye.y += bounds.min.y;

    auto inputs = args.technique.inputsFor(*view, bounds);
    if (!inputs) return fail(inputs.error());
    auto setup = core::computeShadowSetup(*inputs);
    if (!setup) return fail(setup.error());

    const core::PerspectiveCamera& cam = view->camera;
    json out;
    out["technique"] = core::techniqueName(setup->technique);
    out["inputs"] = {
        {"camera", {{"eye", toJson(cam.wsEye)}, {"direction", toJson(glm::normalize(cam.wsDirection))},
                    {"up", toJson(cam.wsUp)}, {"fov_y_degrees", cam.fovYDegrees}, {"aspect", cam.aspect},
                    {"near", cam.zNear}, {"far", cam.zFar}}},
        {"light", {{"type", "directional"}, {"direction", toJson(view->light.wsDirection)}}},
        {"scene_bounds", {{"min", toJson(bounds.min)}, {"max", toJson(bounds.max)}}},
    };
    out["clip_depth"] = setup->clipDepth == core::ClipDepth::ZeroToOne ? "zero_to_one" : "minus_one_to_one";
    out["depth_clamp"] = setup->depthClamp;
    json views = json::array();
    for (const core::ShadowView& v : setup->views) {
        json jv = {{"clip_from_world", toJson(v.clipFromWorld)},
                   {"light_from_world", toJson(v.lightFromWorld)},
                   {"clip_from_light", toJson(v.clipFromLight)}};
        if (v.split) jv["split"] = {v.split->x, v.split->y};
        if (!v.warp.empty()) {
            json warp = json::object();
            for (const auto& [name, value] : v.warp) warp[name] = value;
            jv["warp"] = warp;
        }
        views.push_back(jv);
    }
    out["views"] = views;
    json body = json::array();
    for (const core::Vec3& p : setup->body.vertices()) body.push_back(toJson(p));
    out["body"] = body;
    out["fallbacks"] = setup->fallbacks;
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
    cmd->add_option("--scene-bounds", args->sceneBounds, "scene box minx,miny,minz,maxx,maxy,maxz instead of a scene");
    return {cmd, [args] { return runSetup(*args); }};
}

} // namespace shadowkit::app
