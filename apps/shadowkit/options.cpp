#include "options.h"

#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/scene_io.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <tuple>

namespace shadowkit::app {
namespace {

bool parseNumbers(const std::string& text, char separator, std::vector<double>& out) {
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, separator)) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) return false;
        out.push_back(v);
    }
    return !text.empty() && text.back() != separator;
}

} // namespace

core::Result<core::Vec3> parseVec3(const std::string& flag, const std::string& text) {
    std::vector<double> v;
    if (!parseNumbers(text, ',', v) || v.size() != 3)
        return core::makeError(fmt::format("{}: expected three comma-separated numbers x,y,z, got '{}'", flag, text));
    return core::Vec3(v[0], v[1], v[2]);
}

void SceneOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--scene", scene, "'forest' (built in) or a .gltf/.glb/.obj file")->capture_default_str();
    cmd.add_option("--seed", seed, "forest: random seed")->capture_default_str();
    cmd.add_option("--trees", trees, "forest: number of trees")->capture_default_str();
    cmd.add_option("--terrain-size", terrainSize, "forest: terrain side in metres")->capture_default_str();
    cmd.add_option("--terrain-resolution", terrainResolution, "forest: terrain quads per side")->capture_default_str();
}

core::Result<scene::Scene> SceneOptions::load(bool verbose) const {
    const auto start = std::chrono::steady_clock::now();
    core::Result<scene::Scene> result = core::makeError("");
    if (scene == "forest") {
        scene::ForestOptions o;
        o.seed = seed;
        o.trees = trees;
        o.terrainSize = terrainSize;
        o.terrainResolution = terrainResolution;
        if (core::Status s = scene::validate(o); !s) return core::makeError(s.error());
        result = scene::makeForest(o);
    } else {
        result = scene::loadScene(scene);
        if (!result) return result;
    }
    if (verbose) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print(stderr, "scene {}: {} instances, {:.2f} M triangles, {} batches ({:.2f} s)\n", scene,
                   result->instanceCount(), static_cast<double>(result->triangleCount()) * 1e-6, result->batches.size(), seconds);
    }
    if (result->batches.empty()) return core::makeError(fmt::format("scene {}: is empty (no triangles)", scene));
    return result;
}

void ViewOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--view", view, "standard view from data/views.json (paper, perpendicular, into-sun, sun-behind, noon, aerial)")
        ->capture_default_str();
    cmd.add_option("--eye", eye, "camera position x,y,z in world metres (overrides the view's)");
    cmd.add_option("--dir", dir, "viewing direction x,y,z");
    cmd.add_option("--up", up, "camera up vector x,y,z");
    cmd.add_option("--fov", fov, "vertical field of view in degrees");
    cmd.add_option("--near", zNear, "near plane distance in metres");
    cmd.add_option("--far", zFar, "far plane distance in metres");
    cmd.add_option("--size", size, "image size WxH in pixels (default: the view's)");
    cmd.add_option("--sun", sun, "direction the sunlight travels x,y,z (sun -> scene)");
    cmd.add_option("--sun-elevation", sunElevation, "sun elevation in degrees above the horizon");
    cmd.add_option("--sun-azimuth", sunAzimuth, "sun compass azimuth in degrees (0 = -Z, 90 = +X)");
}

core::Result<scene::ResolvedView> ViewOptions::resolve(const scene::Scene& sceneData) const {
    auto views = scene::loadViews(scene::dataDirectory() / "views.json");
    if (!views) return core::makeError(views.error());
    auto spec = scene::findView(*views, view);
    if (!spec) return core::makeError("--view: " + spec.error());
    scene::ResolvedView out = scene::resolveView(*spec, sceneData);

    if (!size.empty()) {
        std::vector<double> wh;
        if (!parseNumbers(size, 'x', wh) || wh.size() != 2 || wh[0] < 1 || wh[1] < 1 || wh[0] > 16384 || wh[1] > 16384 ||
            wh[0] != std::floor(wh[0]) || wh[1] != std::floor(wh[1]))
            return core::makeError(fmt::format("--size: expected WxH with whole numbers in [1, 16384], got '{}'", size));
        out.width = static_cast<int>(wh[0]);
        out.height = static_cast<int>(wh[1]);
    }
    core::PerspectiveCamera& cam = out.camera;
    cam.aspect = double(out.width) / double(out.height);
    const std::pair<const char*, const std::string*> vectors[] = {{"--eye", &eye}, {"--dir", &dir}, {"--up", &up}};
    core::Vec3* targets[] = {&cam.wsEye, &cam.wsDirection, &cam.wsUp};
    for (size_t i = 0; i < 3; ++i) {
        if (vectors[i].second->empty()) continue;
        auto v = parseVec3(vectors[i].first, *vectors[i].second);
        if (!v) return core::makeError(v.error());
        *targets[i] = *v;
    }
    if (fov) cam.fovYDegrees = *fov;
    if (zNear) cam.zNear = *zNear;
    if (zFar) cam.zFar = *zFar;
    if (core::Status s = cam.validate(); !s) return core::makeError(s.error());

    if (!sun.empty()) {
        if (sunElevation || sunAzimuth) return core::makeError("--sun: give either --sun or --sun-elevation/--sun-azimuth, not both");
        auto v = parseVec3("--sun", sun);
        if (!v) return core::makeError(v.error());
        auto light = core::DirectionalLight::fromDirection(*v);
        if (!light) return core::makeError("--sun: " + light.error());
        out.light = *light;
    } else if (sunElevation || sunAzimuth) {
        // Keep whichever angle was not given from the view's sun.
        const core::Vec3 towards = out.light.wsTowardsLight();
        const double elevation = sunElevation.value_or(glm::degrees(std::asin(std::clamp(towards.y, -1.0, 1.0))));
        const double azimuth = sunAzimuth.value_or(core::azimuthDegreesOf(towards));
        auto light = core::DirectionalLight::fromSunAngles(elevation, azimuth);
        if (!light) return core::makeError("--sun-elevation/--sun-azimuth: " + light.error());
        out.light = *light;
    }
    return out;
}

void BoundsOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--scene-bounds", sceneBounds, "scene box minx,miny,minz,maxx,maxy,maxz instead of a scene");
}

core::Result<BoundedView> BoundsOptions::resolve(const SceneOptions& scene, const ViewOptions& view) const {
    BoundedView out;
    scene::Scene sceneData; // empty with bare bounds: its ground is then y = 0, moved below
    if (!sceneBounds.empty()) {
        std::vector<double> v;
        if (!parseNumbers(sceneBounds, ',', v) || v.size() != 6)
            return core::makeError(fmt::format("--scene-bounds: expected minx,miny,minz,maxx,maxy,maxz, got '{}'", sceneBounds));
        if (v[0] > v[3] || v[1] > v[4] || v[2] > v[5]) return core::makeError("--scene-bounds: min must not exceed max on any axis");
        out.wsBounds = core::Aabb::fromMinMax({v[0], v[1], v[2]}, {v[3], v[4], v[5]});
    } else {
        auto loaded = scene.load(false);
        if (!loaded) return core::makeError(loaded.error());
        sceneData = std::move(loaded).value();
        out.wsBounds = sceneData.wsBounds();
    }
    auto resolved = view.resolve(sceneData);
    if (!resolved) return core::makeError(resolved.error());
    out.view = *resolved;
    if (!sceneBounds.empty() && view.eye.empty()) out.view.camera.wsEye.y += out.wsBounds.min.y;
    return out;
}

void RenderOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--bias-slope", biasSlope, "slope-scaled depth bias (glPolygonOffset factor; default: per technique)");
    cmd.add_option("--bias-constant", biasConstant, "constant depth bias (glPolygonOffset units; default: per technique)");
    cmd.add_option("--cull", cull, "caster faces left out of the map: back, front (back-side rendering), none, auto")
        ->capture_default_str();
    cmd.add_option("--normal-offset", normalOffset, "receiver offset along its normal, in texels' world size");
    cmd.add_option("--receiver-plane-bias", receiverPlaneBias, "on, off or auto: reference depth on the receiver's plane")
        ->capture_default_str();
    cmd.add_option("--filter", filter, "hard, pcf2 (hardware 2x2), pcf:N (N x N), poisson:N (N rotated taps)")
        ->capture_default_str();
    cmd.add_option("--blur-iterations", blurIterations, "eye-space blur of the shadow mask: 0, 1, 2, 4, 8, 16 ...")
        ->capture_default_str();
    cmd.add_option("--blur-radius", blurRadius, "blur tap distance in pixels at the viewer")->capture_default_str();
    cmd.add_option("--blur-depth-falloff", blurDepthFalloff, "blur radius / (1 + falloff * depth): 0 = uniform blur")
        ->capture_default_str();
    cmd.add_flag("--cascade-colors", cascadeColors, "tint each cascade's depth range (seed 002 Figure 3-2)");
}

namespace {

// "pcf:5" -> (PcfGrid, 5); "hard" -> (Hard, 1).
core::Result<gl::FilterSettings> parseFilter(const std::string& text) {
    gl::FilterSettings f;
    const size_t colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    int taps = 0;
    if (colon != std::string::npos) {
        char* end = nullptr;
        const long v = std::strtol(text.c_str() + colon + 1, &end, 10);
        if (*end != '\0' || end == text.c_str() + colon + 1) taps = -1;
        else taps = static_cast<int>(v);
    }
    if (kind == "hard" && colon == std::string::npos) return f;
    if (kind == "pcf2" && colon == std::string::npos) return gl::FilterSettings{gl::ShadowFilter::Pcf2, 1};
    if (kind == "pcf" && taps >= 1 && taps <= 9) return gl::FilterSettings{gl::ShadowFilter::PcfGrid, taps};
    if (kind == "poisson" && taps >= 1 && taps <= 32) return gl::FilterSettings{gl::ShadowFilter::Poisson, taps};
    return core::makeError(fmt::format("--filter: expected hard, pcf2, pcf:N (N 1-9) or poisson:N (N 1-32), got '{}'", text));
}

} // namespace

core::Status RenderOptions::check() const {
    if (auto f = parseFilter(filter); !f) return core::makeError(f.error());
    if (cull != "auto" && cull != "back" && cull != "front" && cull != "none")
        return core::makeError(fmt::format("--cull: expected back, front, none or auto, got '{}'", cull));
    if (receiverPlaneBias != "auto" && receiverPlaneBias != "on" && receiverPlaneBias != "off")
        return core::makeError(fmt::format("--receiver-plane-bias: expected on, off or auto, got '{}'", receiverPlaneBias));
    if (blurIterations < 0 || blurIterations > 64) return core::makeError("--blur-iterations: must be in [0, 64]");
    if (!(blurRadius > 0.0f && blurRadius <= 16.0f)) return core::makeError("--blur-radius: must be in (0, 16] pixels");
    if (!(blurDepthFalloff >= 0.0f && blurDepthFalloff <= 10.0f)) return core::makeError("--blur-depth-falloff: must be in [0, 10]");
    // Each flag checked on its own by core::validate, so the message names the flag.
    const std::tuple<const char*, const std::optional<double>&, double core::BiasSettings::*> fields[] = {
        {"--bias-slope", biasSlope, &core::BiasSettings::slope},
        {"--bias-constant", biasConstant, &core::BiasSettings::constant},
        {"--normal-offset", normalOffset, &core::BiasSettings::normalOffset}};
    for (const auto& [flag, value, member] : fields) {
        if (!value) continue;
        core::BiasSettings b;
        b.*member = *value;
        if (auto s = core::validate(b); !s) return core::makeError(std::string(flag) + ": " + s.error());
    }
    return core::Ok{};
}

core::Result<gl::RenderSettings> RenderOptions::settingsFor(const scene::ResolvedView& view, int mapSize,
                                                            const core::ShadowSetup& setup) const {
    if (auto s = check(); !s) return core::makeError(s.error());
    gl::RenderSettings settings;
    settings.width = view.width;
    settings.height = view.height;
    settings.shadowMapSize = mapSize; // checked by TechniqueOptions and against the driver's limit
    core::BiasSettings& b = settings.bias;
    b = core::recommendedBias(setup.technique, setup.depthLayout);
    if (biasSlope) b.slope = *biasSlope;
    if (biasConstant) b.constant = *biasConstant;
    if (normalOffset) b.normalOffset = *normalOffset;
    if (cull != "auto") b.cull = cull == "back" ? core::CasterCull::Back : cull == "front" ? core::CasterCull::Front : core::CasterCull::None;
    settings.filter = parseFilter(filter).value();
    // Kernels wider than the hardware's 2x2 compare taps texels away from the receiver: on a
    // surface sloped in light space they self-shadow unless the reference depth follows the
    // receiver's plane (measured: 0.8 on lit ground with 5x5 taps; see the gl tests).
    const bool wideKernel = settings.filter.kind == gl::ShadowFilter::PcfGrid || settings.filter.kind == gl::ShadowFilter::Poisson;
    b.receiverPlane = receiverPlaneBias == "auto" ? (b.receiverPlane || wideKernel) : receiverPlaneBias == "on";
    settings.blur.iterations = blurIterations;
    settings.blur.radiusPixels = blurRadius;
    settings.blur.depthFalloff = blurDepthFalloff;
    settings.cascadeColors = cascadeColors;
    return settings;
}

void TechniqueOptions::addTo(CLI::App& cmd) {
    technique = std::string(core::techniqueName(core::defaultTechnique()));
    cmd.add_option("--technique", technique, "shadow technique: " + core::techniqueNameList())->capture_default_str();
    cmd.add_option("--lispsm-formula", lispsmFormula, "LiSPSM n: 'paper' (seed 001 §4.4) or 'scherzer' (seed 000 eq. 1)")
        ->capture_default_str();
    cmd.add_option("--lispsm-direction", lispsmDirection, "LiSPSM warp axis: 'cross' (seed 000 eq. 3) or 'middle' (B's middle vector)")
        ->capture_default_str();
    cmd.add_option("--lispsm-weight", lispsmWeight, "LiSPSM: multiplies n (> 1 warps less)")->capture_default_str();
    cmd.add_option("--lispsm-n", lispsmN, "LiSPSM: fixed n in metres instead of the formula");
    cmd.add_option("--visible-depth", visibleDepth, "near,far view depth actually visible (LiSPSM n only, seed 000 §4.4)");
    cmd.add_option("--tsm-focus", tsmFocus, "TSM: focus point as a fraction of the view depth range (80 % rule)")
        ->capture_default_str();
    cmd.add_option("--depth-layout", depthLayout, "shadow depth: 'hyperbolic', 'linear' or 'auto' (linear for TSM)")
        ->capture_default_str();
    cmd.add_option("--map-size", mapSize, "shadow map texels per side (per cascade for csm)")->capture_default_str();
    cmd.add_option("--cascades", cascades, "csm: number of splits, 1-8")->capture_default_str();
    cmd.add_option("--lambda", lambda, "csm: split scheme, 0 uniform ... 1 logarithmic (seed 002)")->capture_default_str();
    cmd.add_option("--splits", splits, "csm: explicit split distances near,...,far (count + 1 values)");
    cmd.add_option("--cascade-warp", cascadeWarp, "csm: per-split warp, 'none' or 'lispsm'")->capture_default_str();
    cmd.add_flag("--stabilize", stabilize, "csm: rotation-invariant, texel-snapped splits (no swimming)");
    cmd.add_option("--blend-band", blendBand, "csm: fraction of each split blended into the next, 0-0.5")->capture_default_str();
}

core::Result<core::Technique> TechniqueOptions::resolve() const {
    const auto t = core::parseTechnique(technique);
    if (!t) return core::makeError(fmt::format("--technique: unknown technique '{}' (known: {})", technique, core::techniqueNameList()));
    if (lispsmFormula != "paper" && lispsmFormula != "scherzer")
        return core::makeError(fmt::format("--lispsm-formula: expected 'paper' or 'scherzer', got '{}'", lispsmFormula));
    if (lispsmDirection != "cross" && lispsmDirection != "middle")
        return core::makeError(fmt::format("--lispsm-direction: expected 'cross' or 'middle', got '{}'", lispsmDirection));
    if (!(lispsmWeight > 0.0 && std::isfinite(lispsmWeight))) return core::makeError("--lispsm-weight: must be a number > 0");
    if (!(tsmFocus > 0.0 && tsmFocus < 1.0)) return core::makeError("--tsm-focus: must be a fraction in (0, 1)");
    if (depthLayout != "auto" && depthLayout != "hyperbolic" && depthLayout != "linear")
        return core::makeError(fmt::format("--depth-layout: expected 'auto', 'hyperbolic' or 'linear', got '{}'", depthLayout));
    if (lispsmN && !(*lispsmN > 0.0 && std::isfinite(*lispsmN))) return core::makeError("--lispsm-n: must be a number of metres > 0");
    if (!visibleDepth.empty()) {
        std::vector<double> v;
        if (!parseNumbers(visibleDepth, ',', v) || v.size() != 2 || !(v[0] >= 0.0 && v[1] > v[0]))
            return core::makeError(fmt::format("--visible-depth: expected near,far with 0 <= near < far, got '{}'", visibleDepth));
    }
    if (mapSize < 16 || mapSize > 16384) return core::makeError("--map-size: must be in [16, 16384] texels");
    if (cascades < 1 || cascades > 8) return core::makeError("--cascades: must be in [1, 8]");
    if (!(lambda >= 0.0 && lambda <= 1.0)) return core::makeError("--lambda: must be in [0, 1]");
    if (!(blendBand >= 0.0 && blendBand <= 0.5)) return core::makeError("--blend-band: must be in [0, 0.5]");
    if (cascadeWarp != "none" && cascadeWarp != "lispsm")
        return core::makeError(fmt::format("--cascade-warp: expected 'none' or 'lispsm', got '{}'", cascadeWarp));
    std::vector<double> v;
    if (!splits.empty() && !parseNumbers(splits, ',', v))
        return core::makeError(fmt::format("--splits: expected comma-separated distances, got '{}'", splits));
    return *t;
}

core::Result<core::ShadowSetupInputs> TechniqueOptions::inputsFor(const scene::ResolvedView& view, const core::Aabb& wsBounds) const {
    auto t = resolve();
    if (!t) return core::makeError(t.error());
    core::ShadowSetupInputs in{.camera = view.camera, .light = view.light, .wsSceneBounds = wsBounds, .technique = *t};
    in.lispsm.formula = lispsmFormula == "paper" ? core::LispsmFormula::Paper : core::LispsmFormula::Scherzer;
    in.lispsm.direction = lispsmDirection == "middle" ? core::LispsmDirection::MiddleVector : core::LispsmDirection::CrossProduct;
    in.lispsm.weight = lispsmWeight;
    in.lispsm.nOverride = lispsmN;
    in.tsm.focusFraction = tsmFocus;
    if (depthLayout != "auto")
        in.depthLayout = depthLayout == "linear" ? core::DepthLayout::Linear : core::DepthLayout::Hyperbolic;
    core::CascadeOptions& c = in.cascades;
    c.count = cascades;
    c.lambda = lambda;
    c.warp = cascadeWarp == "lispsm" ? core::CascadeWarp::Lispsm : core::CascadeWarp::None;
    c.stabilize = stabilize;
    c.blendBand = blendBand;
    c.mapSize = mapSize;
    if (!splits.empty()) parseNumbers(splits, ',', c.splits); // validated by resolve()
    if (!visibleDepth.empty()) {
        std::vector<double> v;
        parseNumbers(visibleDepth, ',', v); // validated by resolve()
        in.lispsm.visibleDepth = core::Vec2(v[0], v[1]);
    }
    return in;
}

} // namespace shadowkit::app
