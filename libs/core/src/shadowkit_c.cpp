// The C API (shadowkit_c.h): converts plain structs to the C++ inputs and back, nothing more.
#include "shadowkit/shadowkit_c.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/light_size.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/output_conventions.h"
#include "shadowkit/core/version.h"

#include <algorithm>
#include <cstring>
#include <string_view>
#include <utility>

using namespace shadowkit::core;

namespace {

Vec3 toVec3(const double v[3]) { return {v[0], v[1], v[2]}; }
void store(const Vec3& v, double out[3]) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }
Mat4 toMat4(const double m[16]) {
    Mat4 r;
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) r[c][row] = m[c * 4 + row];
    return r;
}
void store(const Mat4& m, double out[16]) {
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) out[c * 4 + row] = m[c][row];
}

void writeError(const std::string& message, char* error, size_t size) {
    if (!error || size == 0) return;
    const size_t n = std::min(message.size(), size - 1);
    std::memcpy(error, message.data(), n);
    error[n] = '\0';
}

// The core names a light's fields as its C++ structs do ("spot.cone"); a C caller set
// shadowkit_local_inputs's, so the message names those ("cone_degrees").
std::string inLocalInputsSpelling(const Error& e) {
    static constexpr std::pair<std::string_view, std::string_view> kNames[] = {
        {"spot.position", "position"}, {"spot.direction", "direction"}, {"spot.cone", "cone_degrees"},
        {"spot.range", "range"},       {"spot.radius", "radius"},       {"point.position", "position"},
        {"point.range", "range"},      {"point.radius", "radius"}};
    for (const auto& [cpp, c] : kNames)
        if (e.field == cpp && e.message.starts_with(cpp)) return std::string(c) + e.message.substr(cpp.size());
    return e.message;
}

Result<PerspectiveCamera> toCamera(const shadowkit_camera& c) {
    if (!c.use_matrices) {
        PerspectiveCamera camera;
        camera.wsEye = toVec3(c.eye);
        camera.wsDirection = toVec3(c.direction);
        camera.wsUp = toVec3(c.up);
        camera.fovYDegrees = c.fov_y_degrees;
        camera.aspect = c.aspect;
        camera.zNear = c.z_near;
        camera.zFar = c.shadow_distance > 0.0 ? std::min(c.z_far, c.shadow_distance) : c.z_far;
        return camera;
    }
    EngineCamera engine;
    engine.viewFromWorld = toMat4(c.view_from_world);
    engine.clipFromView = toMat4(c.clip_from_view);
    engine.clipDepth = c.clip_depth == SHADOWKIT_CLIP_DEPTH_MINUS_ONE_TO_ONE ? ClipDepthRange::MinusOneToOne
                                                                             : ClipDepthRange::ZeroToOne;
    engine.handedness = c.left_handed ? ViewHandedness::LeftHanded : ViewHandedness::RightHanded;
    if (c.shadow_distance > 0.0) engine.shadowDistance = c.shadow_distance;
    return cameraFromMatrices(engine);
}

OutputConventions toConventions(int clipDepth, int reversedZ, int textureOrigin) {
    return {clipDepth == SHADOWKIT_CLIP_DEPTH_MINUS_ONE_TO_ONE ? ClipDepthRange::MinusOneToOne
                                                               : ClipDepthRange::ZeroToOne,
            reversedZ != 0,
            textureOrigin == SHADOWKIT_TEXTURE_ORIGIN_TOP_LEFT ? TextureOrigin::TopLeft : TextureOrigin::BottomLeft};
}

SpotLight toSpot(const shadowkit_local_inputs& in) {
    SpotLight spot;
    spot.wsPosition = toVec3(in.position);
    spot.wsDirection = toVec3(in.direction);
    spot.coneDegrees = in.cone_degrees;
    spot.range = in.range;
    spot.radius = in.radius;
    return spot;
}
PointLight toPoint(const shadowkit_local_inputs& in) {
    PointLight point;
    point.wsPosition = toVec3(in.position);
    point.range = in.range;
    point.radius = in.radius;
    return point;
}

void store(const EngineShadowView& view, shadowkit_view& o) {
    store(view.clipFromWorld, o.clip_from_world);
    store(view.textureFromWorld, o.texture_from_world);
    for (int k = 0; k < 4; ++k) o.linear_depth_from_world[k] = view.linearDepthFromWorld[k];
    store(view.clipFromEyeRelative, o.clip_from_eye_relative);
    store(view.textureFromEyeRelative, o.texture_from_eye_relative);
    for (int k = 0; k < 4; ++k) o.linear_depth_from_eye_relative[k] = view.linearDepthFromEyeRelative[k];
    o.culling_plane_count = static_cast<int>(view.wsCullingPlanes.size());
    for (size_t p = 0; p < view.wsCullingPlanes.size(); ++p) {
        store(view.wsCullingPlanes[p].normal, o.culling_planes[p]);
        o.culling_planes[p][3] = view.wsCullingPlanes[p].d;
    }
    if (view.split) o.split_near = view.split->x, o.split_far = view.split->y;
}

} // namespace

extern "C" {

void shadowkit_default_inputs(shadowkit_inputs* in) {
    *in = shadowkit_inputs{};
    const ShadowSetupInputs defaults;
    const PerspectiveCamera& camera = defaults.camera;
    store(camera.wsEye, in->camera.eye);
    store(camera.wsDirection, in->camera.direction);
    store(camera.wsUp, in->camera.up);
    in->camera.fov_y_degrees = camera.fovYDegrees;
    in->camera.aspect = camera.aspect;
    in->camera.z_near = camera.zNear;
    in->camera.z_far = camera.zFar;
    store(camera.viewFromWorld(), in->camera.view_from_world);
    store(camera.clipFromView(), in->camera.clip_from_view);
    store(defaults.light.wsDirection, in->light_direction);
    in->technique = static_cast<int>(defaults.technique);
    in->map_size = defaults.mapSize;
    in->cascade_count = defaults.cascades.count;
    in->cascade_lambda = defaults.cascades.lambda;
    in->cascade_blend_band = defaults.cascades.blendBand;
}

int shadowkit_compute_setup(const shadowkit_inputs* in, shadowkit_setup* out, char* error, size_t errorSize) {
    if (!in || !out) {
        writeError("shadowkit_compute_setup: inputs and out must not be null", error, errorSize);
        return 1;
    }
    Result<PerspectiveCamera> camera = toCamera(in->camera);
    if (!camera) {
        writeError(camera.error(), error, errorSize);
        return 1;
    }
    if (in->technique < SHADOWKIT_TECHNIQUE_STANDARD || in->technique > SHADOWKIT_TECHNIQUE_CSM) {
        writeError("technique: must be one of the shadowkit_technique values (0 to 5)", error, errorSize);
        return 1;
    }
    if (const Status s = validateSunAngle(in->sun_angle_degrees); !s) {
        const Error& e = s.errorInfo(); // "sun_angle: ...", in the C struct's own spelling
        writeError("sun_angle_degrees" + e.message.substr(e.field.size()), error, errorSize);
        return 1;
    }
    ShadowSetupInputs inputs;
    inputs.camera = *camera;
    // Any non-zero length (the C++ struct wants a unit vector); a zero or NaN one stays so and is
    // refused by validation, naming light_direction.
    const Vec3 light = toVec3(in->light_direction);
    inputs.light = DirectionalLight{glm::length(light) > 0.0 ? glm::normalize(light) : light};
    inputs.wsSceneBounds = Aabb::fromMinMax(toVec3(in->scene_min), toVec3(in->scene_max));
    inputs.technique = static_cast<Technique>(in->technique);
    inputs.mapSize = in->map_size;
    inputs.cascades.count = in->cascade_count;
    inputs.cascades.lambda = in->cascade_lambda;
    inputs.cascades.warp = in->cascade_lispsm ? CascadeWarp::Lispsm : CascadeWarp::None;
    inputs.cascades.blendBand = in->cascade_blend_band;
    const Result<ShadowSetup> setup = computeShadowSetup(inputs);
    if (!setup) {
        writeError(setup.error(), error, errorSize);
        return 1;
    }

    const OutputConventions conventions = toConventions(in->clip_depth, in->reversed_z, in->texture_origin);
    *out = shadowkit_setup{};
    out->technique = static_cast<int>(setup->technique);
    out->map_size = setup->mapSize;
    out->depth_layout = setup->depthLayout == DepthLayout::Linear ? SHADOWKIT_DEPTH_LINEAR : SHADOWKIT_DEPTH_HYPERBOLIC;
    out->depth_clamp = setup->depthClamp;
    out->view_count = static_cast<int>(setup->views.size());
    for (size_t i = 0; i < setup->views.size(); ++i)
        store(toEngineView(setup->views[i], *setup, conventions), out->views[i]);
    const BiasSettings bias = recommendedBias(setup->technique, setup->depthLayout);
    out->bias = {bias.slope,      bias.constant, bias.normalOffset, bias.receiverPlane, bias.normalOffsetFootprint,
                 bias.offsetGuard};
    store(setup->wsEye, out->eye_relative_origin);
    out->fallback_count = static_cast<int>(setup->fallbacks.size());
    out->light_tan_half_angle = tanAngularRadius(in->sun_angle_degrees);
    return 0;
}

void shadowkit_default_local_inputs(shadowkit_local_inputs* in) {
    *in = shadowkit_local_inputs{};
    shadowkit_inputs sun;
    shadowkit_default_inputs(&sun);
    in->camera = sun.camera;
    const SpotLight spot;
    const LocalShadowInputs defaults;
    in->map_size = defaults.mapSize;
    in->kind = SHADOWKIT_LIGHT_SPOT;
    store(spot.wsPosition, in->position);
    store(spot.wsDirection, in->direction);
    in->cone_degrees = spot.coneDegrees;
    in->range = spot.range;
    in->radius = spot.radius;
}

int shadowkit_compute_local_setup(const shadowkit_local_inputs* in, shadowkit_local_setup* out, char* error,
                                  size_t errorSize) {
    if (!in || !out) {
        writeError("shadowkit_compute_local_setup: inputs and out must not be null", error, errorSize);
        return 1;
    }
    if (in->kind != SHADOWKIT_LIGHT_SPOT && in->kind != SHADOWKIT_LIGHT_POINT &&
        in->kind != SHADOWKIT_LIGHT_POINT_ONE_MAP && in->kind != SHADOWKIT_LIGHT_POINT_AIMED_MAP) {
        writeError("kind: must be SHADOWKIT_LIGHT_SPOT (0), SHADOWKIT_LIGHT_POINT (1), "
                   "SHADOWKIT_LIGHT_POINT_ONE_MAP (2) or SHADOWKIT_LIGHT_POINT_AIMED_MAP (3)",
                   error, errorSize);
        return 1;
    }
    Result<PerspectiveCamera> camera = toCamera(in->camera);
    if (!camera) {
        writeError(camera.error(), error, errorSize);
        return 1;
    }
    const LocalShadowInputs inputs{*camera, Aabb::fromMinMax(toVec3(in->scene_min), toVec3(in->scene_max)),
                                   in->map_size};
    const Result<ShadowSetup> setup = [&] {
        switch (in->kind) {
        case SHADOWKIT_LIGHT_SPOT:
            return computeSpotShadowSetup(inputs, toSpot(*in));
        case SHADOWKIT_LIGHT_POINT:
            return computePointShadowSetup(inputs, toPoint(*in));
        case SHADOWKIT_LIGHT_POINT_ONE_MAP:
            return computePointSingleMapSetup(inputs, toPoint(*in));
        default:
            return computePointSingleOrAimedMapSetup(inputs, toPoint(*in));
        }
    }();
    if (!setup) {
        writeError(inLocalInputsSpelling(setup.errorInfo()), error, errorSize);
        return 1;
    }

    const OutputConventions conventions = toConventions(in->clip_depth, in->reversed_z, in->texture_origin);
    *out = shadowkit_local_setup{};
    out->kind = in->kind == SHADOWKIT_LIGHT_POINT ? SHADOWKIT_LIGHT_POINT : SHADOWKIT_LIGHT_SPOT; // one map: a spot's
    out->map_size = setup->mapSize;
    out->depth_clamp = setup->depthClamp;
    out->view_count = static_cast<int>(setup->views.size());
    for (size_t i = 0; i < setup->views.size(); ++i) {
        store(toEngineView(setup->views[i], *setup, conventions), out->views[i]);
        out->faces[i] = setup->views[i].face.value_or(0);
    }
    store(setup->wsLightPosition, out->light_position);
    const Vec2 mapping = storedFromDistance(in->range, conventions.reversedZ);
    out->stored_from_distance[0] = mapping.x, out->stored_from_distance[1] = mapping.y;
    out->texel_per_metre = setup->views.empty() ? 0.0 : texelSizePerMetre(setup->views[0], setup->mapSize);
    out->radius = in->radius;
    const LocalBias bias;
    out->bias = {bias.slopeTexels, bias.normalOffsetTexels, bias.constantMetres};
    out->holds_part_of_view = setup->holdsPartOfView;
    return 0;
}

double shadowkit_texel_size(const shadowkit_view* view, int mapSize, const double lightDirection[3],
                            const double point[3]) {
    return wsTexelSize(toMat4(view->clip_from_world), mapSize, toVec3(lightDirection), toVec3(point));
}

double shadowkit_penumbra_texels_per_metre(const shadowkit_view* view, int mapSize, const double lightDirection[3],
                                           double sunAngleDegrees, const double point[3]) {
    if (!validateSunAngle(sunAngleDegrees)) return 0.0;
    return penumbraTexelsPerMetre(toMat4(view->clip_from_world), mapSize, toVec3(lightDirection), sunAngleDegrees,
                                  toVec3(point));
}

const char* shadowkit_version_string(void) { return SHADOWKIT_VERSION_STRING; }

} // extern "C"
