// A z-up file (CAD, GIS, photogrammetry: easting, northing, height) loaded with its up axis
// stands as the same model written y-up does, to the bit; loaded y-up, an OBJ that looks z-up
// says so (up_axis.cpp).
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

using namespace shadowkit;
using namespace shadowkit::scene;

namespace {

// A ground 40 × 30 m with a 4 m box on it and a mast, y-up, in the model's own metres; its
// outward faces counter-clockwise.
std::vector<glm::dvec3> groundAndBox() {
    return {{-20, 0, -15}, {-20, 0, 15}, {20, 0, 15},  {20, 0, -15}, // ground, facing +y
            {-2, 4, -2},   {-2, 4, 2},   {2, 4, 2},    {2, 4, -2},   // roof, facing +y
            {-2, 0, 2},    {2, 0, 2},    {2, 4, 2},    {-2, 4, 2},   // +z wall
            {2, 0, -2},    {-2, 0, -2},  {-2, 4, -2},  {2, 4, -2},   // -z wall
            {2, 0, 2},     {2, 0, -2},   {2, 4, -2},   {2, 4, 2},    // +x wall
            {-2, 0, -2},   {-2, 0, 2},   {-2, 4, 2},   {-2, 4, -2},  // -x wall
            {9, 0, 5},     {9.2, 0, 5},  {9.2, 11, 5}, {9, 11, 5}};  // a mast's face, facing +z
}

// The model as an OBJ's text, each point written through `written` (its file's axes), at `at`
// (file coordinates).
std::string upAxisObj(glm::dvec3 (*written)(const glm::dvec3&), const glm::dvec3& at = glm::dvec3(0.0)) {
    std::ostringstream out;
    out.precision(17);
    const std::vector<glm::dvec3> points = groundAndBox();
    for (const glm::dvec3& p : points) {
        const glm::dvec3 q = at + written(p);
        out << "v " << q.x << ' ' << q.y << ' ' << q.z << '\n';
    }
    for (size_t quad = 0; quad < points.size() / 4; ++quad) {
        const size_t v = 4 * quad + 1;
        out << "f " << v << ' ' << v + 1 << ' ' << v + 2 << ' ' << v + 3 << '\n';
    }
    return out.str();
}

glm::dvec3 asYUp(const glm::dvec3& p) { return p; }
glm::dvec3 asZUp(const glm::dvec3& p) { return {p.x, -p.z, p.y}; } // shadowkit's (x, y, z) written (x, −z, y)

Scene loadUp(const std::string& name, const std::string& text, UpAxis up) {
    auto scene = scene::testing::loadWritten(name, text, {.up = up});
    EXPECT_TRUE(scene) << scene.error();
    return scene ? std::move(*scene) : Scene{};
}

// Every placed vertex and normal of the full meshes, in world coordinates.
std::vector<std::pair<glm::dvec3, glm::vec3>> placedVertices(const Scene& s) {
    std::vector<std::pair<glm::dvec3, glm::vec3>> out;
    for (const MeshBatch& batch : s.batches)
        for (const glm::mat4& m : batch.worldFromObject)
            for (uint32_t i : s.meshes[batch.mesh].indices) {
                const Vertex& v = s.meshes[batch.mesh].vertices[i];
                out.emplace_back(s.wsOrigin + glm::dvec3(m * glm::vec4(v.position, 1.0f)),
                                 glm::normalize(glm::mat3(m) * v.normal));
            }
    return out;
}

} // namespace

TEST(UpAxisTest, AZUpFileLoadedZUpStandsAsTheSameModelWrittenYUpToTheBit) {
    for (const glm::dvec3& at : {glm::dvec3(0.0), glm::dvec3(512345.678, 5412345.321, 231.5)}) {
        const std::string where = "at " + std::to_string(at.x);
        // The same place in both files: the z-up file's (E, N, H) is the y-up one's (E, H, −N).
        const Scene zUp = loadUp("shadowkit_zup.obj", upAxisObj(asZUp, at), UpAxis::Z);
        const Scene yUp = loadUp("shadowkit_yup.obj", upAxisObj(asYUp, glm::dvec3(at.x, at.z, -at.y)), UpAxis::Y);
        EXPECT_TRUE(zUp.warnings.empty()) << where;
        EXPECT_TRUE(yUp.warnings.empty()) << where;
        EXPECT_EQ(zUp.wsOrigin, yUp.wsOrigin) << where;
        const auto a = placedVertices(zUp), b = placedVertices(yUp);
        ASSERT_EQ(a.size(), b.size()) << where;
        for (size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(a[i].first, b[i].first) << where << ", vertex " << i;
            EXPECT_EQ(a[i].second, b[i].second) << where << ", vertex " << i;
        }
        // The ground faces up (+y), not the side, and in the mesh's own space too.
        EXPECT_GT(zUp.meshes[0].vertices[0].normal.y, 0.99f) << where;
        EXPECT_NEAR(zUp.wsBounds().extent().y, 11.0, 1e-3) << where; // the mast's height
    }
}

TEST(UpAxisTest, AnObjThatLooksZUpLoadedYUpSaysSoAndOneThatDoesNotIsQuiet) {
    const Scene lying = loadUp("shadowkit_lying.obj", upAxisObj(asZUp), UpAxis::Y);
    ASSERT_EQ(lying.warnings.size(), 1u);
    EXPECT_NE(lying.warnings[0].find("shadowkit_lying.obj: its ground faces +z"), std::string::npos)
        << lying.warnings[0];
    EXPECT_NE(lying.warnings[0].find("--scene-up z"), std::string::npos) << lying.warnings[0];
    EXPECT_TRUE(loadUp("shadowkit_upright.obj", upAxisObj(asYUp), UpAxis::Y).warnings.empty());

    // A closed box alone (no ground, as any solid model) cannot say which way is up: quiet.
    EXPECT_TRUE(loadUp("shadowkit_box.obj",
                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
                       UpAxis::Y)
                    .warnings.empty());
}
