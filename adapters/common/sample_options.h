// What both engine samples (adapters/osg/sample, adapters/ogre/sample) read from their command
// line, checked before the scene loads (an engine's OBJ reader can take minutes): the scene,
// the shots (a camera file, a technique, the PNG to write, one or many from --shots), the map
// and image sizes. Header-only: the samples are single files and link nothing of each other.
// Files are read as every shadowkit command reads them (scene::readFile): a camera or shots file
// that is a pipe or a directory is refused in one line instead of waiting for a writer.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/sampling_error.h"
#include "shadowkit/scene/file_read.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace shadowkit::samples {

/// The sample's name in its one-line errors ("shadowkit-osg-sample").
inline std::string& programName() {
    static std::string name = "shadowkit-sample";
    return name;
}

[[noreturn]] inline void fail(const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", programName().c_str(), message.c_str());
    std::exit(1);
}

using Vec3 = std::array<double, 3>;

/// A spot or point light of `shadowkit setup`'s "local_lights" (`--light spot:...`, `point:...`).
struct Lamp {
    bool point = false; ///< a point light: no direction or cone
    Vec3 position{}, direction{};
    double coneDegrees = 40.0; ///< a spot's full opening angle
    double range = 30.0;       ///< metres
};

/// The camera and sun of `shadowkit setup`'s JSON (under "inputs") or of a flat camera file,
/// and its first spot or point light, if it has one: the shot is then lit by that lamp alone,
/// and the mask is the lamp's visibility (scored with `shadowkit score --light`).
struct CameraAndSun {
    Vec3 eye{}, direction{}, up{}, sunTravel{};
    double fovY = 60.0, zNear = 0.5, zFar = 500.0;
    std::optional<Lamp> lamp;
};

inline Vec3 vec3(const nlohmann::json& j, const char* key, const std::string& file) {
    if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3 || !j[key][0].is_number() ||
        !j[key][1].is_number() || !j[key][2].is_number())
        fail(file + ": no \"" + std::string(key) + "\" [x, y, z]");
    return {j[key][0].get<double>(), j[key][1].get<double>(), j[key][2].get<double>()};
}

/// A camera or shots file whole, or the sample's one-line error (`what` names the option).
inline std::string readText(const std::string& what, const std::string& file) {
    constexpr uintmax_t kMaxTextBytes = uintmax_t(16) << 20; // a camera is a few hundred bytes
    auto text = scene::readFile(file, kMaxTextBytes);
    if (!text) fail(what + text.error());
    return std::move(*text);
}

inline CameraAndSun readCamera(const std::string& file) {
    const nlohmann::json root = nlohmann::json::parse(readText("", file), nullptr, false);
    if (root.is_discarded() || !root.is_object()) fail(file + ": not a JSON object");
    const nlohmann::json& holder = root.contains("inputs") ? root["inputs"] : root;
    const nlohmann::json& camera = holder.contains("camera") ? holder["camera"] : holder;
    CameraAndSun c;
    c.eye = vec3(camera, "eye", file), c.direction = vec3(camera, "direction", file), c.up = vec3(camera, "up", file);
    for (auto [key, target] :
         {std::pair{"fov_y_degrees", &c.fovY}, std::pair{"near", &c.zNear}, std::pair{"far", &c.zFar}}) {
        if (!camera.contains(key) || !camera[key].is_number()) fail(file + ": no \"" + std::string(key) + "\"");
        *target = camera[key].get<double>();
    }
    if (!holder.contains("light") || !holder["light"].is_object())
        fail(file + ": no \"light\": {\"direction\"} for the sun");
    c.sunTravel = vec3(holder["light"], "direction", file);
    if (root.contains("local_lights") && root["local_lights"].is_array())
        for (const nlohmann::json& light : root["local_lights"]) {
            const std::string type = light.is_object() ? light.value("type", "") : "";
            if (type != "spot" && type != "point") continue;
            Lamp lamp{.point = type == "point", .position = vec3(light, "position", file)};
            const nlohmann::json range = light.value("range", nlohmann::json());
            if (!range.is_number() || !(range.get<double>() > 0.0 && std::isfinite(range.get<double>())))
                fail(file + ": a " + type + " light's \"range\" is not a positive number of metres");
            lamp.range = range.get<double>();
            if (!lamp.point) {
                lamp.direction = vec3(light, "direction", file);
                const nlohmann::json cone = light.value("cone_degrees", nlohmann::json());
                if (!cone.is_number() || !(cone.get<double>() > 0.0 && cone.get<double>() <= 170.0))
                    fail(file + ": a spot light's \"cone_degrees\" is not in (0, 170]");
                lamp.coneDegrees = cone.get<double>();
            }
            c.lamp = lamp;
            break;
        }
    return c;
}

/// `auto`'s receivers from what the engine drew of the shot's camera (`raster`: view depth and
/// normals, top row first, at the frame's aspect): at most 4,096 facing the sun, as an
/// application hands the adapters from its own read-back (core::receiverSamples).
inline std::vector<core::ReceiverSample> receiversOf(const core::RasterBuffers& raster, const CameraAndSun& view) {
    const auto vec = [](const Vec3& v) { return core::Vec3(v[0], v[1], v[2]); };
    core::PerspectiveCamera camera;
    camera.wsEye = vec(view.eye), camera.wsDirection = vec(view.direction), camera.wsUp = vec(view.up);
    camera.fovYDegrees = view.fovY, camera.aspect = double(raster.width) / double(raster.height);
    camera.zNear = view.zNear, camera.zFar = view.zFar;
    auto sun = core::DirectionalLight::fromDirection(vec(view.sunTravel));
    if (!sun) fail("the shot's sun: " + sun.error());
    return core::receiverSamples(raster, camera, *sun, 4096);
}

/// One picture: the camera and sun, a technique and the PNG to write.
struct Shot {
    std::string cameraFile, technique, out;
    CameraAndSun view;
};

struct Options {
    std::string scene;
    std::vector<Shot> shots;
    int mapSize = 2048;
    int width = 640, height = 360;
    bool picture = false; ///< OSG's sample: the frame as the engine shades it, not the mask
};

/// `SAMPLE SCENE.obj CAMERA.json OUT.png [--technique T] [--map-size N] [--size WxH]`, or
/// `SAMPLE SCENE.obj --shots FILE` (a line "CAMERA.json TECHNIQUE OUT.png" each); `--picture`
/// where `picture` is offered. Every shot's technique goes through `checkTechnique` (which
/// fails in one line) and its camera file is read, before anything is loaded.
inline Options parse(int argc, char** argv, const std::function<void(const std::string&)>& checkTechnique,
                     bool offersPicture) {
    Options o;
    int positional = 0;
    std::string cameraFile, out, technique = "tsm", shotsFile;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) fail(a + " needs a value");
            return argv[++i];
        };
        if (a == "--technique")
            technique = value();
        else if (a == "--shots")
            shotsFile = value();
        else if (a == "--map-size")
            o.mapSize = std::atoi(value().c_str());
        else if (a == "--size") {
            const std::string s = value();
            if (std::sscanf(s.c_str(), "%dx%d", &o.width, &o.height) != 2) fail("--size " + s + ": not WIDTHxHEIGHT");
        } else if (a == "--picture" && offersPicture)
            o.picture = true;
        else if (a.rfind("--", 0) == 0)
            fail("unknown option " + a);
        else if (positional == 0)
            o.scene = a, ++positional;
        else if (positional == 1)
            cameraFile = a, ++positional;
        else if (positional == 2)
            out = a, ++positional;
        else
            fail("one scene, one camera file and one output, got more: " + a);
    }
    if (positional == 3 && shotsFile.empty())
        o.shots.push_back({cameraFile, technique, out, {}});
    else if (positional == 1 && !shotsFile.empty()) {
        std::istringstream in(readText("--shots ", shotsFile));
        std::string line;
        for (int number = 1; std::getline(in, line); ++number) {
            std::istringstream words(line);
            Shot shot;
            if (!(words >> shot.cameraFile)) continue; // a blank line
            std::string extra;
            if (!(words >> shot.technique >> shot.out) || (words >> extra))
                fail("--shots " + shotsFile + ":" + std::to_string(number) + ": not \"CAMERA.json TECHNIQUE OUT.png\"");
            o.shots.push_back(shot);
        }
        if (o.shots.empty()) fail("--shots " + shotsFile + ": no shots in it");
    } else
        fail("usage: " + programName() + " SCENE.obj CAMERA.json OUT.png [--technique T] [--map-size N] [--size WxH]" +
             (offersPicture ? " [--picture]" : "") + ", or SCENE.obj --shots FILE");
    if (o.mapSize < 16 || o.mapSize > 16384) fail("--map-size " + std::to_string(o.mapSize) + ": not in [16, 16384]");
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        fail("--size: not in [1, 16384] pixels a side");
    for (Shot& shot : o.shots) {
        checkTechnique(shot.technique);
        shot.view = readCamera(shot.cameraFile);
    }
    return o;
}

} // namespace shadowkit::samples
