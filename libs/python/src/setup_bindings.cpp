// shadowkit.setup(...): the core's set-up from Python, matrices as NumPy arrays.
//
// NumPy arrays are indexed [row, column] as in the maths (M @ p transforms a column vector p);
// glm stores [column][row], so every matrix is transposed on the way out and in.
#include "bindings.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/light_size.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/output_conventions.h"

#include <pybind11/stl.h>

#include <string>
#include <string_view>

namespace shadowkit::python {

using namespace core;

py::array_t<double> toNumpy(const Mat4& m) {
    py::array_t<double> out({4, 4});
    auto a = out.mutable_unchecked<2>();
    for (py::ssize_t r = 0; r < 4; ++r)
        for (py::ssize_t c = 0; c < 4; ++c) a(r, c) = m[static_cast<int>(c)][static_cast<int>(r)];
    return out;
}

Mat4 toMat4(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* name) {
    if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
        throw py::value_error(std::string(name) + ": must be a 4 x 4 array");
    auto v = a.unchecked<2>();
    Mat4 m;
    for (py::ssize_t r = 0; r < 4; ++r)
        for (py::ssize_t c = 0; c < 4; ++c) m[static_cast<int>(c)][static_cast<int>(r)] = v(r, c);
    return m;
}

Vec3 toVec3(const std::vector<double>& v, const char* name) {
    if (v.size() != 3) throw py::value_error(std::string(name) + ": must have 3 components");
    return {v[0], v[1], v[2]};
}

namespace {

// Parses a name of the core's; raises ValueError listing the accepted ones.
template <class Parse>
auto parseOrRaise(const std::string& text, const char* name, const std::string& accepted, Parse parse) {
    const auto value = parse(text);
    if (!value) throw py::value_error(std::string(name) + ": '" + text + "' is not one of " + accepted);
    return *value;
}

OutputConventions conventionsFor(const std::string& name, bool reversedZ) {
    OutputConventions c;
    if (name == "opengl")
        c = OutputConventions::openGL();
    else if (name == "vulkan" || name == "default")
        c = OutputConventions::vulkan();
    else if (name == "direct3d" || name == "metal")
        c = OutputConventions::direct3D();
    else
        throw py::value_error("conventions: '" + name + "' is not one of default, opengl, vulkan, direct3d, metal");
    c.reversedZ = reversedZ;
    return c;
}

py::dict viewDict(const ShadowView& core, const EngineShadowView& view) {
    py::dict d;
    d["clip_from_world"] = toNumpy(view.clipFromWorld);
    d["texture_from_world"] = toNumpy(view.textureFromWorld);
    d["light_from_world"] = toNumpy(core.lightFromWorld);
    d["clip_from_light"] = toNumpy(core.clipFromLight);
    py::array_t<double> row(4);
    for (py::ssize_t i = 0; i < 4; ++i) row.mutable_at(i) = view.linearDepthFromWorld[static_cast<int>(i)];
    d["linear_depth_from_world"] = row;
    d["clip_from_eye_relative"] = toNumpy(view.clipFromEyeRelative);
    d["texture_from_eye_relative"] = toNumpy(view.textureFromEyeRelative);
    py::array_t<double> relativeRow(4);
    for (py::ssize_t i = 0; i < 4; ++i)
        relativeRow.mutable_at(i) = view.linearDepthFromEyeRelative[static_cast<int>(i)];
    d["linear_depth_from_eye_relative"] = relativeRow;
    py::array_t<double> planes({static_cast<py::ssize_t>(view.wsCullingPlanes.size()), py::ssize_t(4)});
    for (size_t p = 0; p < view.wsCullingPlanes.size(); ++p) {
        const Plane& plane = view.wsCullingPlanes[p];
        const auto i = static_cast<py::ssize_t>(p);
        planes.mutable_at(i, 0) = plane.normal.x, planes.mutable_at(i, 1) = plane.normal.y;
        planes.mutable_at(i, 2) = plane.normal.z, planes.mutable_at(i, 3) = plane.d;
    }
    d["culling_planes"] = planes;
    d["split"] = core.split ? py::object(py::make_tuple(core.split->x, core.split->y)) : py::object(py::none());
    return d;
}

// The camera of setup's keyword arguments: the engine's matrices, or eye, direction and frustum.
PerspectiveCamera cameraOf(const SetupArguments& a) {
    if (a.viewFromWorld || a.clipFromView) {
        if (!a.viewFromWorld || !a.clipFromView)
            throw py::value_error("view_from_world and clip_from_view: give both or neither");
        EngineCamera engine{toMat4(*a.viewFromWorld, "view_from_world"), toMat4(*a.clipFromView, "clip_from_view")};
        if (a.clipDepth == "minus_one_to_one")
            engine.clipDepth = ClipDepthRange::MinusOneToOne;
        else if (a.clipDepth != "zero_to_one")
            throw py::value_error("clip_depth: must be zero_to_one or minus_one_to_one");
        engine.handedness = a.leftHanded ? ViewHandedness::LeftHanded : ViewHandedness::RightHanded;
        if (a.shadowDistance) engine.shadowDistance = *a.shadowDistance;
        return check(cameraFromMatrices(engine));
    }
    PerspectiveCamera camera;
    camera.wsEye = toVec3(a.eye, "eye");
    camera.wsDirection = toVec3(a.direction, "direction");
    camera.wsUp = toVec3(a.up, "up");
    camera.fovYDegrees = a.fovYDegrees;
    camera.aspect = a.aspect;
    camera.zNear = a.zNear;
    camera.zFar = a.shadowDistance ? std::min(a.zFar, *a.shadowDistance) : a.zFar;
    return camera;
}

} // namespace

py::dict setup(const SetupArguments& a) {
    ShadowSetupInputs in;
    in.camera = cameraOf(a);
    if (a.light)
        in.light = DirectionalLight{toVec3(*a.light, "light")};
    else
        in.light = check(DirectionalLight::fromSunAngles(a.sun.first, a.sun.second));
    in.wsSceneBounds = Aabb::fromMinMax(toVec3(a.sceneMin, "scene_min"), toVec3(a.sceneMax, "scene_max"));
    in.technique = parseOrRaise(a.technique, "technique", techniqueNameList(), parseTechnique);
    in.mapSize = a.mapSize;
    in.cascades.count = a.cascades;
    in.cascades.lambda = a.lambda;
    if (a.cascadeWarp == "lispsm")
        in.cascades.warp = CascadeWarp::Lispsm;
    else if (a.cascadeWarp != "none")
        throw py::value_error("cascade_warp: must be none or lispsm");
    check(validateSunAngle(a.sunAngle));
    const ShadowSetup s = check(computeShadowSetup(in));
    const OutputConventions conventions = conventionsFor(a.conventions, a.reversedZ);

    py::dict out;
    out["technique"] = std::string(techniqueName(s.technique));
    out["depth_layout"] = s.depthLayout == DepthLayout::Linear ? "linear" : "hyperbolic";
    out["map_size"] = s.mapSize;
    out["depth_clamp"] = s.depthClamp;
    py::list views;
    for (const ShadowView& v : s.views) views.append(viewDict(v, toEngineView(v, s, conventions)));
    out["views"] = views;
    const BiasSettings b = recommendedBias(s.technique, s.depthLayout);
    out["bias"] = py::dict(py::arg("slope") = b.slope, py::arg("constant") = b.constant,
                           py::arg("normal_offset") = b.normalOffset,
                           py::arg("normal_offset_footprint") = b.normalOffsetFootprint,
                           py::arg("receiver_plane") = b.receiverPlane, py::arg("offset_guard") = b.offsetGuard);
    out["light_tan_half_angle"] = tanAngularRadius(a.sunAngle);
    out["fallbacks"] = s.fallbacks;
    py::list body;
    for (const Vec3& p : s.body.vertices()) body.append(py::make_tuple(p.x, p.y, p.z));
    out["body"] = body;
    out["eye_relative_origin"] = py::make_tuple(s.wsEye.x, s.wsEye.y, s.wsEye.z);
    return out;
}

// The core names a light's fields as its C++ structs do ("spot.cone"); the caller wrote
// local_setup's keywords ("cone"), so the message names those.
ShadowSetup checkLight(Result<ShadowSetup> setup) {
    if (setup) return std::move(setup).value();
    Error e = setup.errorInfo();
    for (const std::string_view light : {"spot.", "point."})
        if (e.field.starts_with(light) && e.message.starts_with(e.field)) {
            const std::string keyword = e.field.substr(light.size());
            e.message = keyword + e.message.substr(e.field.size());
        }
    throw py::value_error(e.message);
}

py::dict localSetup(const LocalSetupArguments& a) {
    const LocalShadowInputs in{
        cameraOf(a.view), Aabb::fromMinMax(toVec3(a.view.sceneMin, "scene_min"), toVec3(a.view.sceneMax, "scene_max")),
        a.view.mapSize};
    ShadowSetup s;
    if (a.kind == "spot") {
        SpotLight spot;
        spot.wsPosition = toVec3(a.position, "position");
        spot.wsDirection = toVec3(a.direction, "direction");
        spot.coneDegrees = a.coneDegrees;
        spot.range = a.range;
        spot.radius = a.radius;
        s = checkLight(computeSpotShadowSetup(in, spot));
    } else if (a.kind == "point" || a.kind == "point_one_map" || a.kind == "point_aimed_map") {
        PointLight point;
        point.wsPosition = toVec3(a.position, "position");
        point.range = a.range;
        point.radius = a.radius;
        s = checkLight(a.kind == "point"           ? computePointShadowSetup(in, point)
                       : a.kind == "point_one_map" ? computePointSingleMapSetup(in, point)
                                                   : computePointSingleOrAimedMapSetup(in, point));
    } else {
        throw py::value_error("kind: '" + a.kind + "' is not one of spot, point, point_one_map, point_aimed_map");
    }
    const OutputConventions conventions = conventionsFor(a.view.conventions, a.view.reversedZ);

    py::dict out;
    out["kind"] = a.kind == "point" ? "point" : "spot"; // a point light in one map is drawn as a spot's
    out["holds_part_of_view"] = s.holdsPartOfView;
    out["map_size"] = s.mapSize;
    out["depth_clamp"] = s.depthClamp;
    py::list views;
    for (const ShadowView& v : s.views) {
        py::dict view = viewDict(v, toEngineView(v, s, conventions));
        view["face"] = v.face ? py::object(py::int_(*v.face)) : py::object(py::none());
        views.append(view);
    }
    out["views"] = views;
    out["skipped_faces"] = s.skippedFaces;
    out["light_position"] = py::make_tuple(s.wsLightPosition.x, s.wsLightPosition.y, s.wsLightPosition.z);
    const Vec2 mapping = storedFromDistance(a.range, conventions.reversedZ);
    out["stored_from_distance"] = py::make_tuple(mapping.x, mapping.y);
    out["texel_per_metre"] = s.views.empty() ? 0.0 : texelSizePerMetre(s.views[0], s.mapSize);
    out["radius"] = a.radius;
    const LocalBias b;
    out["bias"] =
        py::dict(py::arg("slope_texels") = b.slopeTexels, py::arg("normal_offset_texels") = b.normalOffsetTexels,
                 py::arg("constant_metres") = b.constantMetres);
    return out;
}

} // namespace shadowkit::python
