// The scene and view option groups (options.h): which scene a command draws — a file, or the
// built-in forest and its flags, refused together — where its camera and sun stand, and the
// bare bounds `setup` and `analyze` take instead of a scene.
#include "options.h"

#include "common.h"

#include "shadowkit/gl/render_settings.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/scene_io.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string_view>
#include <tuple>
#include <vector>

namespace shadowkit::app {

void SceneOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--scene", scene, "'forest' (built in) or a .gltf/.glb/.obj file")->capture_default_str();
    cmd.add_option("--forest", forest,
                   "forest: its trees, simple (the standard scene's opaque blobs) or leafy (branches and "
                   "alpha-tested leaf cards, 5,000-20,000 triangles a tree)")
        ->check(CLI::IsMember({"simple", "leafy"}))
        ->capture_default_str();
    cmd.add_option("--seed", seed, "forest: random seed")->capture_default_str();
    cmd.add_option("--trees", trees, "forest: number of trees")->capture_default_str();
    cmd.add_option("--terrain-size", terrainSize, "forest: terrain side in metres")->capture_default_str();
    cmd.add_option("--terrain-resolution", terrainResolution, "forest: terrain quads per side")->capture_default_str();
    cmd.add_option("--movers", movers, "forest: moving objects on circles round the clearing, [0, 1000]")
        ->capture_default_str();
    cmd.add_flag("--impostors", impostors,
                 "forest, leafy: the shadow passes cast each far tree from an octahedral impostor (one card facing the "
                 "light) in place of its coarsest billboard cloud");
    // Options bind to this object's fields (CLI11 holds references), so the note of which was
    // given is this object's too.
    for (const char* flag :
         {"--forest", "--seed", "--trees", "--terrain-size", "--terrain-resolution", "--movers", "--impostors"})
        cmd.get_option(flag)->each([this, flag](const std::string&) {
            if (forestFlag.empty()) forestFlag = flag;
        });
    cmd.add_option("--scene-up", sceneUp,
                   "a scene file's up axis: y (glTF's, and shadowkit's) or z (CAD, GIS and photogrammetry exports "
                   "often write z up)")
        ->check(CLI::IsMember({"y", "z"}))
        ->capture_default_str();
    cmd.add_flag("--keep-sky", keepSky,
                 "keep a mesh that encloses a scene file's model and hides the whole sky from it (a sky sphere or "
                 "box), which is left out otherwise: every sun is then behind it");
    cmd.add_option(
        "--world-offset", worldOffset,
        "x,y,z metres: stand the scene and its views this far from the world's origin (large-world precision)");
}

core::Result<core::Vec3> SceneOptions::offset() const {
    if (worldOffset.empty()) return core::Vec3(0.0);
    auto v = parseVec3("--world-offset", worldOffset);
    if (!v) return v;
    // Beyond 1e12 m even double's step (0.1 mm) is coarser than a millimetre frustum.
    if (glm::length(*v) > 1e12)
        return core::makeError(fmt::format("--world-offset: at most 1e12 m from the origin, got '{}'", worldOffset));
    return v;
}

namespace {

scene::ForestOptions forestOptionsOf(const SceneOptions& options) {
    scene::ForestOptions o;
    o.kind = options.forest == "leafy" ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
    o.seed = options.seed;
    o.trees = options.trees;
    o.terrainSize = options.terrainSize;
    o.terrainResolution = options.terrainResolution;
    o.movers = options.movers;
    o.impostors = options.impostors;
    return o;
}

// A forest flag given with a scene file would be dropped in silence (no trees, no movers), and
// so would a file's up axis or its sky given with the forest.
core::Status forestFlagsUnused(const SceneOptions& options) {
    if (options.scene == "forest" && options.sceneUp != "y")
        return core::makeError("--scene-up: a scene file's, and the built-in forest is y-up");
    if (options.scene == "forest" && options.keepSky)
        return core::makeError("--keep-sky: a scene file's, and the built-in forest has no sky mesh");
    if (options.scene == "forest" || options.forestFlag.empty()) return core::Ok{};
    return core::makeError(
        fmt::format("{}: the built-in forest's, and --scene draws {} instead", options.forestFlag, options.scene));
}

// --size: whole numbers in [1, 16384] each way.
core::Result<std::pair<int, int>> parseSize(const std::string& size) {
    std::vector<double> wh;
    if (!parseNumbers(size, 'x', wh) || wh.size() != 2 || wh[0] < 1 || wh[1] < 1 || wh[0] > 16384 || wh[1] > 16384 ||
        wh[0] != std::floor(wh[0]) || wh[1] != std::floor(wh[1]))
        return core::makeError(fmt::format("--size: expected WxH with whole numbers in [1, 16384], got '{}'", size));
    return std::pair{static_cast<int>(wh[0]), static_cast<int>(wh[1])};
}

} // namespace

core::Status SceneOptions::check() const {
    if (auto origin = offset(); !origin) return origin.errorInfo();
    if (auto s = forestFlagsUnused(*this); !s) return s;
    if (scene == "forest") return scene::validate(forestOptionsOf(*this));
    std::error_code ec;
    const auto status = std::filesystem::status(scene, ec);
    if (!std::filesystem::exists(status))
        return core::makeError(fmt::format("--scene: {}: scene file does not exist", scene));
    if (!std::filesystem::is_regular_file(status))
        return core::makeError(fmt::format("--scene: {}: a directory, device or pipe, not a scene file", scene));
    return core::Ok{};
}

core::Result<scene::Scene> SceneOptions::load(bool verbose, double poseSeconds) const {
    auto origin = offset();
    if (!origin) return origin.errorInfo();
    const auto start = std::chrono::steady_clock::now();
    core::Result<scene::Scene> result = core::makeError("");
    if (auto s = forestFlagsUnused(*this); !s) return s.errorInfo();
    if (scene == "forest") {
        const scene::ForestOptions o = forestOptionsOf(*this);
        if (core::Status s = scene::validate(o); !s) return s.errorInfo();
        result = scene::makeForest(o);
    } else {
        result = scene::loadScene(scene, {.up = sceneUp == "z" ? scene::UpAxis::Z : scene::UpAxis::Y,
                                          .mergeSmallMeshes = mergeSmallMeshes,
                                          .poseSeconds = poseSeconds,
                                          .keepSky = keepSky});
        if (!result) return result;
        for (const std::string& warning : result->warnings) warn(warning);
    }
    if (verbose) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const std::string name = scene == "forest" && forest == "leafy" ? "forest (leafy)" : scene;
        // A file far from its origin stands there, its floats relative to it (near_origin.cpp).
        const core::Vec3& at = result->wsOrigin;
        const std::string standing =
            at == core::Vec3(0.0) ? "" : fmt::format(", standing at {:.0f},{:.0f},{:.0f} m", at.x, at.y, at.z);
        // Its own camera and lights, said where they are, so that a user finds `--view file`.
        const size_t cameras = result->cameras.size(), lights = result->lights.size();
        const std::string own = cameras + lights == 0
                                    ? ""
                                    : fmt::format(", {} camera{} and {} light{} of its own (--view file, --sun file)",
                                                  cameras, cameras == 1 ? "" : "s", lights, lights == 1 ? "" : "s");
        // Its animations likewise: they play at --time and along --path (t = 0 otherwise), the
        // instances they move and the meshes they deform (skins, morph weights).
        const size_t moving = scene == "forest" ? 0 : result->tracks.size();
        const size_t deformed = result->deformations.size();
        const std::string animated =
            (moving == 0 ? "" : fmt::format(", {} moved by its animations (--time, --path)", moving)) +
            (deformed == 0 ? ""
                           : fmt::format(", {} mesh{} deformed by its animations (--time, --path)", deformed,
                                         deformed == 1 ? "" : "es"));
        fmt::print(stderr, "scene {}: {} instances, {:.2f} M triangles, {} batches{}{}{} ({:.2f} s)\n", name,
                   result->instanceCount(), static_cast<double>(result->triangleCount()) * 1e-6, result->batches.size(),
                   standing, own, animated, seconds);
    }
    if (result->batches.empty()) return core::makeError(fmt::format("scene {}: is empty (no triangles)", scene));
    result->wsOrigin += *origin; // a file far out already stands at its own origin (near_origin.cpp)
    return result;
}

void ViewOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--view", view,
                   "standard view from data/views.json (paper, perpendicular, into-sun, sun-behind, noon, aerial), "
                   "or file[:CAMERA]: a loaded glTF's own camera, lit by its own lights")
        ->capture_default_str();
    cmd.add_option("--eye", eye, "camera position x,y,z in world metres (overrides the view's)");
    cmd.add_option("--dir", dir, "viewing direction x,y,z");
    cmd.add_option("--up", up, "camera up vector x,y,z");
    cmd.add_option("--fov", fov, "vertical field of view in degrees");
    cmd.add_option("--near", zNear, "near plane distance in metres");
    cmd.add_option("--far", zFar, "far plane distance in metres");
    cmd.add_option("--size", size, "image size WxH in pixels (default: the view's)");
    cmd.add_option("--sun", sun,
                   "direction the sunlight travels x,y,z (sun -> scene), off (night: local lights only), on, or "
                   "file (a loaded glTF's own directional light)");
    cmd.add_option("--sun-elevation", sunElevation, "sun elevation in degrees above the horizon");
    cmd.add_option("--sun-azimuth", sunAzimuth, "sun compass azimuth in degrees (0 = -Z, 90 = +X)");
}

std::optional<std::string> fileCameraOf(const std::string& view) {
    if (view == "file") return std::string();
    if (view.starts_with("file:")) return view.substr(5);
    return std::nullopt;
}

core::Result<std::vector<std::string>> viewNamesOf(const std::string& list) {
    auto all = scene::loadViews(dataDirectory() / "views.json");
    if (!all) return all.errorInfo();
    std::vector<std::string> names;
    if (list == "all" || list == "local") {
        for (const scene::ViewSpec& v : *all)
            if (v.lights.empty() == (list == "all")) names.push_back(v.name);
        return names;
    }
    std::stringstream ss(list);
    for (std::string name; std::getline(ss, name, ',');) {
        if (auto found = scene::findView(*all, name); !found && !fileCameraOf(name))
            return core::makeError("--views: " + found.error() + ", or file (the loaded file's own camera)");
        names.push_back(name);
    }
    if (names.empty()) return core::makeError("--views: no view named");
    return names;
}

core::Result<scene::ViewSpec> ViewOptions::spec() const {
    auto views = scene::loadViews(dataDirectory() / "views.json");
    if (!views) return views.errorInfo();
    auto found = scene::findView(*views, view);
    if (!found) return core::makeError("--view: " + found.error());
    return found;
}

core::Status ViewOptions::check() const {
    if (fileCameraOf(view)) return checkFlags(); // its camera is known once the scene is loaded
    if (auto found = spec(); !found) return core::makeError(found.error() + ", or file (the loaded file's own camera)");
    return checkFlags();
}

core::Status ViewOptions::checkFlags() const {
    if (!size.empty())
        if (auto wh = parseSize(size); !wh) return wh.errorInfo();
    for (const auto& [flag, text] : {std::pair{"--eye", &eye}, {"--dir", &dir}, {"--up", &up}})
        if (!text->empty()) {
            auto v = parseVec3(flag, *text);
            if (!v) return v.errorInfo();
            if (flag != std::string_view("--eye") && glm::length(*v) < 1e-12)
                return core::makeError(fmt::format("{}: must not be the zero vector, got '{}'", flag, *text));
        }
    // What no view's camera changes, checked before a scene is built (so `--check` says it): an eye
    // beyond the world's reach, an up along the direction when both are given (a --dir alone along
    // the view's up gets an up of its own, resolve).
    core::PerspectiveCamera probe;
    if (!eye.empty()) probe.wsEye = *parseVec3("--eye", eye);
    if (!dir.empty() && !up.empty()) probe.wsDirection = *parseVec3("--dir", dir), probe.wsUp = *parseVec3("--up", up);
    if (core::Status s = probe.validate(); !s) return core::makeError("--eye/--dir/--up: " + s.error());
    if (fov && !(*fov > 0.0 && *fov < 180.0)) // NaN-safe
        return core::makeError(fmt::format("--fov: must be in (0, 180) degrees, got {}", *fov));
    for (const auto& [flag, metres] : {std::pair{"--near", zNear}, {"--far", zFar}})
        if (metres && !(*metres > 0.0 && std::isfinite(*metres)))
            return core::makeError(fmt::format("{}: must be a distance > 0 in metres, got {}", flag, *metres));
    if (zNear && zFar && !(*zNear < *zFar))
        return core::makeError(fmt::format("--near {} must be less than --far {}", *zNear, *zFar));
    if (sun != "off" && sun != "on" && !sun.empty()) {
        if (sunElevation || sunAzimuth)
            return core::makeError("--sun: give either --sun or --sun-elevation/--sun-azimuth, not both");
        if (sun != "file")
            if (auto v = parseVec3("--sun", sun); !v) return v.errorInfo();
    }
    return core::Ok{};
}

core::Result<scene::ResolvedView> ViewOptions::resolve(const scene::Scene& sceneData, bool sayFraming) const {
    if (auto s = checkFlags(); !s) return s.errorInfo();
    scene::ResolvedView out;
    if (const std::optional<std::string> camera = fileCameraOf(view)) {
        std::string said;
        auto own = scene::fileView(sceneData, *camera, gl::kMaxLocalLightsPerKind, &said);
        if (!own) return core::makeError("--view " + view + ": " + own.error());
        if (sayFraming) fmt::print(stderr, "view {}: {}\n", view, said);
        out = std::move(*own);
    } else {
        auto found = spec();
        if (!found) return found.errorInfo();
        out = scene::resolveView(*found, sceneData);
    }
    if (out.framed && eye.empty() && sayFraming)
        fmt::print(
            stderr,
            "view {}: framing the loaded scene (no terrain to stand on{}): eye {:.1f},{:.1f},{:.1f}, near {:.3g} "
            "m, far {:.3g} m\n",
            view,
            out.framedPart.isEmpty()
                ? std::string()
                : fmt::format("; its middle, {:.3g} m across, as a few of its vertices reach {:.3g} m: a ground "
                              "or a backdrop",
                              out.framedPart.diagonal(), sceneData.localBounds().diagonal()),
            out.camera.wsEye.x, out.camera.wsEye.y, out.camera.wsEye.z, out.camera.zNear, out.camera.zFar);

    if (!size.empty()) std::tie(out.width, out.height) = *parseSize(size); // checked above
    out.setSize(out.width, out.height);                                    // the camera's aspect the picture's
    core::PerspectiveCamera& cam = out.camera;
    if (!eye.empty()) cam.wsEye = *parseVec3("--eye", eye); // checked above
    if (!dir.empty()) out.lookAlong(*parseVec3("--dir", dir));
    if (!up.empty()) cam.wsUp = *parseVec3("--up", up);
    if (fov) cam.fovYDegrees = *fov;
    if (out.framed && (!eye.empty() || !dir.empty()) && !zNear && !zFar && glm::length(cam.wsDirection) > 0.0) {
        // The framing's planes fitted its own eye: from another eye (or along another direction)
        // they would cut the scene away. Refit them to the scene's box seen from this camera: its
        // corners' depths, a margin each way, the near plane no closer than 1/1000 of the far.
        const core::Vec3 forward = glm::normalize(cam.wsDirection);
        double nearest = INFINITY, farthest = 0.0;
        for (const core::Vec3& corner : sceneData.wsBounds().corners()) {
            const double depth = glm::dot(corner - cam.wsEye, forward);
            nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
        }
        if (farthest > 0.0) {
            cam.zFar = 1.1 * farthest;
            cam.zNear = std::max(0.9 * nearest, 1e-3 * cam.zFar);
            out.fogDensity = 0.3 / cam.zFar;
            fmt::print(stderr, "view {}: the loaded scene from the given camera: near {:.3g} m, far {:.3g} m\n", view,
                       cam.zNear, cam.zFar);
        }
    }
    if (zNear) cam.zNear = *zNear;
    if (zFar) cam.zFar = *zFar;
    if (core::Status s = cam.validate(); !s) // a flag against the view's own camera: --far within its near plane
        return core::makeError(fmt::format("view {} with --eye/--dir/--up/--near/--far: {}", view, s.error()));

    if (sun == "off" || sun == "on") {
        out.sun = sun == "on";
    } else if (sun == "file") {
        const std::optional<core::DirectionalLight> own = scene::fileSunOf(sceneData);
        if (!own)
            return core::makeError("--sun file: the scene has no directional light of its own (KHR_lights_punctual)");
        out.light = *own;
        out.sun = true;
    } else if (!sun.empty()) {
        auto light = core::DirectionalLight::fromDirection(*parseVec3("--sun", sun)); // checked above
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
            return core::makeError(
                fmt::format("--scene-bounds: expected minx,miny,minz,maxx,maxy,maxz, got '{}'", sceneBounds));
        if (v[0] > v[3] || v[1] > v[4] || v[2] > v[5])
            return core::makeError("--scene-bounds: min must not exceed max on any axis");
        auto origin = scene.offset();
        if (!origin) return origin.errorInfo();
        sceneData.wsOrigin = *origin; // the views move with the box
        out.wsBounds =
            core::Aabb::fromMinMax(core::Vec3(v[0], v[1], v[2]) + *origin, core::Vec3(v[3], v[4], v[5]) + *origin);
    } else {
        auto loaded = scene.load(false);
        if (!loaded) return loaded.errorInfo();
        sceneData = std::move(loaded).value();
        out.wsBounds = sceneData.wsBounds();
    }
    auto resolved = view.resolve(sceneData);
    if (!resolved) return resolved.errorInfo();
    out.view = *resolved;
    if (!sceneBounds.empty() && view.eye.empty()) out.view.camera.wsEye.y += out.wsBounds.min.y - sceneData.wsOrigin.y;
    return out;
}

} // namespace shadowkit::app
