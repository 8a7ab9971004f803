// The view a loaded file brings: its own camera, lit by its own lights (`--view file`). The
// standard views measure any model under the seeds' suns; this one measures it as its author set
// it up — a glTF exported from a DCC tool or an engine with a camera and a sun in it.
#include "shadowkit/scene/views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace shadowkit::scene {
namespace {

std::string nameOf(const Scene& scene, size_t camera) {
    const std::string& name = scene.cameras[camera].name;
    return "camera " + std::to_string(camera) + (name.empty() ? "" : " '" + name + "'");
}

core::Result<size_t> cameraNamed(const Scene& scene, const std::string& which) {
    if (scene.cameras.empty()) return core::makeError("the scene has no camera of its own (a glTF's `cameras`)");
    if (which.empty()) return size_t(0);
    if (std::all_of(which.begin(), which.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        const size_t index = which.size() < 10 ? size_t(std::stoul(which)) : scene.cameras.size();
        if (index < scene.cameras.size()) return index;
    }
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        if (scene.cameras[i].name == which) return i;
    std::string names;
    for (size_t i = 0; i < scene.cameras.size(); ++i) names += (i ? ", " : "") + nameOf(scene, i);
    return core::makeError("no camera '" + which + "' in the scene, which has " + names);
}

// Metres from `from` to the farthest corner of `box`: the reach a light needs to light all of it.
double reachOver(const core::Aabb& box, const core::Vec3& from) {
    double reach = 0.0;
    for (const core::Vec3& corner : box.corners()) reach = std::max(reach, glm::length(corner - from));
    return reach;
}

} // namespace

std::optional<core::DirectionalLight> fileSunOf(const Scene& scene) {
    for (const FileLight& light : scene.lights)
        if (light.kind == FileLight::Kind::Sun)
            return core::DirectionalLight::fromDirection(light.localDirection).value(); // unit (gltf_viewpoints.cpp)
    return std::nullopt;
}

core::Result<ResolvedView> fileView(const Scene& scene, const std::string& which, int maxLocalLights,
                                    std::string* said) {
    auto index = cameraNamed(scene, which);
    if (!index) return index.errorInfo();
    const FileCamera& fc = scene.cameras[*index];
    const core::Aabb box = scene.localBounds();
    ResolvedView out;
    out.framed = false;

    // The picture: 1280 pixels wide at the camera's aspect, as the standard views are.
    out.width = 1280;
    out.height = fc.aspect ? std::clamp(int(std::lround(1280.0 / *fc.aspect)), 1, 16384) : 720;
    core::PerspectiveCamera& cam = out.camera;
    cam.wsEye = fc.localEye, cam.wsDirection = fc.localForward, cam.wsUp = fc.localUp;
    cam.fovYDegrees = fc.fovYDegrees;
    cam.aspect = double(out.width) / double(out.height);

    // Planes: the file's, tightened to the scene's box where they leave room — an exporter's far
    // plane is often a million metres (2CylinderEngine.glb: 0.05 to 10⁶ m round an engine 700
    // units across), which would spend the depth buffer's precision on nothing.
    double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
    for (const core::Vec3& corner : box.corners()) {
        const double depth = glm::dot(corner - fc.localEye, fc.localForward);
        nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
    }
    const std::string named = nameOf(scene, *index);
    if (!(farthest > fc.zNear))
        return core::makeError(named + " looks away from the scene: nothing lies in front of it");
    cam.zFar = std::min(fc.zFar.value_or(std::numeric_limits<double>::infinity()), 1.1 * farthest);
    cam.zNear = std::max(fc.zNear, std::min(0.9 * nearest, 0.5 * cam.zFar));
    if (fc.orthographicHalfHeight) {
        // A telephoto: the eye drawn back by a hundred times the depth the picture spans (the
        // scene's within the camera's planes), so that a size at its far end is drawn 1 % smaller
        // than at its near end, and the field opened to the orthographic half height at its middle.
        const double front = std::max(nearest, fc.zNear), back = std::min(farthest, *fc.zFar);
        const double span = std::max(back - front, 1e-6 * std::max(std::abs(back), 1.0));
        const double behind = 100.0 * span;
        cam.wsEye -= behind * fc.localForward;
        cam.fovYDegrees = glm::degrees(2.0 * std::atan(*fc.orthographicHalfHeight / (behind + 0.5 * (front + back))));
        cam.zNear = behind + front - 0.05 * span;
        cam.zFar = behind + back + 0.05 * span;
    }
    // A framed scene's: e^-0.3 at the far plane; none seen orthographically, where the telephoto's
    // eye is so far back that fog would be one veil over the whole picture.
    out.fogDensity = fc.orthographicHalfHeight ? 0.0 : 0.3 / cam.zFar;

    // The lights: the first sun, then points and spots up to what a frame can shadow.
    const FileLight* sun = nullptr;
    size_t suns = 0, dropped = 0;
    for (const FileLight& light : scene.lights) {
        const double range = light.range.value_or(std::max(1.01 * reachOver(box, light.localPosition), 1e-3));
        if (light.kind == FileLight::Kind::Sun) {
            if (!sun) sun = &light;
            ++suns;
        } else if (light.kind == FileLight::Kind::Point) {
            if (int(out.points.size()) < maxLocalLights)
                out.points.push_back({.wsPosition = light.localPosition, .range = range});
            else
                ++dropped;
        } else {
            if (int(out.spots.size()) < maxLocalLights)
                out.spots.push_back({.wsPosition = light.localPosition,
                                     .wsDirection = light.localDirection,
                                     .coneDegrees = light.coneDegrees,
                                     .range = range});
            else
                ++dropped;
        }
    }
    std::string lit;
    if (sun) {
        out.light = *fileSunOf(scene);
        lit = "its sun" + (sun->name.empty() ? "" : " '" + sun->name + "'");
        if (suns > 1) lit += " (the first of its " + std::to_string(suns) + " suns: a frame draws one)";
    } else if (!out.points.empty() || !out.spots.empty()) {
        out.sun = false; // night: its lamps alone, as the author lit it
        lit = "no sun";
    } else {
        // Unlit: the standard views' sun, 45° up and 90° to the right of where the camera looks.
        out.light = core::DirectionalLight::fromSunAngles(45.0, core::azimuthDegreesOf(fc.localForward) + 90.0).value();
        lit = "no light of its own: the standard sun, 45° up, 90° right of the camera";
    }
    if (!out.points.empty() || !out.spots.empty())
        lit += ", " + std::to_string(out.points.size()) + " point and " + std::to_string(out.spots.size()) +
               " spot lights";
    if (dropped)
        lit += " (" + std::to_string(dropped) + " more left out: a frame shadows " + std::to_string(maxLocalLights) +
               " of each kind)";

    cam.wsEye += scene.wsOrigin;
    for (core::SpotLight& s : out.spots) s.wsPosition += scene.wsOrigin;
    for (core::PointLight& p : out.points) p.wsPosition += scene.wsOrigin;
    if (said) {
        char planes[64];
        std::snprintf(planes, sizeof planes, "; near %.3g m, far %.3g m", cam.zNear, cam.zFar);
        *said = named + " of " + std::to_string(scene.cameras.size()) + ", " + lit + planes;
    }
    return out;
}

} // namespace shadowkit::scene
