#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {
std::vector<ViewSpec> standardViews() {
    auto views = loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    EXPECT_TRUE(views) << views.error();
    return views ? *views : std::vector<ViewSpec>{};
}
core::Vec3 horizontal(core::Vec3 v) { return glm::normalize(core::Vec3(v.x, 0, v.z)); }
} // namespace

TEST(ViewsTest, StandardViewsFileHoldsTheEvaluationViews) {
    const auto views = standardViews();
    for (const char* name : {"paper", "perpendicular", "into-sun", "sun-behind", "noon", "aerial"})
        EXPECT_TRUE(findView(views, name)) << name;
}

TEST(ViewsTest, ResolvedViewsPutTheEyeAboveTheGroundAndTheSunWhereTheTableSays) {
    ForestOptions o;
    o.trees = 0;
    o.terrainResolution = 64;
    const Scene forest = makeForest(o);
    const auto views = standardViews();

    const ResolvedView paper = resolveView(*findView(views, "paper"), forest);
    EXPECT_NEAR(paper.camera.wsEye.y, forest.terrain->heightAt(0, 0) + 1.8, 1e-9);
    EXPECT_EQ(paper.width, 512);
    // Sun at 90° azimuth from the view: horizontally perpendicular, 45° up.
    EXPECT_NEAR(glm::dot(horizontal(paper.light.wsDirection), horizontal(paper.camera.wsDirection)), 0.0, 1e-9);
    EXPECT_NEAR(std::asin(-paper.light.wsDirection.y), glm::radians(45.0), 1e-9);

    const ResolvedView intoSun = resolveView(*findView(views, "into-sun"), forest);
    EXPECT_NEAR(glm::dot(horizontal(intoSun.light.wsDirection), horizontal(intoSun.camera.wsDirection)), -1.0, 1e-9);
    const ResolvedView behind = resolveView(*findView(views, "sun-behind"), forest);
    EXPECT_NEAR(glm::dot(horizontal(behind.light.wsDirection), horizontal(behind.camera.wsDirection)), 1.0, 1e-9);
    const ResolvedView aerial = resolveView(*findView(views, "aerial"), forest);
    EXPECT_NEAR(std::asin(aerial.camera.wsDirection.y), glm::radians(-35.0), 1e-9);
    EXPECT_TRUE(aerial.camera.validate());
}

TEST(ViewsTest, UnknownViewListsTheKnownOnes) {
    const auto r = findView(standardViews(), "sideways");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("sideways"), std::string::npos);
    EXPECT_NE(r.error().find("perpendicular"), std::string::npos);
}

TEST(ViewsTest, MalformedFilesNameTheFileAndTheProblem) {
    const auto dir = shadowkit::test_support::scratchDir();
    const auto bad = dir / "shadowkit_views_bad.json";
    std::ofstream(bad) << R"({"views": [{"name": "x", "near": 10, "far": 1}]})";
    auto r = loadViews(bad);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("shadowkit_views_bad.json"), std::string::npos);
    EXPECT_NE(r.error().find("near"), std::string::npos);
    std::ofstream(bad) << "{ not json";
    EXPECT_NE(loadViews(bad).error().find("not valid JSON"), std::string::npos);
    EXPECT_FALSE(loadViews(dir / "does_not_exist_views.json"));
    // Found by fuzz_views (tools/fuzz.sh): a number JSON cannot hold ended the program through an
    // uncaught out_of_range, and a height of 3.6e20 was converted to int (undefined behaviour).
    std::ofstream(bad) << R"({"views": [{"name": "x", "fov": 8888811e488888}]})";
    EXPECT_NE(loadViews(bad).error().find("not valid JSON"), std::string::npos);
    std::ofstream(bad) << R"({"views": [{"name": "x", "height": 360000000000000000000}]})";
    EXPECT_NE(loadViews(bad).error().find("whole numbers in [1, 16384]"), std::string::npos) << loadViews(bad).error();
    // Found by fuzz_views in CI (2026-12-02): an eye 5.6e49 m up parsed, then no camera could hold it.
    std::ofstream(bad) << R"({"views": [{"name": "x", "eye_height": 5.6e49}]})";
    EXPECT_NE(loadViews(bad).error().find("eye_xz and eye_height"), std::string::npos) << loadViews(bad).error();
    std::ofstream(bad) << R"({"views": [{"name": "x", "eye_xz": [-1e14, 0]}]})";
    EXPECT_NE(loadViews(bad).error().find("eye_xz and eye_height"), std::string::npos) << loadViews(bad).error();
    std::filesystem::remove(bad);
}

// A pitch a hair short of ±90°, which the file allows, looks straight up or down: the sky's up is
// then no direction in the image, and the camera's up is its own (as fuzz_paths found for paths).
TEST(ViewsTest, AViewLookingStraightUpOrDownIsAUsableCamera) {
    ForestOptions o;
    o.trees = 0;
    o.terrainSize = 100;
    const Scene forest = makeForest(o);
    for (const double pitch : {89.99999999, -89.99999999, 89.9, -60.0}) {
        ViewSpec spec;
        spec.azimuthDegrees = 30.0;
        spec.pitchDegrees = pitch;
        const ResolvedView view = resolveView(spec, forest);
        EXPECT_TRUE(view.camera.validate()) << pitch;
        // The top of the image leans away from where the camera looks when it looks up, towards it
        // when it looks down, as with the sky's up at any other pitch.
        const core::Vec3 heading =
            horizontal(core::Vec3(std::sin(glm::radians(30.0)), 0, -std::cos(glm::radians(30.0))));
        const core::Vec3 top =
            view.camera.wsUp - view.camera.wsDirection * glm::dot(view.camera.wsUp, view.camera.wsDirection);
        EXPECT_LT(glm::dot(top, heading) * pitch, 0.0) << pitch;
    }
}

// A front end's --dir along the view's up (straight down or up) once left the sky's up in place,
// which the camera refuses: the up is then taken from where the view looked, so the picture's top
// faces that way; any other direction keeps the view's up as it is.
TEST(ViewsTest, ADirectionAlongTheViewsUpTakesItsUpFromWhereTheViewLooked) {
    ForestOptions o;
    o.trees = 0;
    o.terrainSize = 100;
    const Scene forest = makeForest(o);
    ViewSpec spec;
    spec.azimuthDegrees = 30.0;
    const ResolvedView view = resolveView(spec, forest);
    const core::Vec3 heading = horizontal(view.camera.wsDirection);
    for (const core::Vec3& along : {core::Vec3(0, -1, 0), core::Vec3(0, 3, 0), core::Vec3(1e-9, -1, 0)}) {
        ResolvedView looking = view;
        looking.lookAlong(along);
        EXPECT_EQ(looking.camera.wsDirection, along);
        EXPECT_TRUE(looking.camera.validate()) << along.y;
        EXPECT_NEAR(glm::length(looking.camera.wsUp), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(looking.camera.wsUp, heading), 1.0, 1e-6) << along.y;
    }
    ResolvedView aside = view;
    aside.lookAlong(core::Vec3(1, -1, 0));
    EXPECT_EQ(aside.camera.wsUp, view.camera.wsUp);
    // A view straight down, its top north, turned north: its top faces down, where it looked.
    ResolvedView down = view;
    down.camera.wsDirection = core::Vec3(0, -1, 0), down.camera.wsUp = core::Vec3(0, 0, -1);
    down.lookAlong(core::Vec3(0, 0, -2));
    EXPECT_TRUE(down.camera.validate());
    EXPECT_NEAR(glm::dot(down.camera.wsUp, core::Vec3(0, -1, 0)), 1.0, 1e-6);
}

TEST(ViewsTest, AViewsSunAngleReachesTheResolvedViewAndBadOnesAreErrors) {
    const auto file = shadowkit::test_support::scratchDir() / "shadowkit_views_sun_angle.json";
    std::ofstream(file) << R"({"views": [{"name": "sized", "sun_angle": 0.53}, {"name": "point"}]})";
    auto views = loadViews(file);
    ASSERT_TRUE(views) << views.error();
    ForestOptions o;
    o.trees = 0;
    o.terrainResolution = 16;
    const Scene forest = makeForest(o);
    const ResolvedView sized = resolveView(findView(*views, "sized").value(), forest);
    ASSERT_TRUE(sized.sunAngleDegrees);
    EXPECT_EQ(*sized.sunAngleDegrees, 0.53);
    // Unset stays unset: the front end's --sun-angle decides (the standard views are so).
    EXPECT_FALSE(resolveView(findView(*views, "point").value(), forest).sunAngleDegrees);
    for (const ViewSpec& v : standardViews()) EXPECT_FALSE(v.sunAngleDegrees) << v.name;

    for (const char* bad :
         {R"({"views": [{"name": "x", "sun_angle": -0.1}]})", R"({"views": [{"name": "x", "sun_angle": 25}]})"}) {
        std::ofstream(file) << bad;
        auto r = loadViews(file);
        ASSERT_FALSE(r) << bad;
        EXPECT_NE(r.error().find("sun_angle must be in [0, 20]"), std::string::npos) << r.error();
    }
    std::ofstream(file) << R"({"views": [{"name": "x", "sun_angle": "big"}]})";
    EXPECT_NE(loadViews(file).error().find("wrong type"), std::string::npos) << loadViews(file).error();
    std::filesystem::remove(file);
}

namespace {

// A 40 × 10 × 30 m model of 800 vertices (a lattice of points two by two triangles would join:
// framing reads vertices), alone or on a ground quad of 4 vertices 4 km wide (Godot's truck
// town: 12 vertices of ground 2 km each way round 100,000 of town).
Scene modelOnGround(bool withGround) {
    Scene scene;
    Mesh model;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
            for (int k = 0; k < 2; ++k)
                model.vertices.push_back({.position = {-20.0f + 40.0f * float(i) / 19.0f, 10.0f * float(k),
                                                       -15.0f + 30.0f * float(j) / 19.0f},
                                          .normal = {0, 1, 0},
                                          .albedo = {0.5f, 0.5f, 0.5f}});
    model.indices = {0, 2, 40, 2, 42, 40};
    model.computeBounds();
    scene.meshes.push_back(model);
    scene.batches.push_back({.mesh = 0, .worldFromObject = {glm::translate(glm::mat4(1.0f), {100, 0, 50})}});
    if (withGround) {
        Mesh ground;
        for (float x : {-2000.0f, 2000.0f})
            for (float z : {-2000.0f, 2000.0f})
                ground.vertices.push_back({.position = {x, 0.0f, z}, .normal = {0, 1, 0}});
        ground.indices = {0, 1, 3, 0, 3, 2};
        ground.computeBounds();
        scene.meshes.push_back(ground);
        scene.batches.push_back({.mesh = 1, .worldFromObject = {glm::mat4(1.0f)}});
    }
    return scene;
}

} // namespace

// A model on a ground kilometres wide was framed as the ground: the model a few pixels in the
// middle of it, its shadows unmeasurable. The views frame the model, tightly, as they frame it
// alone; the ground still stands under it.
TEST(ViewsTest, AModelOnAGroundKilometresWideIsFramedNotTheGround) {
    const Scene alone = modelOnGround(false), onGround = modelOnGround(true);
    const core::Aabb model = alone.wsBounds();
    for (const char* name : {"paper", "noon", "aerial"}) {
        const ViewSpec spec = *findView(standardViews(), name);
        const ResolvedView lone = resolveView(spec, alone), grounded = resolveView(spec, onGround);
        ASSERT_TRUE(lone.framed && grounded.framed) << name;
        EXPECT_TRUE(lone.framedPart.isEmpty()) << name; // the bounds themselves
        ASSERT_FALSE(grounded.framedPart.isEmpty()) << name;
        EXPECT_NEAR(grounded.framedPart.diagonal(), model.diagonal(), 0.01 * model.diagonal()) << name;
        // Every corner of the model in the picture and between the planes, one near its edge.
        const core::Mat4 clipFromWorld = grounded.camera.clipFromWorld();
        double outermost = 0.0;
        for (const core::Vec3& corner : model.corners()) {
            const glm::dvec4 clip = clipFromWorld * glm::dvec4(corner, 1.0);
            EXPECT_LE(std::abs(clip.x / clip.w), 1.0) << name;
            EXPECT_LE(std::abs(clip.y / clip.w), 1.0) << name;
            EXPECT_GE(clip.w, grounded.camera.zNear) << name;
            EXPECT_LE(clip.w, grounded.camera.zFar) << name;
            outermost = std::max({outermost, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
        }
        EXPECT_GT(outermost, 0.9) << name;
        EXPECT_LT(glm::distance(grounded.camera.wsEye, lone.camera.wsEye), 0.01 * model.diagonal()) << name;
    }
}
