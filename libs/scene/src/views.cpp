#include "shadowkit/scene/views.h"

#include "framing.h"
#include "shadowkit/scene/file_read.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace shadowkit::scene {
namespace {

using nlohmann::json;

core::Result<ViewLight> parseLight(const json& j, const std::string& view) {
    const std::string where = "view \"" + view + "\": lights: ";
    if (!j.is_object()) return core::makeError(where + "each light must be an object");
    ViewLight l;
    const std::string type = j.value("type", "");
    if (type != "point" && type != "spot") return core::makeError(where + "type must be \"point\" or \"spot\"");
    l.spot = type == "spot";
    auto vec3 = [&](const char* key, core::Vec3& out) -> core::Status {
        if (!j.contains(key)) return core::Ok{};
        const auto v = j[key].get<std::vector<double>>();
        if (v.size() != 3) return core::makeError(where + key + " must hold 3 numbers");
        out = core::Vec3(v[0], v[1], v[2]);
        return core::Ok{};
    };
    if (auto s = vec3("at", l.at); !s) return s.errorInfo();
    if (auto s = vec3("aim", l.aim); !s) return s.errorInfo();
    l.coneDegrees = j.value("cone", l.coneDegrees);
    l.range = j.value("range", l.range);
    l.radius = j.value("radius", l.radius);
    const core::Status valid =
        l.spot
            ? core::SpotLight{.wsDirection = l.aim, .coneDegrees = l.coneDegrees, .range = l.range, .radius = l.radius}
                  .validate()
            : core::PointLight{.range = l.range, .radius = l.radius}.validate();
    if (!valid) return core::makeError(where + valid.error());
    if (!core::isFinite(l.at)) return core::makeError(where + "at must be finite");
    return l;
}

core::Result<ViewSpec> parseView(const json& j) {
    ViewSpec v;
    if (!j.is_object() || !j.contains("name") || !j["name"].is_string())
        return core::makeError("each view needs a string \"name\"");
    v.name = j["name"].get<std::string>();
    try {
        v.probes = j.value("probes", "");
        // Sizes read as numbers first: nlohmann's conversion of 3.6e20 to int is undefined.
        const double width = j.value("width", double(v.width)), height = j.value("height", double(v.height));
        if (!(width >= 1 && width <= 16384 && height >= 1 && height <= 16384) || width != std::floor(width) ||
            height != std::floor(height))
            return core::makeError("view \"" + v.name + "\": width and height must be whole numbers in [1, 16384]");
        v.width = int(width), v.height = int(height);
        v.fovYDegrees = j.value("fov", v.fovYDegrees);
        v.zNear = j.value("near", v.zNear);
        v.zFar = j.value("far", v.zFar);
        if (j.contains("eye_xz")) {
            const auto xz = j["eye_xz"].get<std::vector<double>>();
            if (xz.size() != 2) return core::makeError("view \"" + v.name + "\": eye_xz must hold 2 numbers");
            v.eyeX = xz[0];
            v.eyeZ = xz[1];
        }
        v.eyeHeight = j.value("eye_height", v.eyeHeight);
        v.azimuthDegrees = j.value("azimuth", v.azimuthDegrees);
        v.pitchDegrees = j.value("pitch", v.pitchDegrees);
        v.sunElevationDegrees = j.value("sun_elevation", v.sunElevationDegrees);
        v.sunAzimuthFromViewDegrees = j.value("sun_azimuth_from_view", v.sunAzimuthFromViewDegrees);
        v.sun = j.value("sun", v.sun);
        if (j.contains("sun_angle")) v.sunAngleDegrees = j["sun_angle"].get<double>();
        if (j.contains("lights")) {
            if (!j["lights"].is_array()) return core::makeError("view \"" + v.name + "\": lights must be an array");
            for (const json& entry : j["lights"]) {
                auto light = parseLight(entry, v.name);
                if (!light) return light.errorInfo();
                v.lights.push_back(*light);
            }
        }
    } catch (const json::exception& e) {
        return core::makeError("view \"" + v.name + "\": a field has the wrong type (" + e.what() + ")");
    }
    if (v.width <= 0 || v.height <= 0 || v.width > 16384 || v.height > 16384)
        return core::makeError("view \"" + v.name + "\": width and height must be in [1, 16384]");
    // The eye stands eye_height above the ground at eye_xz (kMaxGroundPointMetres: why that far).
    constexpr double kReach = kMaxGroundPointMetres;
    if (!(std::abs(v.eyeX) <= kReach && std::abs(v.eyeZ) <= kReach && std::abs(v.eyeHeight) <= kReach))
        return core::makeError("view \"" + v.name + "\": eye_xz and eye_height must be finite, at most 5e12 m");
    if (!(std::abs(v.pitchDegrees) < 90.0))
        return core::makeError("view \"" + v.name + "\": pitch must be in (-90, 90)");
    if (!(std::abs(v.sunElevationDegrees) <= 90.0))
        return core::makeError("view \"" + v.name + "\": sun_elevation must be in [-90, 90]");
    if (v.sunAngleDegrees && !(*v.sunAngleDegrees >= 0.0 && *v.sunAngleDegrees <= 20.0))
        return core::makeError("view \"" + v.name + "\": sun_angle must be in [0, 20] degrees (the sun: 0.53)");
    core::PerspectiveCamera probe;
    probe.fovYDegrees = v.fovYDegrees;
    probe.zNear = v.zNear;
    probe.zFar = v.zFar;
    if (core::Status s = probe.validate(); !s) return core::makeError("view \"" + v.name + "\": " + s.error());
    return v;
}

} // namespace

core::Result<std::vector<ViewSpec>> loadViews(const std::filesystem::path& file) {
    const auto text = readFile(file);
    if (!text) return text.errorInfo();
    json root;
    try {
        root = json::parse(*text);
    } catch (const json::exception& e) { // parse errors, and numbers out of range (out_of_range.406)
        return core::makeError(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    if (!root.is_object() || !root.contains("views") || !root["views"].is_array())
        return core::makeError(file.string() + ": expected an object with a \"views\" array");
    std::vector<ViewSpec> views;
    for (const json& entry : root["views"]) {
        auto view = parseView(entry);
        if (!view) return core::makeError(file.string() + ": " + view.error());
        views.push_back(std::move(view).value());
    }
    return views;
}

core::Result<ViewSpec> findView(const std::vector<ViewSpec>& views, const std::string& name) {
    std::string names;
    for (const ViewSpec& v : views) {
        if (v.name == name) return v;
        names += (names.empty() ? "" : ", ") + v.name;
    }
    return core::makeError("unknown view \"" + name + "\" (known: " + names + ")");
}

void ResolvedView::lookAlong(const core::Vec3& wsDirection) {
    const core::Vec3 forward = glm::normalize(wsDirection);
    // Parallel where the camera would refuse it (core::PerspectiveCamera::validate).
    const auto across = [&](const core::Vec3& v) { return v - glm::dot(v, forward) * forward; };
    if (glm::length(glm::cross(forward, glm::normalize(camera.wsUp))) < 1e-6) {
        // A valid camera's direction is never along its up, so this is never zero; an invalid one
        // keeps its up, for the camera's own check to name.
        const core::Vec3 up = across(glm::normalize(camera.wsDirection));
        if (glm::length(up) > 1e-6) camera.wsUp = glm::normalize(up);
    }
    camera.wsDirection = wsDirection;
}

ResolvedView resolveView(const ViewSpec& view, const Scene& scene) {
    ResolvedView out;
    out.width = view.width;
    out.height = view.height;
    core::PerspectiveCamera& cam = out.camera;
    const double az = glm::radians(view.azimuthDegrees);
    double pitch = glm::radians(view.pitchDegrees);
    cam.wsUp = core::Vec3(0, 1, 0);
    cam.fovYDegrees = view.fovYDegrees;
    cam.aspect = double(view.width) / double(view.height);
    // Where the view's local lights are placed from: the ground under the eye, or the framed centre.
    core::Vec3 lightsFrom(view.eyeX, 0.0, view.eyeZ);
    const core::Aabb bounds = scene.localBounds(); // placed in the scene's coordinates, moved to the world's at the end
    out.framed = isFramed(scene, bounds);
    if (!out.framed) {
        cam.wsEye = core::Vec3(view.eyeX, scene.groundHeightAt(view.eyeX, view.eyeZ) + view.eyeHeight, view.eyeZ);
        cam.zNear = view.zNear;
        cam.zFar = view.zFar;
    } else {
        const core::Aabb framedBox = framedBounds(scene, bounds);
        if (framedBox.diagonal() < bounds.diagonal()) out.framedPart = framedBox;
        const Framing framing = frameBounds(framedBox, az, pitch, view.fovYDegrees, cam.aspect);
        pitch = framing.pitchRadians;
        cam.wsEye = framing.eye;
        cam.zNear = framing.zNear;
        cam.zFar = framing.zFar;
        const core::Vec3 centre = framedBox.center();
        lightsFrom = core::Vec3(centre.x, 0.0, centre.z);
        out.fogDensity = framing.fogDensity;
    }
    cam.wsDirection = core::Vec3(std::sin(az) * std::cos(pitch), std::sin(pitch), -std::cos(az) * std::cos(pitch));
    // Within 1e-5 of looking straight up or down (a pitch within 5.7e-4° of ±90°, which the file
    // allows) the sky's up is no direction in the image: the camera's own up, the pitch turned a
    // right angle on, which the sky's up is everywhere else once made square to the direction.
    if (glm::length(glm::cross(cam.wsDirection, cam.wsUp)) < 1e-5)
        cam.wsUp = core::Vec3(-std::sin(az) * std::sin(pitch), std::cos(pitch), std::cos(az) * std::sin(pitch));
    // Validated in parseView: the angles are in range, so this cannot fail.
    out.light = core::DirectionalLight::fromSunAngles(view.sunElevationDegrees,
                                                      view.azimuthDegrees + view.sunAzimuthFromViewDegrees)
                    .value();
    out.sun = view.sun;
    out.sunAngleDegrees = view.sunAngleDegrees;
    // The view's frame on the ground: right and forward by its azimuth alone (not its pitch).
    const core::Vec3 forward(std::sin(az), 0.0, -std::cos(az)), right(std::cos(az), 0.0, std::sin(az)),
        up(0.0, 1.0, 0.0);
    for (const ViewLight& l : view.lights) {
        core::Vec3 position = lightsFrom + l.at.x * right + l.at.z * forward;
        position.y = scene.groundHeightAt(position.x, position.z) + l.at.y;
        if (l.spot)
            out.spots.push_back({.wsPosition = position,
                                 .wsDirection = l.aim.x * right + l.aim.y * up + l.aim.z * forward,
                                 .coneDegrees = l.coneDegrees,
                                 .range = l.range,
                                 .radius = l.radius});
        else
            out.points.push_back({.wsPosition = position, .range = l.range, .radius = l.radius});
    }
    cam.wsEye += scene.wsOrigin;
    for (core::SpotLight& s : out.spots) s.wsPosition += scene.wsOrigin;
    for (core::PointLight& p : out.points) p.wsPosition += scene.wsOrigin;
    return out;
}

} // namespace shadowkit::scene
