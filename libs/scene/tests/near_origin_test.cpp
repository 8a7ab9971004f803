// A model in survey metres (UTM, national grids: 5e5–1e7 m out) loads where its file puts it,
// to the millimetre, with every float the renderer gets near zero (near_origin.cpp), and an
// export writes it back where it was.
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// Where the tests' model stands: a UTM easting and northing, with millimetres. A float there
// steps by 0.03 m (x) and 0.5 m (z).
const glm::dvec3 kSurvey(512345.678, 20.25, 5412345.321);

// A little model with millimetre detail, in the model's own metres: a sloped quad and a spike.
const std::vector<glm::dvec3> kSurveyModel = {{0, 0, 0},         {0.001, 0, 0.002}, {4, 0.5, 0},
                                              {4.003, 0.5, 3.5}, {0, 0, 3.5},       {2, 7.25, 1.75}};
constexpr const char* kSurveyModelFaces = "f 1 5 4 3\nf 1 2 6\nf 2 3 6\nf 3 4 6\nf 4 5 6\n";

// Every vertex the full meshes' triangles use, in world coordinates, in double.
std::vector<glm::dvec3> worldVertices(const Scene& s) {
    std::vector<glm::dvec3> out;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject)
            for (uint32_t i : s.meshes[batch.mesh].indices)
                out.push_back(s.wsOrigin +
                              glm::dvec3(glm::dmat4(m) * glm::dvec4(s.meshes[batch.mesh].vertices[i].position, 1.0)));
    return out;
}

// Each expected point has a loaded vertex within `tolerance` metres, and each loaded vertex an
// expected point.
void expectSamePoints(const std::vector<glm::dvec3>& loaded, const std::vector<glm::dvec3>& expected, double tolerance,
                      const std::string& where) {
    const auto nearest = [](const glm::dvec3& p, const std::vector<glm::dvec3>& among) {
        double best = INFINITY;
        for (const glm::dvec3& q : among) best = std::min(best, glm::length(p - q));
        return best;
    };
    for (const glm::dvec3& p : expected) EXPECT_LE(nearest(p, loaded), tolerance) << where << ": a file vertex lost";
    for (const glm::dvec3& p : loaded) EXPECT_LE(nearest(p, expected), tolerance) << where << ": a vertex moved";
}

// What the renderer and the ray tracer get: every scene coordinate within 16 model sizes of the
// scene's origin, where float keeps 2e-6 of the model.
void expectFloatsNearZero(const Scene& s, const std::string& where) {
    const core::Aabb local = s.localBounds();
    ASSERT_FALSE(local.isEmpty()) << where;
    EXPECT_LE(std::max(glm::length(local.min), glm::length(local.max)), 17.0 * local.diagonal()) << where;
    for (const Mesh& mesh : s.meshes)
        EXPECT_LE(glm::length(mesh.osBounds.center()), 17.0 * mesh.osBounds.diagonal() + 1.0)
            << where << " " << mesh.name;
}

// The model as an OBJ's text, at `at`.
std::string surveyObj(const glm::dvec3& at) {
    std::ostringstream out;
    out.precision(17);
    for (const glm::dvec3& p : kSurveyModel)
        out << "v " << at.x + p.x << ' ' << at.y + p.y << ' ' << at.z + p.z << '\n';
    out << kSurveyModelFaces;
    return out.str();
}

std::vector<glm::dvec3> modelAt(const glm::dvec3& at) {
    std::vector<glm::dvec3> out;
    for (const glm::dvec3& p : kSurveyModel) out.push_back(at + p);
    return out;
}

} // namespace

// Before: the OBJ's positions became floats as they were read, and the 5.4e6 m northing moved
// every vertex by up to a quarter of a metre.
TEST(NearOriginTest, AnObjInSurveyMetresKeepsItsMillimetres) {
    const auto loaded = scene::testing::loadWritten("shadowkit_survey.obj", surveyObj(kSurvey));
    ASSERT_TRUE(loaded) << loaded.error();
    expectSamePoints(worldVertices(*loaded), modelAt(kSurvey), 1e-4, "survey OBJ");
    expectFloatsNearZero(*loaded, "survey OBJ");
    EXPECT_GT(glm::length(loaded->wsOrigin), 5e6); // it stands out there, in the world's coordinates

    // Near the origin nothing moves: the scene's coordinates are the file's.
    const auto nearScene = scene::testing::loadWritten("shadowkit_near.obj", surveyObj(glm::dvec3(3, 0, -2)));
    ASSERT_TRUE(nearScene) << nearScene.error();
    EXPECT_EQ(nearScene->wsOrigin, core::Vec3(0.0));
    expectSamePoints(worldVertices(*nearScene), modelAt(glm::dvec3(3, 0, -2)), 1e-6, "near OBJ");
}

// A glTF's nodes are composed in double (before: in float, a 0.03–0.5 m step out there), and a
// mesh whose own float32 vertices lie far out is moved to its origin without losing a bit.
TEST(NearOriginTest, GltfNodesAndVerticesFarOutStandWhereTheFileSays) {
    // Mesh 0: a unit triangle, placed by two nodes 100 m apart out there (one instanced batch).
    // Mesh 1: a triangle whose float32 vertices are themselves far out, under no node transform.
    const float far[] = {512345.5f, 1.25f, 5412345.0f, 512347.0f, 1.25f, 5412345.0f, 512345.5f, 1.25f, 5412346.5f};
    std::vector<unsigned char> buffer(36 + sizeof far);
    const float unit[] = {0, 0, 0, 1, 0, 0, 0, 0, -1};
    std::memcpy(buffer.data(), unit, 36);
    std::memcpy(buffer.data() + 36, far, sizeof far);
    std::ostringstream text;
    text.precision(17);
    text << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],"nodes":[)"
         << R"({"mesh":0,"translation":[)" << kSurvey.x << ',' << kSurvey.y << ',' << kSurvey.z << "]},"
         << R"({"mesh":0,"translation":[)" << kSurvey.x + 100 << ',' << kSurvey.y << ',' << kSurvey.z << "]},"
         << R"({"mesh":1}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]},)"
         << R"({"primitives":[{"attributes":{"POSITION":1}}]}],"accessors":[)"
         << R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,0,0]},)"
         << R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC3",)"
         << R"("min":[512345.5,1.25,5412345.0],"max":[512347.0,1.25,5412346.5]}],)"
         << R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36}],)"
         << R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)"
         << scene::testing::base64(buffer) << "\"}]}";
    const auto loaded = scene::testing::loadWritten("shadowkit_survey.gltf", text.str());
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_EQ(loaded->batches.size(), 2u);
    EXPECT_EQ(loaded->batches[0].worldFromObject.size(), 2u); // still one instanced batch
    std::vector<glm::dvec3> expected;
    for (const double dx : {0.0, 100.0})
        for (int v = 0; v < 3; ++v)
            expected.push_back(kSurvey + glm::dvec3(dx, 0, 0) +
                               glm::dvec3(unit[3 * v], unit[3 * v + 1], unit[3 * v + 2]));
    for (int v = 0; v < 3; ++v) expected.emplace_back(far[3 * v], far[3 * v + 1], far[3 * v + 2]);
    expectSamePoints(worldVertices(*loaded), expected, 1e-5, "survey glTF"); // float 50 m from the origin: 4e-6
    expectFloatsNearZero(*loaded, "survey glTF");
}

// An export writes world coordinates: a .glb puts the batches under a node at the scene's
// origin (double in its JSON), an OBJ adds the origin to every vertex in double. Before, both
// wrote the scene's own coordinates, and the model came back at the world's origin.
TEST(NearOriginTest, AnExportedSceneFarOutLoadsBackWhereItWas) {
    const auto loaded = scene::testing::loadWritten("shadowkit_survey_source.obj", surveyObj(kSurvey));
    ASSERT_TRUE(loaded) << loaded.error();
    for (const char* name : {"shadowkit_survey_export.glb", "shadowkit_survey_export.obj"}) {
        const auto file = shadowkit::test_support::scratchDir() / name;
        ASSERT_TRUE(exportScene(*loaded, file)) << name;
        const auto back = loadScene(file);
        std::filesystem::remove(file);
        ASSERT_TRUE(back) << back.error();
        // The OBJ writes 0.1 mm (%.4f); the glb's vertices are the scene's floats, placed in double.
        expectSamePoints(worldVertices(*back), modelAt(kSurvey), 1e-4, name);
        expectFloatsNearZero(*back, name);
    }
}
