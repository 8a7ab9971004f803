// The C API gives what the C++ API gives for the same inputs, value for value: the sun's set-ups and
// the local lights'.
#include "shadowkit/shadowkit_c.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/light_size.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/output_conventions.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace shadowkit::core;

namespace {

void copy(const Mat4& m, double out[16]) { std::memcpy(out, &m[0][0], 16 * sizeof(double)); }
void copy(const Vec3& v, double out[3]) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }
void expectEqual(const Mat4& m, const double c[16], const char* what) {
    for (int i = 0; i < 16; ++i) ASSERT_EQ((&m[0][0])[i], c[i]) << what << " element " << i;
}

} // namespace

TEST(CApiTest, GivesTheCppResultsForTheSameInputs) {
    std::mt19937 rng(2026);
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    for (int i = 0; i < 400; ++i) {
        shadowkit_inputs c;
        shadowkit_default_inputs(&c);
        ShadowSetupInputs cpp;
        EXPECT_EQ(c.technique, static_cast<int>(cpp.technique));

        cpp.wsSceneBounds = Aabb::fromMinMax(Vec3(-uniform(50, 500), 0, -uniform(50, 500)),
                                             Vec3(uniform(50, 500), uniform(5, 40), uniform(50, 500)));
        copy(cpp.wsSceneBounds.min, c.scene_min);
        copy(cpp.wsSceneBounds.max, c.scene_max);
        const Vec3 light(uniform(-1, 1), uniform(-1, -0.1), uniform(-1, 1)); // not unit: the C API normalises
        copy(light, c.light_direction);
        cpp.light = DirectionalLight{glm::normalize(light)};
        c.technique = static_cast<int>(rng() % 6);
        cpp.technique = static_cast<Technique>(c.technique);
        c.cascade_count = cpp.cascades.count = 1 + static_cast<int>(rng() % 8);
        c.cascade_lispsm = static_cast<int>(rng() % 2);
        cpp.cascades.warp = c.cascade_lispsm ? CascadeWarp::Lispsm : CascadeWarp::None;
        c.map_size = cpp.mapSize = 1024;

        PerspectiveCamera camera;
        camera.wsEye = Vec3(uniform(-40, 40), uniform(1, 30), uniform(-40, 40));
        camera.wsDirection = glm::normalize(Vec3(uniform(-1, 1), uniform(-0.6, 0.2), uniform(-1, 1)));
        camera.fovYDegrees = uniform(30, 90);
        camera.zFar = uniform(80, 400);
        if (i % 2 == 0) { // the engine's matrices, reversed infinite [0, 1] with a shadow distance
            c.camera.use_matrices = 1;
            // Reversed infinite: clip z = near, w = -z, so depth = near / distance.
            Mat4 projection = glm::infinitePerspectiveRH(glm::radians(camera.fovYDegrees), camera.aspect, camera.zNear);
            projection[2][2] = 0.0, projection[3][2] = camera.zNear;
            copy(camera.viewFromWorld(), c.camera.view_from_world);
            copy(projection, c.camera.clip_from_view);
            c.camera.shadow_distance = camera.zFar;
            cpp.camera = cameraFromMatrices({camera.viewFromWorld(), projection, ClipDepthRange::ZeroToOne,
                                             ViewHandedness::RightHanded, camera.zFar})
                             .value();
        } else {
            c.camera.use_matrices = 0;
            copy(camera.wsEye, c.camera.eye);
            copy(camera.wsDirection, c.camera.direction);
            c.camera.fov_y_degrees = camera.fovYDegrees;
            c.camera.z_far = camera.zFar;
            cpp.camera = camera;
        }
        c.clip_depth = static_cast<int>(rng() % 2);
        c.reversed_z = static_cast<int>(rng() % 2);
        c.texture_origin = static_cast<int>(rng() % 2);
        c.sun_angle_degrees = i % 3 == 0 ? 0.0 : uniform(0.0, 5.0);
        const OutputConventions conventions{c.clip_depth ? ClipDepthRange::MinusOneToOne : ClipDepthRange::ZeroToOne,
                                            c.reversed_z != 0,
                                            c.texture_origin ? TextureOrigin::TopLeft : TextureOrigin::BottomLeft};

        shadowkit_setup out;
        char error[256];
        ASSERT_EQ(shadowkit_compute_setup(&c, &out, error, sizeof error), 0) << error;
        const ShadowSetup setup = computeShadowSetup(cpp).value();
        ASSERT_EQ(out.view_count, static_cast<int>(setup.views.size()));
        EXPECT_EQ(out.depth_layout,
                  setup.depthLayout == DepthLayout::Linear ? SHADOWKIT_DEPTH_LINEAR : SHADOWKIT_DEPTH_HYPERBOLIC);
        const BiasSettings bias = recommendedBias(setup.technique, setup.depthLayout);
        EXPECT_EQ(out.bias.slope, bias.slope);
        EXPECT_EQ(out.bias.normal_offset, bias.normalOffset);
        EXPECT_EQ(out.bias.normal_offset_footprint, bias.normalOffsetFootprint);
        EXPECT_EQ(out.bias.offset_guard != 0, bias.offsetGuard);
        EXPECT_EQ(out.light_tan_half_angle, tanAngularRadius(c.sun_angle_degrees));
        for (size_t v = 0; v < setup.views.size(); ++v) {
            const EngineShadowView view = toEngineView(setup.views[v], setup, conventions);
            expectEqual(view.clipFromWorld, out.views[v].clip_from_world, "clip_from_world");
            expectEqual(view.textureFromWorld, out.views[v].texture_from_world, "texture_from_world");
            expectEqual(view.textureFromEyeRelative, out.views[v].texture_from_eye_relative,
                        "texture_from_eye_relative");
            expectEqual(view.clipFromEyeRelative, out.views[v].clip_from_eye_relative, "clip_from_eye_relative");
            for (int k = 0; k < 3; ++k) ASSERT_EQ(out.eye_relative_origin[k], setup.wsEye[k]);
            ASSERT_EQ(out.views[v].culling_plane_count, static_cast<int>(view.wsCullingPlanes.size()));
            ASSERT_EQ(out.views[v].culling_planes[2][3], view.wsCullingPlanes[2].d);
            const double point[3] = {camera.wsEye.x, 0.0, camera.wsEye.z};
            ASSERT_EQ(shadowkit_texel_size(&out.views[v], 1024, c.light_direction, point),
                      wsTexelSize(view.clipFromWorld, 1024, light, Vec3(point[0], point[1], point[2])));
            ASSERT_EQ(
                shadowkit_penumbra_texels_per_metre(&out.views[v], 1024, c.light_direction, c.sun_angle_degrees, point),
                penumbraTexelsPerMetre(view.clipFromWorld, 1024, light, c.sun_angle_degrees,
                                       Vec3(point[0], point[1], point[2])));
        }
    }
}

TEST(CApiTest, BadInputGivesTheCppMessageAndLeavesTheOutputAlone) {
    shadowkit_inputs in;
    shadowkit_default_inputs(&in);
    in.scene_max[0] = in.scene_max[1] = in.scene_max[2] = 10.0;
    in.camera.use_matrices = 1;
    in.camera.clip_from_view[3] = 0.5; // w depends on x
    shadowkit_setup out;
    out.view_count = -7;
    char error[256];
    ASSERT_NE(shadowkit_compute_setup(&in, &out, error, sizeof error), 0);
    EXPECT_EQ(out.view_count, -7);
    EngineCamera engine;
    std::memcpy(&engine.clipFromView[0][0], in.camera.clip_from_view, sizeof in.camera.clip_from_view);
    std::memcpy(&engine.viewFromWorld[0][0], in.camera.view_from_world, sizeof in.camera.view_from_world);
    EXPECT_EQ(std::string(error), cameraFromMatrices(engine).error());

    char tiny[8]; // truncated, terminated
    ASSERT_NE(shadowkit_compute_setup(&in, &out, tiny, sizeof tiny), 0);
    EXPECT_EQ(std::strlen(tiny), 7u);
    in.camera.use_matrices = 0;
    in.technique = 42;
    ASSERT_NE(shadowkit_compute_setup(&in, &out, error, sizeof error), 0);
    EXPECT_NE(std::string(error).find("technique"), std::string::npos);
    in.technique = SHADOWKIT_TECHNIQUE_TSM;
    for (const double angle : {-0.5, 25.0, std::nan("")}) {
        in.sun_angle_degrees = angle;
        ASSERT_NE(shadowkit_compute_setup(&in, &out, error, sizeof error), 0) << angle;
        EXPECT_EQ(std::string(error), "sun_angle_degrees: must be in [0, 20] degrees (the sun: 0.53)");
    }
    EXPECT_EQ(out.view_count, -7);
}

namespace {

// A camera 5 m up looking north and down at a 100 m box: the lights below stand in its view.
shadowkit_local_inputs localInputs(int kind) {
    shadowkit_local_inputs in;
    shadowkit_default_local_inputs(&in);
    in.camera.use_matrices = 0;
    copy(Vec3(0, 5, 0), in.camera.eye);
    copy(Vec3(0, -0.5, 1), in.camera.direction);
    copy(Vec3(-50, 0, -50), in.scene_min);
    copy(Vec3(50, 10, 50), in.scene_max);
    in.kind = kind;
    copy(kind == SHADOWKIT_LIGHT_SPOT ? Vec3(0, 8, 15) : Vec3(0, 3, 12), in.position);
    copy(Vec3(0, -1, 0), in.direction);
    in.cone_degrees = 60.0;
    in.range = 25.0;
    in.radius = 0.05;
    return in;
}

} // namespace

// The local lights' set-ups through C: the C++ set-up's views in the asked conventions, each
// point-light view with its own cube face, and what the installed lookup needs beside them —
// the distance mapping the depth pass writes, a texel's size per metre, the recommended biases.
TEST(CApiTest, LocalLightsGiveTheCppViewsAndWhatTheLookupNeeds) {
    char error[256];
    for (const int kind : {SHADOWKIT_LIGHT_SPOT, SHADOWKIT_LIGHT_POINT})
        for (const int reversed : {0, 1}) {
            SCOPED_TRACE(std::string(kind == SHADOWKIT_LIGHT_SPOT ? "spot" : "point") +
                         (reversed ? ", reversed-Z" : ""));
            shadowkit_local_inputs in = localInputs(kind);
            in.reversed_z = reversed;
            in.clip_depth = SHADOWKIT_CLIP_DEPTH_MINUS_ONE_TO_ONE;
            shadowkit_local_setup out;
            ASSERT_EQ(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0) << error;

            PerspectiveCamera camera;
            camera.wsEye = Vec3(0, 5, 0);
            camera.wsDirection = Vec3(0, -0.5, 1);
            const LocalShadowInputs inputs{camera, Aabb::fromMinMax(Vec3(-50, 0, -50), Vec3(50, 10, 50)), 1024};
            const Vec3 wsLight(in.position[0], in.position[1], in.position[2]);
            SpotLight spot;
            spot.wsPosition = wsLight, spot.coneDegrees = 60.0, spot.range = 25.0, spot.radius = 0.05;
            PointLight point;
            point.wsPosition = wsLight, point.range = 25.0, point.radius = 0.05;
            const Result<ShadowSetup> cpp = kind == SHADOWKIT_LIGHT_SPOT ? computeSpotShadowSetup(inputs, spot)
                                                                         : computePointShadowSetup(inputs, point);
            ASSERT_TRUE(cpp) << cpp.error();
            const OutputConventions conventions{ClipDepthRange::MinusOneToOne, reversed != 0};
            ASSERT_EQ(out.view_count, static_cast<int>(cpp->views.size()));
            // A point light inside the view frustum skips no face: the frustum surrounds it.
            EXPECT_EQ(out.view_count, kind == SHADOWKIT_LIGHT_SPOT ? 1 : 6);
            int facesSeen = 0;
            for (int i = 0; i < out.view_count; ++i) {
                const EngineShadowView view = toEngineView(cpp->views[static_cast<size_t>(i)], *cpp, conventions);
                expectEqual(view.clipFromWorld, out.views[i].clip_from_world, "clip_from_world");
                expectEqual(view.textureFromWorld, out.views[i].texture_from_world, "texture_from_world");
                EXPECT_EQ(out.faces[i], cpp->views[static_cast<size_t>(i)].face.value_or(0));
                facesSeen |= 1 << out.faces[i];
            }
            if (kind == SHADOWKIT_LIGHT_POINT) {
                EXPECT_EQ(facesSeen, 0x3f) << "each cube face once";
            }
            EXPECT_EQ(out.depth_clamp, cpp->depthClamp);
            EXPECT_EQ(out.light_position[1], wsLight.y);
            EXPECT_EQ(out.radius, 0.05);

            // The spot's map sees the ground under it: (u, v) of the point below the lamp inside.
            if (kind == SHADOWKIT_LIGHT_SPOT) {
                Mat4 textureFromWorld;
                std::memcpy(&textureFromWorld[0][0], out.views[0].texture_from_world, sizeof textureFromWorld);
                const Vec4 t = textureFromWorld * Vec4(0, 0, 15, 1);
                for (const double uv : {t.x / t.w, t.y / t.w}) {
                    EXPECT_GT(uv, 0.0);
                    EXPECT_LT(uv, 1.0);
                }
            } else {
                EXPECT_NEAR(out.texel_per_metre, 2.0 / 1024.0, 1e-12) << "a 90° face's texel per metre";
            }
            // Stored = distance · x + y: the light's own point stores its near side, its range the far.
            const double atLight = out.stored_from_distance[1];
            const double atRange = 25.0 * out.stored_from_distance[0] + out.stored_from_distance[1];
            EXPECT_NEAR(atLight, reversed ? 1.0 : 0.0, 1e-15);
            EXPECT_NEAR(atRange, reversed ? 0.0 : 1.0, 1e-15);
            EXPECT_EQ(out.texel_per_metre, texelSizePerMetre(cpp->views[0], 1024));
            const LocalBias bias;
            EXPECT_EQ(out.bias.slope_texels, bias.slopeTexels);
            EXPECT_EQ(out.bias.normal_offset_texels, bias.normalOffsetTexels);
            EXPECT_EQ(out.bias.constant_metres, bias.constantMetres);
        }
}

TEST(CApiTest, APointLightInOneMapIsTheCppOneMapDrawnAsASpot) {
    // Outside the view (behind the eye, above): one map, the C++ set-up's, its kind a spot's.
    char error[256];
    shadowkit_local_inputs in = localInputs(SHADOWKIT_LIGHT_POINT_ONE_MAP);
    copy(Vec3(0, 9, -6), in.position);
    in.clip_depth = SHADOWKIT_CLIP_DEPTH_MINUS_ONE_TO_ONE;
    shadowkit_local_setup out;
    ASSERT_EQ(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0) << error;
    EXPECT_EQ(out.kind, SHADOWKIT_LIGHT_SPOT);
    ASSERT_EQ(out.view_count, 1);
    PerspectiveCamera camera;
    camera.wsEye = Vec3(0, 5, 0);
    camera.wsDirection = Vec3(0, -0.5, 1);
    const LocalShadowInputs inputs{camera, Aabb::fromMinMax(Vec3(-50, 0, -50), Vec3(50, 10, 50)), 1024};
    const Result<ShadowSetup> cpp =
        computePointSingleMapSetup(inputs, PointLight{.wsPosition = Vec3(0, 9, -6), .range = 25.0, .radius = 0.05});
    ASSERT_TRUE(cpp) << cpp.error();
    const OutputConventions conventions{ClipDepthRange::MinusOneToOne, false};
    expectEqual(toEngineView(cpp->views[0], *cpp, conventions).clipFromWorld, out.views[0].clip_from_world,
                "clip_from_world");
    EXPECT_EQ(out.texel_per_metre, texelSizePerMetre(cpp->views[0], 1024));
    // Among what the camera sees: refused, named as shadowkit_local_inputs spells it.
    in = localInputs(SHADOWKIT_LIGHT_POINT_ONE_MAP); // 3 m up, 12 m ahead of the eye
    out.view_count = -7;
    EXPECT_NE(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0);
    EXPECT_EQ(std::string(error).rfind("position: ", 0), 0u) << error;
    EXPECT_EQ(out.view_count, -7);
}

TEST(CApiTest, APointLightInAnAimedMapIsTheCppOneMapWhereThereIsOneAndTheAimedOneAmongTheView) {
    PerspectiveCamera camera;
    camera.wsEye = Vec3(0, 5, 0);
    camera.wsDirection = Vec3(0, -0.5, 1);
    const LocalShadowInputs inputs{camera, Aabb::fromMinMax(Vec3(-50, 0, -50), Vec3(50, 10, 50)), 1024};
    const OutputConventions conventions{ClipDepthRange::ZeroToOne, false};
    char error[256];
    // Behind and above the eye: the single map, all of the view in reach held. Among what the
    // camera sees (3 m up, 12 m ahead), where ONE_MAP is refused: the C++ 170° aimed map.
    for (const Vec3& wsLamp : {Vec3(0, 9, -6), Vec3(0, 3, 12)}) {
        shadowkit_local_inputs in = localInputs(SHADOWKIT_LIGHT_POINT_AIMED_MAP);
        copy(wsLamp, in.position);
        in.clip_depth = SHADOWKIT_CLIP_DEPTH_ZERO_TO_ONE;
        shadowkit_local_setup out;
        ASSERT_EQ(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0) << error;
        const PointLight point{.wsPosition = wsLamp, .range = 25.0, .radius = 0.05};
        const Result<ShadowSetup> single = computePointSingleMapSetup(inputs, point);
        const Result<ShadowSetup> cpp = single ? single : computePointAimedMapSetup(inputs, point);
        ASSERT_TRUE(cpp) << cpp.error();
        EXPECT_EQ(out.kind, SHADOWKIT_LIGHT_SPOT);
        ASSERT_EQ(out.view_count, 1);
        EXPECT_EQ(out.holds_part_of_view, single ? 0 : 1);
        expectEqual(toEngineView(cpp->views[0], *cpp, conventions).clipFromWorld, out.views[0].clip_from_world,
                    "clip_from_world");
    }
    // Bad input is refused as ONE_MAP refuses it.
    shadowkit_local_inputs in = localInputs(SHADOWKIT_LIGHT_POINT_AIMED_MAP);
    in.range = -1.0;
    shadowkit_local_setup out;
    EXPECT_NE(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0);
    EXPECT_EQ(std::string(error), "range: must be a finite number of metres > 0");
}

TEST(CApiTest, BadLocalInputNamesTheInputAndLeavesTheOutputAlone) {
    shadowkit_local_setup out;
    out.view_count = -7;
    char error[256];
    auto refused = [&](const shadowkit_local_inputs& in) {
        EXPECT_NE(shadowkit_compute_local_setup(&in, &out, error, sizeof error), 0);
        return std::string(error);
    };
    shadowkit_local_inputs in = localInputs(SHADOWKIT_LIGHT_SPOT);
    in.kind = 7;
    EXPECT_NE(refused(in).find("kind"), std::string::npos);
    in = localInputs(SHADOWKIT_LIGHT_SPOT);
    in.cone_degrees = 180.0;
    // Named as shadowkit_local_inputs spells them, not as the C++ structs do.
    EXPECT_EQ(refused(in), "cone_degrees: must be in (0, 170] degrees");
    in = localInputs(SHADOWKIT_LIGHT_SPOT);
    in.direction[0] = in.direction[1] = in.direction[2] = 0.0;
    EXPECT_EQ(refused(in).rfind("direction: ", 0), 0u) << error;
    in = localInputs(SHADOWKIT_LIGHT_POINT);
    in.range = 0.0;
    EXPECT_EQ(refused(in), "range: must be a finite number of metres > 0");
    in = localInputs(SHADOWKIT_LIGHT_POINT);
    in.radius = in.range;
    EXPECT_EQ(refused(in), "radius: must be in [0, range) metres");
    in = localInputs(SHADOWKIT_LIGHT_POINT);
    in.map_size = 3;
    EXPECT_NE(refused(in).find("map_size"), std::string::npos);
    EXPECT_NE(shadowkit_compute_local_setup(nullptr, &out, error, sizeof error), 0);
    EXPECT_EQ(out.view_count, -7);
}
