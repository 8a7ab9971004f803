// `import shadowkit`: the core's set-ups (setup, local_setup) and the measure pipeline (Evaluator,
// evaluate) for scripted studies. Matrices are NumPy arrays indexed [row, column].
#include "bindings.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/version.h"
#include "shadowkit/frame/option_table.h"

#include <pybind11/stl.h>

namespace py = pybind11;
using shadowkit::python::SetupArguments;

PYBIND11_MODULE(_native, m) {
    m.doc() = "shadowkit: shadow-map set-ups and their error against ray-traced truth";
    m.attr("__version__") = SHADOWKIT_VERSION_STRING;

    // The one table of options (frame/option_table.h): the flag of every frame field, so a
    // keyword argument can be held to the command line's name for it.
    m.def(
        "option_flags",
        [] {
            std::vector<std::pair<std::string, std::string>> rows;
            for (const shadowkit::frame::OptionRow& row : shadowkit::frame::optionTable())
                if (!row.flag.empty()) rows.emplace_back(std::string(row.flag), std::string(row.member));
            return rows;
        },
        "Every frame option's command-line flag and the struct member it sets, as (flag, member) pairs.");

    const SetupArguments d;
    m.def(
        "setup",
        [](std::vector<double> eye, std::vector<double> direction, std::vector<double> up, double fov, double aspect,
           double zNear, double zFar,
           std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> viewFromWorld,
           std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> clipFromView,
           std::string clipDepth, bool leftHanded, std::optional<double> shadowDistance,
           std::optional<std::vector<double>> light, std::pair<double, double> sun, std::vector<double> sceneMin,
           std::vector<double> sceneMax, std::string technique, int mapSize, int cascades, double lambda,
           std::string cascadeWarp, std::string conventions, bool reversedZ, double sunAngle) {
            return shadowkit::python::setup(
                {eye,      direction,     up,           fov,         aspect,     zNear,
                 zFar,     viewFromWorld, clipFromView, clipDepth,   leftHanded, shadowDistance,
                 light,    sun,           sceneMin,     sceneMax,    technique,  mapSize,
                 cascades, lambda,        cascadeWarp,  conventions, reversedZ,  sunAngle});
        },
        R"(The shadow set-up for a camera, the sun and the scene's bounds.

Camera: eye, direction, up, fov (vertical, degrees), aspect, near, far -- or the engine's own
view_from_world and clip_from_view (4 x 4, [row, column]) with clip_depth ('zero_to_one' or
'minus_one_to_one'), left_handed (orthographic only), reversed-Z and infinite far recognised.
shadow_distance ends shadows before the far plane (required with an infinite far plane).
Sun: light (the direction sunlight travels) or sun=(elevation, azimuth) in degrees;
sun_angle its angular diameter in degrees ([0, 20], the real sun 0.53; 0 a point).
technique: standard, focused, lispsm, psm, tsm, csm; cascades, lambda, cascade_warp ('none',
'lispsm') for csm. conventions: 'default' (= 'vulkan': clip depth [0, 1], v up), 'opengl',
'direct3d'/'metal'; reversed_z.

Returns a dict: technique, depth_layout, map_size, depth_clamp, bias (the recommended one),
light_tan_half_angle (tan of sun_angle / 2: the GLSL's lightTanHalfAngle for PCSS),
fallbacks, body (the focus body's points) and views, each with clip_from_world,
texture_from_world, light_from_world, clip_from_light, linear_depth_from_world,
culling_planes (k x 4: n, d; outside where n.p + d > 0), split, and for camera-relative
rendering clip_from_eye_relative, texture_from_eye_relative and linear_depth_from_eye_relative
(taking p - eye_relative_origin, the camera's eye). Raises ValueError with the
core's message for bad input.)",
        py::kw_only(), py::arg("eye") = d.eye, py::arg("direction") = d.direction, py::arg("up") = d.up,
        py::arg("fov") = d.fovYDegrees, py::arg("aspect") = d.aspect, py::arg("near") = d.zNear,
        py::arg("far") = d.zFar, py::arg("view_from_world") = py::none(), py::arg("clip_from_view") = py::none(),
        py::arg("clip_depth") = d.clipDepth, py::arg("left_handed") = d.leftHanded,
        py::arg("shadow_distance") = py::none(), py::arg("light") = py::none(), py::arg("sun") = d.sun,
        py::arg("scene_min") = d.sceneMin, py::arg("scene_max") = d.sceneMax, py::arg("technique") = d.technique,
        py::arg("map_size") = d.mapSize, py::arg("cascades") = d.cascades, py::arg("lambda_") = d.lambda,
        py::arg("cascade_warp") = d.cascadeWarp, py::arg("conventions") = d.conventions,
        py::arg("reversed_z") = d.reversedZ, py::arg("sun_angle") = d.sunAngle);

    // A spot or point light's maps: the camera and box arguments as setup's.
    const shadowkit::python::LocalSetupArguments l;
    m.def(
        "local_setup",
        [](std::string kind, std::vector<double> position, std::vector<double> direction, double cone, double range,
           double radius, std::vector<double> eye, std::vector<double> viewDirection, std::vector<double> up,
           double fov, double aspect, double zNear, double zFar,
           std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> viewFromWorld,
           std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> clipFromView,
           std::string clipDepth, bool leftHanded, std::optional<double> shadowDistance, std::vector<double> sceneMin,
           std::vector<double> sceneMax, int mapSize, std::string conventions, bool reversedZ) {
            shadowkit::python::LocalSetupArguments a;
            a.kind = kind, a.position = position, a.direction = direction;
            a.coneDegrees = cone, a.range = range, a.radius = radius;
            shadowkit::python::SetupArguments& v = a.view;
            v.eye = eye, v.direction = viewDirection, v.up = up, v.fovYDegrees = fov, v.aspect = aspect;
            v.zNear = zNear, v.zFar = zFar, v.viewFromWorld = viewFromWorld, v.clipFromView = clipFromView;
            v.clipDepth = clipDepth, v.leftHanded = leftHanded, v.shadowDistance = shadowDistance;
            v.sceneMin = sceneMin, v.sceneMax = sceneMax, v.mapSize = mapSize;
            v.conventions = conventions, v.reversedZ = reversedZ;
            return shadowkit::python::localSetup(a);
        },
        R"(A spot or point light's shadow maps (core/local_lights.h, seed 003), for the installed
glsl/shadowkit_local_shadows.glsl.

Light: kind ('spot', 'point', 'point_one_map': a point light in one map for engines without
cube maps, the narrowest cone over what the camera sees in its range, refused where that spans more
than 170 degrees, or 'point_aimed_map': that map, or where it is refused a 170-degree cone aimed at
the middle of what the camera sees in range, holds_part_of_view then True), position, direction and cone (the spot's axis and full opening angle in
degrees), range (metres: nothing farther is lit), radius (the lamp's sphere for PCSS; 0 a point).
Camera, scene box and conventions as setup's: view_direction is the camera's direction.

Returns a dict: kind (the maps': 'spot' for a point light in one map), holds_part_of_view
(an aimed map: receivers outside its cone get no shadow from this light), map_size, depth_clamp, views (a spot's one, or the cube faces that see
something of the camera's view), each as setup's views with its cube face (0-5, OpenGL's order;
None for a spot); skipped_faces; and what the lookup takes beside them: light_position,
stored_from_distance (the depth pass writes distance * [0] + [1]: 1 / range and 0, reversed
-1 / range and 1), texel_per_metre, radius and bias (slope_texels, normal_offset_texels,
constant_metres). Raises ValueError with the core's message for bad input.)",
        py::kw_only(), py::arg("kind") = l.kind, py::arg("position") = l.position, py::arg("direction") = l.direction,
        py::arg("cone") = l.coneDegrees, py::arg("range") = l.range, py::arg("radius") = l.radius,
        py::arg("eye") = d.eye, py::arg("view_direction") = d.direction, py::arg("up") = d.up,
        py::arg("fov") = d.fovYDegrees, py::arg("aspect") = d.aspect, py::arg("near") = d.zNear,
        py::arg("far") = d.zFar, py::arg("view_from_world") = py::none(), py::arg("clip_from_view") = py::none(),
        py::arg("clip_depth") = d.clipDepth, py::arg("left_handed") = d.leftHanded,
        py::arg("shadow_distance") = py::none(), py::arg("scene_min") = d.sceneMin, py::arg("scene_max") = d.sceneMax,
        py::arg("map_size") = shadowkit::core::LocalShadowInputs{}.mapSize, py::arg("conventions") = d.conventions,
        py::arg("reversed_z") = d.reversedZ);

    shadowkit::python::bindEvaluation(m);
}
