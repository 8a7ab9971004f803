#include "local_light_options.h"

#include "options.h" // parseNumbers

#include <fmt/format.h>

#include <map>

namespace shadowkit::app {
namespace {

constexpr const char* kForms = "point:x,y,z[,range][,radius=R] or spot:x,y,z,dx,dy,dz,angle[,range][,radius=R]";

core::Result<LocalLight> parseLight(const std::string& spec) {
    const size_t colon = spec.find(':');
    const std::string kind = spec.substr(0, colon);
    std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
    auto bad = [&] { return core::makeError(fmt::format("--light: expected {}, got '{}'", kForms, spec)); };
    // The lamp's size, last and named: ",radius=R" (metres).
    std::vector<double> radius;
    if (const size_t named = rest.find(",radius="); named != std::string::npos) {
        if (!parseNumbers(rest.substr(named + 8), ',', radius) || radius.size() != 1) return bad();
        rest.resize(named);
    }
    std::vector<double> v;
    if (!parseNumbers(rest, ',', v)) return bad();
    core::Status valid = core::Ok{};
    LocalLight light;
    if (kind == "point" && (v.size() == 3 || v.size() == 4)) {
        core::PointLight p{.wsPosition = {v[0], v[1], v[2]}};
        if (v.size() == 4) p.range = v[3];
        if (!radius.empty()) p.radius = radius[0];
        valid = p.validate();
        light = p;
    } else if (kind == "spot" && (v.size() == 7 || v.size() == 8)) {
        core::SpotLight s{.wsPosition = {v[0], v[1], v[2]}, .wsDirection = {v[3], v[4], v[5]}, .coneDegrees = v[6]};
        if (v.size() == 8) s.range = v[7];
        if (!radius.empty()) s.radius = radius[0];
        valid = s.validate();
        light = s;
    } else {
        return bad();
    }
    if (!valid) return core::makeError(fmt::format("--light: {} (in '{}')", valid.error(), spec));
    return light;
}

} // namespace

void LocalLightOptions::addTo(CLI::App& cmd, bool withMaps) {
    cmd.add_option("--light", specs,
                   fmt::format("a local light with shadows, repeatable: {} (degrees, metres; range 30 m "
                               "unless given; radius: the lamp's size, soft shadows with --filter pcss)",
                               kForms));
    cmd.add_option("--local-map-size", mapSize, "texels per side of each spot map and cube face")
        ->check(CLI::Range(core::kMinMapSize, core::kMaxMapSize))
        ->capture_default_str();
    if (!withMaps) return;
    cmd.add_option("--local-pass", pass,
                   "how a point light's cube faces are drawn: layered (one pass: vertex-layer where "
                   "the driver has it, else geometry), vertex-layer, geometry, per-face (six passes)")
        ->transform(choice(Choices<gl::LocalPass>{{"layered", gl::LocalPass::Layered},
                                                  {"vertex-layer", gl::LocalPass::VertexLayer},
                                                  {"geometry", gl::LocalPass::Geometry},
                                                  {"per-face", gl::LocalPass::PerFace}}))
        ->default_str("layered");
    cmd.add_option("--local-bias-slope", bias.slopeTexels,
                   "local lights: slope-scaled bias in texels at the receiver's distance (times the tangent of "
                   "the light's angle to the normal, at most 3.2)")
        ->check(CLI::Range(0.0, 16.0))
        ->capture_default_str();
    cmd.add_option("--local-normal-offset", bias.normalOffsetTexels,
                   "local lights: normal offset in texels at the receiver's distance, where the light grazes "
                   "the receiver (within 17.5 degrees of its plane)")
        ->check(CLI::Range(0.0, 16.0))
        ->capture_default_str();
    cmd.add_option("--local-bias-constant", bias.constantMetres, "local lights: constant bias in metres")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
}

core::Result<core::LocalLighting> LocalLightOptions::lightingFor(const scene::ResolvedView& view,
                                                                 const core::Aabb& wsSceneBounds) const {
    auto extra = lights();
    if (!extra) return extra.errorInfo();
    frame::FrameConfig config; // what a frame with these lights sets up (frame::FrameDriver)
    config.lights.assign(extra->begin(), extra->end());
    config.localMapSize = mapSize;
    auto lighting = frame::localLightingFor(config, view, wsSceneBounds);
    if (!lighting) return withFlagName(lighting.errorInfo());
    return lighting;
}

core::Status LocalLightOptions::check() const {
    if (auto parsed = lights(); !parsed) return parsed.errorInfo();
    return core::Ok{};
}

core::Result<std::vector<LocalLight>> LocalLightOptions::lights() const {
    std::vector<LocalLight> out;
    for (const std::string& spec : specs) {
        auto light = parseLight(spec);
        if (!light) return light.errorInfo();
        out.push_back(*light);
    }
    return out;
}

} // namespace shadowkit::app
