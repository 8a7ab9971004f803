// Output conventions: every combination of clip depth range, reversed-Z and texture origin
// gives the default convention's lookup transformed by the documented flip, what the engine
// draws is what it looks up, and the culling planes keep every receiver and caster.
#include "setup_configs.h"
#include "shadowkit/core/output_conventions.h"

#include <gtest/gtest.h>

#include <random>

using namespace shadowkit::core;

namespace {

struct RandomInputs : shadowkit::core::testing::RandomSource {
    RandomInputs() : RandomSource(1123) {}
    ShadowSetupInputs inputs() {
        ShadowSetupInputs in;
        in.wsSceneBounds = Aabb::fromMinMax(Vec3(-400, 0, -400), Vec3(400, 40, 400));
        in.camera.wsEye = Vec3(uniform(-300, 300), uniform(1, 60), uniform(-300, 300));
        in.camera.wsDirection = unit();
        in.camera.wsUp = std::abs(in.camera.wsDirection.y) < 0.95 ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
        in.camera.fovYDegrees = uniform(20, 100);
        in.camera.zNear = uniform(0.1, 1);
        in.camera.zFar = uniform(50, 600);
        Vec3 l = unit();
        l.y = -std::abs(l.y) - 0.05;
        in.light = DirectionalLight{glm::normalize(l)};
        in.cascades.warp = uniform(0, 1) < 0.5 ? CascadeWarp::Lispsm : CascadeWarp::None;
        return in;
    }
};

// Points each map must serve: B's vertices (receivers) and points between them and the sun
// inside the scene box (casters).
std::vector<Vec3> receiversAndCasters(const ShadowSetup& setup, const ShadowSetupInputs& in, RandomInputs& random) {
    std::vector<Vec3> points;
    for (const Vec3& p : setup.body.vertices()) {
        points.push_back(p);
        const Vec3 towardsSun = -glm::normalize(in.light.wsDirection);
        const double reach = (in.wsSceneBounds.max.y - p.y) / towardsSun.y; // to the box's top
        if (reach > 0.0) points.push_back(p + random.uniform(0, 1) * reach * towardsSun);
    }
    return points;
}

struct Lookup {
    double u, v, d;
};
Lookup lookUp(const EngineShadowView& view, const Vec3& p) {
    const Vec4 t = view.textureFromWorld * Vec4(p, 1.0);
    return {t.x / t.w, t.y / t.w, referenceDepth(view, p)};
}

} // namespace

TEST(OutputConventionsTest, EveryConventionIsTheDefaultLookupUnderTheDocumentedFlip) {
    RandomInputs random;
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
        ShadowSetupInputs in = random.inputs();
        for (const TechniqueInfo& info : allTechniques()) {
            in.technique = info.technique;
            const Result<ShadowSetup> setup = computeShadowSetup(in);
            ASSERT_TRUE(setup) << setup.error();
            if (info.technique == Technique::Standard || info.technique == Technique::Csm || setup->body.isEmpty())
                continue;
            const ShadowView& core = setup->views[0];
            const EngineShadowView reference = toEngineView(core, *setup, OutputConventions{});
            const std::vector<Vec3> points = receiversAndCasters(*setup, in, random);
            for (ClipDepthRange range : {ClipDepthRange::ZeroToOne, ClipDepthRange::MinusOneToOne})
                for (bool reversed : {false, true})
                    for (TextureOrigin origin : {TextureOrigin::BottomLeft, TextureOrigin::TopLeft}) {
                        const OutputConventions conventions{range, reversed, origin};
                        const EngineShadowView view = toEngineView(core, *setup, conventions);
                        for (const Vec3& p : points) {
                            const Lookup a = lookUp(reference, p), b = lookUp(view, p);
                            // The default is the core's convention: u, v = ndc · 0.5 + 0.5.
                            const Vec4 cs = core.clipFromWorld * Vec4(p, 1.0);
                            ASSERT_NEAR(a.u, 0.5 * cs.x / cs.w + 0.5, 1e-9);
                            ASSERT_NEAR(b.u, a.u, 1e-9) << info.name;
                            ASSERT_NEAR(b.v, origin == TextureOrigin::TopLeft ? 1.0 - a.v : a.v, 1e-9) << info.name;
                            ASSERT_NEAR(b.d, reversed ? 1.0 - a.d : a.d, 1e-9) << info.name;
                            // What the rasteriser stores from the engine's clip matrix is the reference
                            // depth the lookup compares with (Hyperbolic maps store clip depth).
                            if (setup->depthLayout != DepthLayout::Hyperbolic) continue;
                            const Vec4 drawn = view.clipFromWorld * Vec4(p, 1.0);
                            const double ndcZ = drawn.z / drawn.w;
                            const double stored = range == ClipDepthRange::ZeroToOne ? ndcZ : 0.5 * ndcZ + 0.5;
                            ASSERT_NEAR(stored, b.d, 1e-9) << info.name;
                            ASSERT_NEAR(drawn.x / drawn.w, cs.x / cs.w, 1e-12); // x and y rows untouched
                            ++checked;
                        }
                    }
        }
    }
    EXPECT_GT(checked, 10000);
}

TEST(OutputConventionsTest, ClipConversionMapsTheLightsNearAndFarPlanes) {
    auto ndcOf = [](const OutputConventions& c, double coreDepth) {
        const Vec4 v = clipConversion(c) * Vec4(0.3, -0.2, 2.0 * coreDepth, 2.0); // w = 2
        return v.z / v.w;
    };
    EXPECT_DOUBLE_EQ(ndcOf(OutputConventions::openGL(), 0.0), -1.0);
    EXPECT_DOUBLE_EQ(ndcOf(OutputConventions::openGL(), 1.0), 1.0);
    EXPECT_DOUBLE_EQ(ndcOf({ClipDepthRange::ZeroToOne, true}, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(ndcOf({ClipDepthRange::ZeroToOne, true}, 1.0), 0.0);
    EXPECT_DOUBLE_EQ(ndcOf({ClipDepthRange::MinusOneToOne, true}, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(ndcOf({ClipDepthRange::MinusOneToOne, true}, 1.0), -1.0);
    EXPECT_DOUBLE_EQ(ndcOf(OutputConventions::vulkan(), 0.25), 0.25);
}

TEST(OutputConventionsTest, CullingPlanesKeepReceiversAndCastersAndDropWhatIsBesideTheMap) {
    RandomInputs random;
    for (int i = 0; i < 300; ++i) {
        ShadowSetupInputs in = random.inputs();
        for (const TechniqueInfo& info : allTechniques()) {
            in.technique = info.technique;
            const Result<ShadowSetup> setup = computeShadowSetup(in);
            ASSERT_TRUE(setup);
            if (info.technique == Technique::Csm || setup->body.isEmpty()) continue;
            const EngineShadowView view = toEngineView(setup->views[0], *setup, OutputConventions::direct3D());
            EXPECT_EQ(view.wsCullingPlanes.size(), setup->depthClamp ? 5u : 6u);
            const double size = glm::length(in.wsSceneBounds.max - in.wsSceneBounds.min);
            for (const Vec3& p : receiversAndCasters(*setup, in, random))
                for (const Plane& plane : view.wsCullingPlanes)
                    ASSERT_LE(plane.signedDistance(p), 1e-6 * size) << info.name;
            // Far beside the map, perpendicular to the light: culled by a side plane.
            const Vec3 l = glm::normalize(in.light.wsDirection);
            const Vec3 side = glm::normalize(glm::cross(l, std::abs(l.y) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0)));
            const Vec3 beside = setup->body.vertices()[0] + 100.0 * size * side;
            bool culled = false;
            for (const Plane& plane : view.wsCullingPlanes) culled = culled || plane.signedDistance(beside) > 0.0;
            EXPECT_TRUE(culled) << info.name;
        }
    }
}

TEST(OutputConventionsTest, TexelSizeIsTheMapExtentOverItsTexelsForAUniformMap) {
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-500, 0, -500), Vec3(500, 20, 500));
    in.light = DirectionalLight::fromSunAngles(40, 120).value();
    in.technique = Technique::Focused;
    in.mapSize = 1024;
    const ShadowSetup setup = computeShadowSetup(in).value();
    const Mat4& clipFromLight = setup.views[0].clipFromLight;
    // An orthographic map spans 2 / m[0][0] by 2 / m[1][1] metres across its texels; the size on
    // the plane facing the light is the geometric mean of the two.
    const double expected = std::sqrt((2.0 / clipFromLight[0][0]) * (2.0 / clipFromLight[1][1])) / in.mapSize;
    for (const Vec3& p : setup.body.vertices())
        EXPECT_NEAR(wsTexelSize(setup.views[0].clipFromWorld, in.mapSize, in.light.wsDirection, p), expected,
                    1e-9 * expected);

    // A warped map spends its texels near the viewer: smaller texels at the near plane than at the far.
    in.technique = Technique::Lispsm;
    in.light = DirectionalLight::fromSunAngles(30, 90).value(); // perpendicular to the view along -Z
    const ShadowSetup warped = computeShadowSetup(in).value();
    const Vec3 wsNear = in.camera.wsEye + in.camera.zNear * glm::normalize(in.camera.wsDirection);
    const Vec3 wsFar = in.camera.wsEye + 0.9 * in.camera.zFar * glm::normalize(in.camera.wsDirection);
    EXPECT_LT(5.0 * wsTexelSize(warped.views[0].clipFromWorld, in.mapSize, in.light.wsDirection, wsNear),
              wsTexelSize(warped.views[0].clipFromWorld, in.mapSize, in.light.wsDirection, wsFar));
}
