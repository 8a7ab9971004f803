// Camera paths (data/paths/*.json): keyframes of eye and target over time, and optionally of
// the sun, interpolated smoothly so that a sequence of frames can be rendered, and any one of
// them by itself. The format is documented in docs/dynamics.md ("Camera paths").
#pragma once

#include "shadowkit/core/light.h"
#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/scene/views.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::scene {

// Positions are (x, height above the ground, z): a path follows the terrain.
struct CameraKey {
    double time = 0.0; // seconds
    core::Vec3 eye{0.0, 1.8, 0.0};
    core::Vec3 target{0.0, 1.8, -10.0};
};
struct SunKey {
    double time = 0.0;              // seconds
    double elevationDegrees = 45.0; // [-90, 90]
    double azimuthDegrees = 90.0;   // compass (conventions.h)
    // The sun's angular diameter in degrees, [0, 20] ("angle"; the real sun 0.53): on every key
    // of a path or on none. None: the sun's size comes from elsewhere (--sun-angle).
    std::optional<double> angleDegrees;
};

struct CameraPath {
    std::string name;
    int width = 1280, height = 720;
    double fovYDegrees = 60.0, zNear = 0.5, zFar = 500.0;
    int frames = 240;              // spread evenly from the first camera key's time to the last's
    std::vector<CameraKey> camera; // at least one, times increasing
    std::vector<SunKey> sun;       // may be empty (the sun then comes from elsewhere); times increasing
    // "on_loaded_scene": "frame" — the keys are written for the forest, so on a scene without
    // ground (a loaded file) each frame frames the scene as a still view does, from the compass
    // direction and pitch the keys give at that moment. "keys" (the default): the keys are
    // positions in whatever scene is drawn, as a path written for that model wants.
    bool frameLoadedScene = false;

    double startTime() const { return camera.front().time; }
    double endTime() const { return camera.back().time; }
    // Time of frame i in [0, frames): the first frame at startTime(), the last at endTime().
    double timeOfFrame(int frame) const;
};

// Reads a path file; errors name the file and the offending key or field.
core::Result<CameraPath> loadCameraPath(const std::filesystem::path& file);
// A path by name (pathsDirectory/NAME.json: the front end says where its data lives, e.g. the
// project's data/paths) or by file name (anything ending in .json or holding a '/'); an unknown
// name lists the paths there are.
core::Result<CameraPath> findCameraPath(const std::string& nameOrFile, const std::filesystem::path& pathsDirectory);

// Interpolation through every key at its time, continuous in position and velocity, each
// coordinate within its two neighbouring keys' range (a monotone piecewise cubic; a single
// key holds still). Before the first key and after the last the path holds its end key.
CameraKey cameraAt(const std::vector<CameraKey>& keys, double t);
// Likewise for the sun's angles, and its size when the keys have one; precondition: keys not empty.
SunKey sunAt(const std::vector<SunKey>& keys, double t);

// What a path that frames a loaded scene (frameLoadedScene, no terrain) frames in every frame:
// the union of the box a still view frames (framing.h) over the scene as it stands at the path's
// frames — at most kPathFramingSamples of them, spread evenly, the first and the last included.
// One box for the whole path, so that the camera holds its distance while the scene's movers
// move (a walking figure's swinging arms would otherwise pull it to and fro) and keeps a mover
// that travels in the picture, and so that a frame drawn alone is the frame drawn in a sequence.
// Animates `scene` to each of those times and leaves it at `now` (animation.h). Empty where the
// path follows its keys.
inline constexpr int kPathFramingSamples = 64;
core::Aabb framedOverPath(const CameraPath& path, Scene& scene, double now);

// The camera at time t placed over the scene's ground, or framing a scene without ground when
// the path says so (frameLoadedScene) — `framedBox` (framedOverPath's) where given, else the
// scene as it stands now — with the path's sun when it has one (else `fallbackSun`) and its size
// when its keys give one. Fails when eye and target meet.
core::Result<ResolvedView> viewAt(const CameraPath& path, const Scene& scene, double t,
                                  const core::DirectionalLight& fallbackSun = {}, const core::Aabb& framedBox = {});

} // namespace shadowkit::scene
