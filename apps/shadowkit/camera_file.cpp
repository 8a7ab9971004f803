#include "camera_file.h"

#include "shadowkit/scene/file_read.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace shadowkit::app {
namespace {

using nlohmann::json;

// A field's number, finite; `what` names it for the error.
core::Result<double> numberAt(const json& object, const char* key, const std::string& what) {
    if (!object.contains(key)) return core::makeError(fmt::format("{}: no \"{}\"", what, key));
    const json& v = object.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        return core::makeError(fmt::format("{}: \"{}\" must be a finite number", what, key));
    return v.get<double>();
}

core::Result<core::Vec3> vectorAt(const json& object, const char* key, const std::string& what) {
    if (!object.contains(key)) return core::makeError(fmt::format("{}: no \"{}\"", what, key));
    const json& v = object.at(key);
    if (!v.is_array() || v.size() != 3)
        return core::makeError(fmt::format("{}: \"{}\" must be three numbers [x, y, z]", what, key));
    core::Vec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!v[size_t(i)].is_number() || !std::isfinite(v[size_t(i)].get<double>()))
            return core::makeError(fmt::format("{}: \"{}\" must be three finite numbers", what, key));
        out[i] = v[size_t(i)].get<double>();
    }
    return out;
}

} // namespace

core::Result<CameraFile> loadCameraFile(const std::string& file) {
    const std::string what = "--camera " + file;
    const auto text = scene::readFile(file);
    if (!text) return core::makeError("--camera " + text.error());
    json root = json::parse(*text, nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded() || !root.is_object()) return core::makeError(what + ": not a JSON object");
    // `setup`'s output holds the camera and the sun under "inputs".
    const json& holder = root.contains("inputs") && root["inputs"].is_object() ? root["inputs"] : root;
    const json& camera = holder.contains("camera") && holder["camera"].is_object() ? holder["camera"] : holder;

    CameraFile out;
    core::PerspectiveCamera& cam = out.camera;
    auto eye = vectorAt(camera, "eye", what);
    if (!eye) return eye.errorInfo();
    auto direction = vectorAt(camera, "direction", what);
    if (!direction) return direction.errorInfo();
    auto up = vectorAt(camera, "up", what);
    if (!up) return up.errorInfo();
    auto fov = numberAt(camera, "fov_y_degrees", what);
    if (!fov) return fov.errorInfo();
    auto zNear = numberAt(camera, "near", what);
    if (!zNear) return zNear.errorInfo();
    auto zFar = numberAt(camera, "far", what);
    if (!zFar) return zFar.errorInfo();
    cam.wsEye = *eye, cam.wsDirection = *direction, cam.wsUp = *up;
    cam.fovYDegrees = *fov, cam.zNear = *zNear, cam.zFar = *zFar;
    cam.aspect = 0.0;
    if (camera.contains("aspect")) {
        auto aspect = numberAt(camera, "aspect", what);
        if (!aspect) return aspect.errorInfo();
        cam.aspect = *aspect;
    }
    for (auto [key, target] : {std::pair{"width", &out.width}, std::pair{"height", &out.height}}) {
        if (!camera.contains(key)) continue;
        const json& v = camera.at(key);
        if (!v.is_number_integer() || v.get<int64_t>() < 1 || v.get<int64_t>() > 16384)
            return core::makeError(fmt::format("{}: \"{}\" must be a whole number of pixels in [1, 16384]", what, key));
        *target = v.get<int>();
    }
    if (out.width.has_value() != out.height.has_value())
        return core::makeError(what + ": \"width\" and \"height\" come together");
    // Checked as any camera is, once it has an aspect (the mask's, if the file gives none).
    core::PerspectiveCamera probe = cam;
    if (probe.aspect == 0.0) probe.aspect = 1.0;
    if (auto s = probe.validate(); !s) return core::makeError(what + ": " + s.error());

    if (holder.contains("light")) {
        const json& light = holder["light"];
        if (!light.is_object()) return core::makeError(what + ": \"light\" must be an object with a \"direction\"");
        auto travel = vectorAt(light, "direction", what + " light");
        if (!travel) return travel.errorInfo();
        auto sun = core::DirectionalLight::fromDirection(*travel);
        if (!sun) return core::makeError(what + ": light: " + sun.error());
        out.light = *sun;
    }
    return out;
}

} // namespace shadowkit::app
