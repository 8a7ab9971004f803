// Standard views (data/views.json, docs/references.md, evaluation §2): camera, screen size and sun.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace shadowkit::scene {

// How far a view's or a camera path's ground point (x, height above the ground, z) may lie from
// the scene's origin in each coordinate, metres: half the camera's reach (core::kMaxWorldMetres),
// so that the eye resolved over any ground stays inside it.
inline constexpr double kMaxGroundPointMetres = 0.5 * core::kMaxWorldMetres;

// A spot or point light of a view, placed in the view's own frame so it follows the eye over
// any ground: `at` is (right, height above the ground under the light, forward) in metres from
// the ground point under the eye, `aim` a spot light's axis as (right, up, forward).
struct ViewLight {
    bool spot = false;
    core::Vec3 at{0.0, 3.0, 10.0};
    core::Vec3 aim{0.0, 0.0, 1.0};
    double coneDegrees = 40.0;
    double range = 30.0;
    double radius = 0.0; // metres: the lamp's size (soft shadows); 0 a point
};

struct ViewSpec {
    std::string name;
    std::string probes;             // what the view is for (one line)
    int width = 1280, height = 720; // pixels
    double fovYDegrees = 60.0;
    double zNear = 0.5, zFar = 500.0;
    double eyeX = 0.0, eyeZ = 0.0;
    double eyeHeight = 1.8;      // metres above the ground under the eye
    double azimuthDegrees = 0.0; // compass direction of the view (conventions.h)
    double pitchDegrees = 0.0;   // positive looks up
    double sunElevationDegrees = 45.0;
    double sunAzimuthFromViewDegrees = 90.0;
    bool sun = true; // false: night, lit by `lights` alone ("sun": false)
    // The sun's angular diameter in degrees, [0, 20] ("sun_angle"; the real sun 0.53). Unset: the
    // front end's (--sun-angle); the standard views leave it unset (the seeds' point-like sun).
    std::optional<double> sunAngleDegrees;
    std::vector<ViewLight> lights;
};

struct ResolvedView {
    core::PerspectiveCamera camera;
    core::DirectionalLight light;
    int width = 0, height = 0; // the picture; the camera's aspect is width / height (setSize)
    bool sun = true;
    std::vector<core::PointLight> points; // the view's local lights in the world
    std::vector<core::SpotLight> spots;
    // Exponential fog for this scene, 1/m: the forest's 0.002 (e^-1 at its views' 500 m far
    // plane), or for a framed scene e^-0.3 at its far plane, whatever its size: a model metres
    // wide is not fogged away, a county-sized one keeps its depth cue.
    double fogDensity = 0.002;
    bool framed = false; // the camera frames the scene's bounds (a scene without a heightfield); front ends say so
    // Framed, the part of the scene the camera frames where a few vertices (a ground, a backdrop)
    // reach far beyond the rest (framing.h, framedBounds); front ends say so. Empty: the bounds.
    core::Aabb framedPart;
    // Along a camera path that frames the scene: the box every frame of it frames (camera_path.h,
    // framedOverPath), found once before the first frame. Empty: each frame frames the scene as
    // it stands then.
    core::Aabb pathFramedBox;
    // The sun's angular diameter in degrees at this moment, when the view ("sun_angle") or a
    // camera path's sun keys ("angle") give one; it then takes the place of the front end's
    // (--sun-angle, gl::RenderSettings::sunAngleDegrees): frame::FrameDriver draws the frame with it.
    std::optional<double> sunAngleDegrees;

    // Another picture size (a front end's --size): the camera's aspect follows it, so the view
    // widens or narrows around the same eye, direction and vertical field of view — a framed
    // scene keeps the framing its own size gave. A size without its aspect draws the view
    // stretched (measure::Measurer refuses it).
    void setSize(int newWidth, int newHeight) {
        width = newWidth, height = newHeight;
        camera.aspect = double(width) / double(height);
    }
    // Another direction (a front end's --dir), the up kept — but for a direction along it (--dir
    // 0,-1,0: straight down), where the up is taken square to the new direction from the one the
    // view looked along, so the picture's top faces where the view looked (resolveView's rule for
    // a view straight down).
    void lookAlong(const core::Vec3& wsDirection);
};

// Reads a views file; errors name the file and the offending entry or field.
core::Result<std::vector<ViewSpec>> loadViews(const std::filesystem::path& file);
// The view of that name, or an error listing the names there are.
core::Result<ViewSpec> findView(const std::vector<ViewSpec>& views, const std::string& name);
// Places the eye over the scene's ground and turns angles into camera and sun.
// The view in this scene. A scene with a heightfield (the forest) stands the eye at the view's
// place above the ground. A scene without one (a loaded file: no ground to stand on, any size)
// is framed instead: the camera looks at the centre of the scene's bounds along the view's
// compass direction, from above at the view's pitch or 30° down if that is steeper, back just
// far enough for every corner of the bounds to be in the picture (5 % margin), with near and
// far planes around the box; the sun keeps its angles to the view, local lights stand around
// the centre as they stood around the eye, and the fog scales with the scene.
ResolvedView resolveView(const ViewSpec& view, const Scene& scene);

// The view a loaded file brings (`--view file`, file_view.cpp): its camera `which` — empty for
// the first, a number for its index in scene.cameras, else its name — lit by its own lights: its
// first directional light the sun (none: night where it has spot or point lights, else the
// standard views' default sun, 45° up and 90° right of the camera), its point and spot lights the
// view's local lights, at most `maxLocalLights` of each kind, those of unlimited range reaching
// the whole scene. The picture 1280 wide at the camera's aspect (1280 × 720 where it gives none);
// the near and far planes the file's, tightened to the scene's box where they leave room. An
// error says why there is no such view (no camera, none of that name, one facing away from the
// scene); `said`, when given, gets one line on what was used.
// The file's sun: its first directional light (`--sun file`), or nothing where it has none.
std::optional<core::DirectionalLight> fileSunOf(const Scene& scene);

core::Result<ResolvedView> fileView(const Scene& scene, const std::string& which, int maxLocalLights,
                                    std::string* said = nullptr);

} // namespace shadowkit::scene
