// Camera paths. Every coordinate (x, height, z of eye and target; the sun's elevation and
// azimuth) is interpolated over the key times by a monotone piecewise cubic (Fritsch and
// Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17(2), 1980): it
// passes through every key at its time, its velocity is continuous (no jump between frames
// a camera would show), and between two keys a coordinate never leaves their range. A
// Catmull-Rom spline is as smooth but swings beyond the keys: a camera kept 1.8 m above
// the ground by two keys would dip towards it between them. Tangents: the weighted
// harmonic mean of the neighbouring slopes with non-uniform spacing (zero where the slope
// changes sign, so a key that is a turning point is an extremum); the end tangents are the
// end segments' slopes.
#include "shadowkit/scene/camera_path.h"

#include "framing.h"
#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/file_read.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {
namespace {

using nlohmann::json;

// The monotone cubic through (times[k], values[k]) at t; holds the ends outside them.
double monotoneCubic(const std::vector<double>& times, const std::vector<double>& values, double t) {
    const size_t n = times.size();
    if (n == 1 || t <= times.front()) return values.front();
    if (t >= times.back()) return values.back();
    size_t k = 0; // segment [k, k + 1] holds t
    while (k + 2 < n && t >= times[k + 1]) ++k;
    auto slope = [&](size_t i) { return (values[i + 1] - values[i]) / (times[i + 1] - times[i]); };
    auto tangent = [&](size_t i) {
        if (i == 0) return slope(0);
        if (i == n - 1) return slope(n - 2);
        const double before = slope(i - 1), after = slope(i);
        if (before * after <= 0.0) return 0.0;
        const double h0 = times[i] - times[i - 1], h1 = times[i + 1] - times[i];
        return 3.0 * (h0 + h1) / ((2.0 * h1 + h0) / before + (h1 + 2.0 * h0) / after);
    };
    const double h = times[k + 1] - times[k], s = (t - times[k]) / h;
    const double s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * values[k] + (s3 - 2.0 * s2 + s) * h * tangent(k) +
           (-2.0 * s3 + 3.0 * s2) * values[k + 1] + (s3 - s2) * h * tangent(k + 1);
}

// Interpolates each of the `Components` coordinates valueOf(key)[c] over the keys' times.
template <int Components, typename Key, typename ValueOf>
glm::vec<Components, double> interpolate(const std::vector<Key>& keys, double t, ValueOf valueOf) {
    std::vector<double> times, values;
    for (const Key& key : keys) times.push_back(key.time);
    glm::vec<Components, double> out;
    for (int c = 0; c < Components; ++c) {
        values.clear();
        for (const Key& key : keys) values.push_back(valueOf(key)[c]);
        out[c] = monotoneCubic(times, values, t);
    }
    return out;
}

// What a key may hold, so that every coordinate the interpolation computes is finite: values
// within kMaxGroundPointMetres (1e13 m apart at most) over gaps of at least kMinKeyGapSeconds
// give slopes below 1e19 m/s and tangents of that order, and times within kMaxPathSeconds keep a
// frame's time, start + span × i / (frames − 1), finite. A file without them met an eye 1e49 m
// up, or key times 1e308 s apart ("eye and target meet at t = -nan s"), frames into a run.
constexpr double kMaxPathSeconds = 1e9;    // about 32 years either side of 0
constexpr double kMinKeyGapSeconds = 1e-6; // a thousand times finer than any frame rate
constexpr double kMaxSunAzimuthDegrees = 1e6;

core::Result<core::Vec3> groundPoint(const json& key, const char* xzField, const char* heightField,
                                     const std::string& where) {
    if (!key.contains(xzField)) return core::makeError(where + ": needs \"" + xzField + "\"");
    const auto xz = key[xzField].get<std::vector<double>>();
    if (xz.size() != 2) return core::makeError(where + ": " + xzField + " must hold 2 numbers");
    const core::Vec3 p(xz[0], key.value(heightField, 1.8), xz[1]);
    const double reach = kMaxGroundPointMetres;
    if (!(std::abs(p.x) <= reach && std::abs(p.y) <= reach && std::abs(p.z) <= reach))
        return core::makeError(where + ": " + xzField + " and " + heightField + " must be finite, at most 5e12 m");
    if (p.y < 0.0) return core::makeError(where + ": " + heightField + " must be >= 0 metres above the ground");
    return p;
}

// A key's time: within kMaxPathSeconds of 0, and after the previous key's (if any) by at least
// kMinKeyGapSeconds.
core::Status keyTime(double time, const double* previous, const std::string& where) {
    if (!(std::abs(time) <= kMaxPathSeconds))
        return core::makeError(where + ": time must be finite, within 1e9 s of 0");
    if (previous && !(time - *previous >= kMinKeyGapSeconds))
        return core::makeError(where + ": times must increase from key to key, by 1e-6 s at least");
    return core::Ok{};
}

core::Result<CameraPath> parsePath(const json& root) {
    CameraPath path;
    if (!root.is_object() || !root.contains("camera") || !root["camera"].is_array() || root["camera"].empty())
        return core::makeError("expected an object with a non-empty \"camera\" array of keys");
    path.name = root.value("name", "");
    if (root.contains("on_loaded_scene")) {
        const json& mode = root["on_loaded_scene"];
        if (!mode.is_string() || (mode != "frame" && mode != "keys"))
            return core::makeError("on_loaded_scene must be \"frame\" (frame a scene without ground from the keys' "
                                   "directions) or \"keys\" (the keys as written)");
        path.frameLoadedScene = mode == "frame";
    }
    // Whole numbers read as numbers first: converting 3.6e20 to int is undefined.
    const double width = root.value("width", double(path.width)), height = root.value("height", double(path.height));
    const double frames = root.value("frames", double(path.frames));
    path.fovYDegrees = root.value("fov", path.fovYDegrees);
    path.zNear = root.value("near", path.zNear);
    path.zFar = root.value("far", path.zFar);
    if (!(width >= 1 && width <= 16384 && height >= 1 && height <= 16384) || width != std::floor(width) ||
        height != std::floor(height))
        return core::makeError("width and height must be whole numbers in [1, 16384]");
    if (!(frames >= 1 && frames <= 100000) || frames != std::floor(frames))
        return core::makeError("frames must be a whole number in [1, 100000]");
    path.width = int(width), path.height = int(height), path.frames = int(frames);
    core::PerspectiveCamera probe;
    probe.fovYDegrees = path.fovYDegrees;
    probe.zNear = path.zNear;
    probe.zFar = path.zFar;
    if (core::Status s = probe.validate(); !s) return core::makeError(s.error());
    for (size_t k = 0; k < root["camera"].size(); ++k) {
        const json& j = root["camera"][k];
        const std::string where = "camera key " + std::to_string(k);
        if (!j.is_object() || !j.contains("time") || !j["time"].is_number())
            return core::makeError(where + ": needs a number \"time\"");
        CameraKey key;
        key.time = j["time"].get<double>();
        auto eye = groundPoint(j, "eye_xz", "eye_height", where);
        if (!eye) return eye.errorInfo();
        auto target = groundPoint(j, "target_xz", "target_height", where);
        if (!target) return target.errorInfo();
        key.eye = *eye;
        key.target = *target;
        // Between keys eye and target may still meet (viewAt says when); at a key, the file is wrong.
        if (!(glm::length(key.target - key.eye) > 1e-6))
            return core::makeError(where + ": eye and target meet (eye_xz and eye_height equal target_xz and "
                                           "target_height)");
        const double* previous = path.camera.empty() ? nullptr : &path.camera.back().time;
        if (core::Status s = keyTime(key.time, previous, where); !s) return s.errorInfo();
        path.camera.push_back(key);
    }
    if (root.contains("sun")) {
        if (!root["sun"].is_array()) return core::makeError("\"sun\" must be an array of keys");
        for (size_t k = 0; k < root["sun"].size(); ++k) {
            const json& j = root["sun"][k];
            const std::string where = "sun key " + std::to_string(k);
            if (!j.is_object() || !j.contains("time") || !j.contains("elevation") || !j.contains("azimuth"))
                return core::makeError(where + ": needs \"time\", \"elevation\" and \"azimuth\"");
            SunKey key{j["time"].get<double>(), j["elevation"].get<double>(), j["azimuth"].get<double>()};
            if (!(std::abs(key.azimuthDegrees) <= kMaxSunAzimuthDegrees) || !(std::abs(key.elevationDegrees) <= 90.0))
                return core::makeError(where + ": azimuth must be within 1e6 degrees of 0, elevation in [-90, 90]");
            if (j.contains("angle")) {
                if (!j["angle"].is_number() || !(j["angle"].get<double>() >= 0.0 && j["angle"].get<double>() <= 20.0))
                    return core::makeError(where + ": angle must be a number in [0, 20] degrees (the sun: 0.53)");
                key.angleDegrees = j["angle"].get<double>();
            }
            // All or none: between a key with a size and one without there is nothing to interpolate.
            if (!path.sun.empty() && path.sun.front().angleDegrees.has_value() != key.angleDegrees.has_value())
                return core::makeError(where +
                                       ": \"angle\" on some sun keys but not on others: give it on every key or none");
            const double* previous = path.sun.empty() ? nullptr : &path.sun.back().time;
            if (core::Status s = keyTime(key.time, previous, where); !s) return s.errorInfo();
            path.sun.push_back(key);
        }
    }
    return path;
}

} // namespace

double CameraPath::timeOfFrame(int frame) const {
    if (frames <= 1) return startTime();
    return startTime() + (endTime() - startTime()) * double(frame) / double(frames - 1);
}

core::Result<CameraPath> loadCameraPath(const std::filesystem::path& file) {
    const auto text = readFile(file);
    if (!text) return text.errorInfo();
    json root;
    try {
        root = json::parse(*text);
    } catch (const json::exception& e) { // parse errors, and numbers out of range (out_of_range.406)
        return core::makeError(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    core::Result<CameraPath> path = core::makeError("");
    try {
        path = parsePath(root);
    } catch (const json::exception& e) {
        return core::makeError(file.string() + ": a field has the wrong type (" + e.what() + ")");
    }
    if (!path) return core::makeError(file.string() + ": " + path.error());
    if (path->name.empty()) path->name = file.stem().string();
    return path;
}

core::Result<CameraPath> findCameraPath(const std::string& nameOrFile, const std::filesystem::path& dir) {
    if (nameOrFile.find('/') != std::string::npos || nameOrFile.ends_with(".json")) return loadCameraPath(nameOrFile);
    const std::filesystem::path file = dir / (nameOrFile + ".json");
    if (std::filesystem::exists(file)) return loadCameraPath(file);
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    return core::makeError("unknown path \"" + nameOrFile + "\" (known: " + (known.empty() ? "none" : known) +
                           ", or a .json file)");
}

CameraKey cameraAt(const std::vector<CameraKey>& keys, double t) {
    SK_ASSERT(!keys.empty(), "cameraAt(): a path needs keys");
    CameraKey out;
    out.time = t;
    out.eye = interpolate<3>(keys, t, [](const CameraKey& k) { return k.eye; });
    out.target = interpolate<3>(keys, t, [](const CameraKey& k) { return k.target; });
    return out;
}

SunKey sunAt(const std::vector<SunKey>& keys, double t) {
    SK_ASSERT(!keys.empty(), "sunAt(): a sun path needs keys");
    const core::Vec2 angles =
        interpolate<2>(keys, t, [](const SunKey& k) { return core::Vec2(k.elevationDegrees, k.azimuthDegrees); });
    SunKey out{t, angles.x, angles.y};
    // Monotone between keys, so never outside the two keys' sizes: never negative.
    if (keys.front().angleDegrees)
        out.angleDegrees = interpolate<1>(keys, t, [](const SunKey& k) { return glm::dvec1(*k.angleDegrees); }).x;
    return out;
}

core::Aabb framedOverPath(const CameraPath& path, Scene& scene, double now) {
    if (!path.frameLoadedScene || scene.terrain) return {};
    // A still scene stands as it is at every frame: its box once.
    const int frames = std::max(path.frames, 1);
    const int samples = scene.animated() ? std::min(frames, kPathFramingSamples) : 1;
    core::Aabb box;
    for (int k = 0; k < samples; ++k) {
        if (scene.animated()) {
            const int frame = samples == 1 ? 0 : int(std::lround(double(k) * (frames - 1) / (samples - 1)));
            animate(scene, path.timeOfFrame(frame));
        }
        const core::Aabb bounds = scene.localBounds();
        if (isFramed(scene, bounds)) box.extend(framedBounds(scene, bounds));
    }
    if (scene.animated()) animate(scene, now);
    return box;
}

core::Result<ResolvedView> viewAt(const CameraPath& path, const Scene& scene, double t,
                                  const core::DirectionalLight& fallbackSun, const core::Aabb& framedBox) {
    const CameraKey key = cameraAt(path.camera, t);
    ResolvedView view;
    view.width = path.width;
    view.height = path.height;
    view.camera.fovYDegrees = path.fovYDegrees;
    view.camera.aspect = double(path.width) / double(path.height);
    view.camera.zNear = path.zNear;
    view.camera.zFar = path.zFar;
    auto meet = [&] {
        return core::makeError("path \"" + path.name + "\" at t = " + std::to_string(t) + " s: eye and target meet");
    };
    core::Vec3 eye, target;
    // The box framed: the path's where given, else the scene's now (a walk over every
    // instance, only where it may be framed).
    core::Aabb box = framedBox;
    if (box.isEmpty() && path.frameLoadedScene && !scene.terrain) {
        const core::Aabb bounds = scene.localBounds();
        if (isFramed(scene, bounds)) box = framedBounds(scene, bounds);
    }
    if (path.frameLoadedScene && !scene.terrain && !box.isEmpty()) {
        // The keys' direction (heights above a ground this scene lacks cancel out of it) as a
        // compass direction and a pitch. Within 1e-5 of vertical the compass is north's, so that
        // the framing's up is the image's (north, below).
        const core::Vec3 along = key.target - key.eye;
        const double level = std::hypot(along.x, along.z);
        if (!(glm::length(along) > 1e-6)) return meet();
        const double azimuth = level > 1e-5 * glm::length(along) ? std::atan2(along.x, -along.z) : 0.0;
        const Framing framing =
            frameBounds(box, azimuth, std::atan2(along.y, level), path.fovYDegrees, view.camera.aspect);
        eye = framing.eye;
        target = framing.eye + framing.direction;
        view.camera.zNear = framing.zNear;
        view.camera.zFar = framing.zFar;
        view.fogDensity = framing.fogDensity;
        view.framed = true;
    } else {
        eye = core::Vec3(key.eye.x, scene.groundHeightAt(key.eye.x, key.eye.z) + key.eye.y, key.eye.z);
        target =
            core::Vec3(key.target.x, scene.groundHeightAt(key.target.x, key.target.z) + key.target.y, key.target.z);
    }
    if (!(glm::length(target - eye) > 1e-6)) return meet();
    view.camera.wsEye = scene.wsOrigin + eye; // the keys are in the scene's coordinates
    view.camera.wsDirection = glm::normalize(target - eye);
    // Up is the sky's, except where the camera looks straight up or down — a path may pass under or
    // over its target — where the sky's up is no direction in the image: north is the top of it
    // there, as on a map (conventions.h). Within 1e-5 of vertical, ten times the cone
    // PerspectiveCamera::validate refuses.
    const core::Vec3 sky(0, 1, 0);
    const bool vertical = glm::length(glm::cross(view.camera.wsDirection, sky)) < 1e-5;
    view.camera.wsUp = vertical ? core::Vec3(0, 0, -1) : sky;
    view.light = fallbackSun;
    if (!path.sun.empty()) {
        const SunKey sun = sunAt(path.sun, t);
        auto light = core::DirectionalLight::fromSunAngles(sun.elevationDegrees, sun.azimuthDegrees);
        if (!light) return light.errorInfo();
        view.light = *light;
        view.sunAngleDegrees = sun.angleDegrees;
    }
    if (core::Status s = view.camera.validate(); !s) return core::makeError("path \"" + path.name + "\": " + s.error());
    return view;
}

} // namespace shadowkit::scene
