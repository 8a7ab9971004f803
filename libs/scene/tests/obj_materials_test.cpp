// OBJ materials that cut their faces (obj_materials.cpp): a map_d read as a mask, right side up,
// through the channel the MTL names, found where exporters leave it, and a missing one named;
// a dissolve (d, Tr) below half read as glass, cut away whole, and a map_d multiplied by it.
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/material.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace shadowkit::scene {
namespace {

namespace fs = std::filesystem;

// An image whose rows above `splitRow` hold `top` and the rest `bottom` (RGBA each).
Image splitImage(int side, int splitRow, glm::u8vec4 top, glm::u8vec4 bottom) {
    Image image(side, side);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const glm::u8vec4 c = y < splitRow ? top : bottom;
            std::copy(&c[0], &c[0] + 4, image.pixel(x, y));
        }
    return image;
}

// A unit quad lying on the ground facing up, x from 0 to 1 and z from 0 to −1, its texture
// coordinates the OBJ's (v up: the image's last row along its near edge, z = 0, and its first
// along its far edge, z = −1), wearing material `cut`; beside it a triangle wearing `bark`, a
// plain material.
void writeCard(const fs::path& obj, const std::string& mtl) {
    std::ofstream(obj.parent_path() / "card.mtl") << mtl;
    std::ofstream(obj) << "mtllib card.mtl\no card\n"
                          "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nv 2 0 0\nv 3 0 0\nv 2 0 -1\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                          "usemtl cut\nf 1/1 2/2 3/3 4/4\nusemtl bark\nf 5 6 7\n";
}

// The card written with `mtl` and loaded back.
core::Result<Scene> loadCard(const fs::path& obj, const std::string& mtl) {
    writeCard(obj, mtl);
    return loadScene(obj);
}

// A leaf mask whose top half is transparent, as an RGBA PNG.
Image halfLeaf() { return splitImage(8, 4, {255, 255, 255, 0}, {255, 255, 255, 255}); }

const Mesh* meshWearing(const Scene& scene, bool alphaTested) {
    for (const Mesh& mesh : scene.meshes) {
        const Material* material = scene.materialOf(mesh);
        if ((material && material->alphaTested()) == alphaTested) return &mesh;
    }
    return nullptr;
}

// The mask's value on the card at `h` of the way from its near edge (v = 0) to its far edge
// (v = 1), halfway across: the uvs of its corners interpolated, as every pass and the ray tracer do.
float alphaAt(const Scene& scene, const Mesh& card, float h) {
    glm::vec2 bottom{0.0f}, top{0.0f};
    int bottoms = 0, tops = 0;
    for (const Vertex& v : card.vertices) {
        if (v.position.z > -0.5f)
            bottom += v.uv, ++bottoms;
        else
            top += v.uv, ++tops;
    }
    const glm::vec2 uv = glm::mix(bottom / float(bottoms), top / float(tops), h);
    return sampleLevel0(scene.textures[size_t(scene.materialOf(card)->baseColorTexture)], uv).a;
}

TEST(ObjMaterialsTest, AMapDCutsItsFacesRightSideUpAndLeavesPlainFacesOpaque) {
    const fs::path dir = test_support::scratchDir() / "obj_map_d";
    fs::create_directories(dir);
    // The image's top half transparent: the card's far half (v near 1) is cut away, not its near half.
    ASSERT_TRUE(writePng(halfLeaf(), dir / "leaf.png"));
    const auto scene =
        loadCard(dir / "card.obj", "newmtl cut\nKd 0.2 0.5 0.1\nmap_d leaf.png\nnewmtl bark\nKd 0.4 0.3 0.2\n");
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_EQ(scene->meshes.size(), 2u); // the cut faces a mesh of their own
    const Mesh* card = meshWearing(*scene, true);
    const Mesh* bark = meshWearing(*scene, false);
    ASSERT_TRUE(card && bark);
    EXPECT_EQ(card->triangleCount(), 2u);
    EXPECT_EQ(bark->triangleCount(), 1u);
    EXPECT_EQ(bark->material, -1); // as before: its colour in the vertices
    const Material& material = *scene->materialOf(*card);
    EXPECT_EQ(material.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(material.alphaCutoff, 0.5f);
    EXPECT_TRUE(material.doubleSided); // a card: cast from both sides
    EXPECT_LT(alphaAt(*scene, *card, 0.8f), 0.5f);
    EXPECT_GT(alphaAt(*scene, *card, 0.2f), 0.5f);
    EXPECT_NEAR(card->vertices[0].albedo.g, 0.5f, 1e-6f); // Kd still colours the vertices
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings.front();
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, AGreyMaskIsReadByItsLuminanceAndImfchanPicksAChannel) {
    const fs::path dir = test_support::scratchDir() / "obj_map_d_grey";
    fs::create_directories(dir);
    // Opaque grey levels, as most map_d files are saved: black above, white below.
    ASSERT_TRUE(writePng(splitImage(8, 4, {0, 0, 0, 255}, {255, 255, 255, 255}), dir / "grey.png"));
    const auto grey = loadCard(dir / "card.obj", "newmtl cut\nmap_d grey.png\nnewmtl bark\n");
    ASSERT_TRUE(grey) << grey.error();
    const Mesh* card = meshWearing(*grey, true);
    ASSERT_TRUE(card);
    EXPECT_LT(alphaAt(*grey, *card, 0.8f), 0.5f);
    EXPECT_GT(alphaAt(*grey, *card, 0.2f), 0.5f);

    // Red above, green below: `-imfchan g` keeps the near half, `-imfchan r` the far one.
    ASSERT_TRUE(writePng(splitImage(8, 4, {255, 0, 0, 255}, {0, 255, 0, 255}), dir / "rg.png"));
    for (const auto& [channel, upperKept] : {std::pair{'g', false}, std::pair{'r', true}}) {
        const auto scene =
            loadCard(dir / "card.obj", std::string("newmtl cut\nmap_d -imfchan ") + channel + " rg.png\nnewmtl bark\n");
        ASSERT_TRUE(scene) << scene.error();
        const Mesh* cut = meshWearing(*scene, true);
        ASSERT_TRUE(cut);
        EXPECT_EQ(alphaAt(*scene, *cut, 0.8f) > 0.5f, upperKept) << channel;
        EXPECT_EQ(alphaAt(*scene, *cut, 0.2f) > 0.5f, !upperKept) << channel;
    }
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, AMapDIsFoundWhereExportersLeaveItAndAMissingOneIsNamed) {
    const fs::path dir = test_support::scratchDir() / "obj_map_d_paths";
    fs::create_directories(dir / "textures");
    const Image leaf = halfLeaf();
    ASSERT_TRUE(writePng(leaf, dir / "textures" / "leaf.png"));
    ASSERT_TRUE(writePng(leaf, dir / "beside.png"));
    // A Windows exporter's relative path, and an absolute one from its author's disk.
    for (const char* name : {"textures\\leaf.png", "C:\\Users\\artist\\tree\\beside.png"}) {
        const auto scene = loadCard(dir / "card.obj", std::string("newmtl cut\nmap_d ") + name + "\nnewmtl bark\n");
        ASSERT_TRUE(scene) << scene.error();
        EXPECT_TRUE(meshWearing(*scene, true)) << name;
        EXPECT_TRUE(scene->warnings.empty()) << name << ": " << scene->warnings.front();
    }
    // A mask that is not there: the file loads, its card whole, and one line says why — one,
    // though two materials name it.
    const auto scene = loadCard(dir / "card.obj", "newmtl cut\nmap_d gone.png\nnewmtl bark\nmap_d gone.png\n");
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_FALSE(meshWearing(*scene, true));
    size_t triangles = 0;
    for (const Mesh& mesh : scene->meshes) triangles += mesh.triangleCount();
    EXPECT_EQ(triangles, 3u);
    ASSERT_EQ(scene->warnings.size(), 1u);
    const std::string& warning = scene->warnings.front();
    EXPECT_NE(warning.find("card.obj: material 'cut': its map_d 'gone.png' cannot be read"), std::string::npos)
        << warning;
    EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
    fs::remove_all(dir);
}

// An OBJ travels without its MTL as often as without its masks. The file still loads, every face
// in the default grey and none cut, and one line says so — once, though the OBJ names the library
// twice. Until 2026-12-07 it loaded without a word: tinyobjloader's warning was dropped, and a tree
// whose leaves lost their map_d cast solid cards unannounced.
TEST(ObjMaterialsTest, AMaterialLibraryThatCannotBeReadIsNamedInOneWarning) {
    const fs::path dir = test_support::scratchDir() / "obj_no_mtl";
    fs::create_directories(dir);
    std::ofstream(dir / "card.obj") << "mtllib gone.mtl\nmtllib gone.mtl\no card\n"
                                       "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                       "usemtl cut\nf 1/1 2/2 3/3 4/4\n";
    const auto scene = loadScene(dir / "card.obj");
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_FALSE(meshWearing(*scene, true)) << "nothing cuts the card";
    std::vector<std::string> named;
    for (const std::string& warning : scene->warnings)
        if (warning.find("gone.mtl") != std::string::npos) named.push_back(warning);
    ASSERT_EQ(named.size(), 1u);
    EXPECT_NE(named[0].find("card.obj: its material library 'gone.mtl': cannot be read"), std::string::npos)
        << named[0];
    EXPECT_EQ(named[0].find('\n'), std::string::npos) << named[0];
    fs::remove_all(dir);
}

// A name with spaces: `newmtl` names the material by the rest of its line, and tinyobjloader's
// OBJ reader took a `usemtl` line's first word alone, so those faces wore no material (two of
// assimp-testmodels' OBJ files); now both are read whole, however the blanks run. A library that
// was read but lacks a name a usemtl line gives (by its case, here; a comment after a name is
// not part of it) leaves those faces grey and
// uncut: one warning names the names. An OBJ naming no library at all is not told about its
// usemtl lines (exporters write `usemtl Default` with none: 6 of assimp-testmodels' 25 OBJ files).
TEST(ObjMaterialsTest, NamesWithSpacesAreReadWholeAndNamesNoLibraryDefinesAreNamedInOneWarning) {
    const fs::path dir = test_support::scratchDir() / "obj_material_names";
    fs::create_directories(dir);
    std::ofstream(dir / "lib.mtl") << "newmtl leaves\nKd 0 1 0\nnewmtl Hard Shiny  Plastic \nKd 1 0 0\n"
                                      "newmtl bark#2 # the trunk\nKd 0 0 1\n";
    const std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Leaves\nf 1 2 3\nusemtl leaves\nf 1 2 3\n"
                              "  usemtl  Hard\tShiny Plastic \r\nf 1 2 3\n# usemtl bark\nusemtl Leaves\nf 1 2 3\n"
                              "usemtl bark#2\t# a comment\nf 1 2 3\n";
    std::ofstream(dir / "tree.obj") << "mtllib lib.mtl\n" << faces;
    const auto scene = loadScene(dir / "tree.obj");
    ASSERT_TRUE(scene) << scene.error();
    std::vector<std::string> named;
    for (const std::string& warning : scene->warnings)
        if (warning.find("usemtl names") != std::string::npos) named.push_back(warning);
    ASSERT_EQ(named.size(), 1u);
    EXPECT_NE(named[0].find("tree.obj: usemtl names 1 material that no material library defines ('Leaves')"),
              std::string::npos)
        << named[0];
    // The faces wearing `leaves`, `Hard Shiny Plastic` and `bark#2` (a comment after it on both
    // sides) take their Kd.
    bool green = false, red = false, blue = false;
    for (const Mesh& mesh : scene->meshes)
        for (const Vertex& v : mesh.vertices) {
            green = green || (v.albedo.g > 0.99f && v.albedo.r < 0.01f);
            red = red || (v.albedo.r > 0.99f && v.albedo.g < 0.01f);
            blue = blue || (v.albedo.b > 0.99f && v.albedo.r < 0.01f);
        }
    EXPECT_TRUE(green);
    EXPECT_TRUE(red) << "the name with spaces";
    EXPECT_TRUE(blue) << "the name with a comment after it";

    std::ofstream(dir / "bare.obj") << faces;
    const auto bare = loadScene(dir / "bare.obj");
    ASSERT_TRUE(bare) << bare.error();
    for (const std::string& warning : bare->warnings) EXPECT_EQ(warning.find("usemtl"), std::string::npos) << warning;
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, MapDSpelledMapUpperDCutsAndAnUncutMapKdWithAlphaIsNamed) {
    const fs::path dir = test_support::scratchDir() / "obj_map_kd";
    fs::create_directories(dir);
    ASSERT_TRUE(writePng(halfLeaf(), dir / "leaf.png"));
    // DAZ Studio's spelling.
    const auto upper = loadCard(dir / "card.obj", "newmtl cut\n  map_D leaf.png\nnewmtl bark\n");
    ASSERT_TRUE(upper) << upper.error();
    EXPECT_TRUE(meshWearing(*upper, true));
    // The leaf's alpha in its diffuse texture alone: drawn opaque, as the MTL reads it, and said.
    const auto scene = loadCard(dir / "card.obj", "newmtl cut\nmap_Kd leaf.png\nnewmtl bark\nmap_Kd leaf.png\n");
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_FALSE(meshWearing(*scene, true));
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings.front().find("card.obj: material 'cut' ('leaf.png') and 1 more: a map_Kd with alpha"),
              std::string::npos)
        << scene->warnings.front();
    // A diffuse texture without alpha is nothing to say.
    ASSERT_TRUE(writePng(splitImage(8, 4, {0, 0, 0, 255}, {255, 255, 255, 255}), dir / "leaf.png"));
    const auto opaque = loadScene(dir / "card.obj");
    ASSERT_TRUE(opaque) << opaque.error();
    EXPECT_TRUE(opaque->warnings.empty()) << opaque->warnings.front();
    fs::remove_all(dir);
}

// Whether `mesh`, as the ray-traced truth and every pass test it, covers nothing.
bool cutAwayWhole(const Scene& scene, const Mesh& mesh) {
    const Material* material = scene.materialOf(mesh);
    return material && coversNothing(*material, scene.textures);
}

TEST(ObjMaterialsTest, GlassThatDissolvesBelowHalfLetsTheSunThroughAndTheRestCastsWhole) {
    const fs::path dir = test_support::scratchDir() / "obj_dissolve";
    fs::create_directories(dir);
    // A pane written as exporters write glass, `d 0.1`, or as 1 − Tr where the file has no d;
    // d wins over Tr where both are written (tinyobjloader's rule, MTL's own keyword).
    for (const char* glass : {"d 0.1", "Tr 0.9", "d 0.1\nTr 0.0", "Tr 0.0\nd 0.1"}) {
        const auto scene =
            loadCard(dir / "card.obj", std::string("newmtl cut\nKd 0.2 0.5 0.1\n") + glass + "\nnewmtl bark\nd 1\n");
        ASSERT_TRUE(scene) << scene.error();
        ASSERT_EQ(scene->meshes.size(), 2u) << glass;
        const Mesh* pane = meshWearing(*scene, true);
        const Mesh* bark = meshWearing(*scene, false);
        ASSERT_TRUE(pane && bark) << glass;
        EXPECT_TRUE(cutAwayWhole(*scene, *pane)) << glass;
        EXPECT_NEAR(scene->materialOf(*pane)->baseColorFactor.a, 0.1f, 1e-6f) << glass;
        EXPECT_NEAR(pane->vertices[0].albedo.g, 0.5f, 1e-6f) << glass; // Kd still colours the vertices
        EXPECT_EQ(bark->material, -1) << glass;
        // One line, naming the material and its dissolve (tinyobjloader's own warning aside,
        // where both d and Tr are written).
        const auto said = std::find_if(scene->warnings.begin(), scene->warnings.end(), [](const std::string& w) {
            return w.find("material 'cut' (d 0.1) dissolves below half: cut away whole") != std::string::npos;
        });
        ASSERT_NE(said, scene->warnings.end()) << glass;
        EXPECT_EQ(said->find('\n'), std::string::npos);
    }
    // Tinted glass that stops more than half of the light casts whole, as glTF's MASK does with
    // an alpha over its cutoff — and says nothing.
    for (const char* tinted : {"d 0.5", "d 0.7", "Tr 0.3"}) {
        const auto scene = loadCard(dir / "card.obj", std::string("newmtl cut\n") + tinted + "\nnewmtl bark\n");
        ASSERT_TRUE(scene) << scene.error();
        EXPECT_FALSE(meshWearing(*scene, true)) << tinted;
        EXPECT_TRUE(scene->warnings.empty()) << tinted << ": " << scene->warnings.front();
    }
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, AMapDIsMultipliedByItsDissolve) {
    const fs::path dir = test_support::scratchDir() / "obj_dissolve_map_d";
    fs::create_directories(dir);
    // A grey ramp from 0.25 (top row) to 1 (bottom row): at d 0.8 the texels under 0.625 are
    // cut, which alone (d 1) are kept.
    Image ramp(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            uint8_t* p = ramp.pixel(x, y);
            p[0] = p[1] = p[2] = 255;
            p[3] = uint8_t(64 + y * 191 / 7);
        }
    ASSERT_TRUE(writePng(ramp, dir / "ramp.png"));
    for (const auto& [dissolve, cutAtMiddle] : {std::pair{"1", false}, std::pair{"0.8", true}}) {
        const auto scene =
            loadCard(dir / "card.obj", std::string("newmtl cut\nmap_d ramp.png\nd ") + dissolve + "\nnewmtl bark\n");
        ASSERT_TRUE(scene) << scene.error();
        const Mesh* card = meshWearing(*scene, true);
        ASSERT_TRUE(card) << dissolve;
        const Material& material = *scene->materialOf(*card);
        // 0.55 of the way up the card the ramp reads about 0.55: kept alone, cut times 0.8.
        const float alpha = material.baseColorFactor.a * alphaAt(*scene, *card, 0.55f);
        EXPECT_EQ(alpha < material.alphaCutoff, cutAtMiddle) << dissolve << ": " << alpha;
        EXPECT_GE(material.baseColorFactor.a * alphaAt(*scene, *card, 0.02f), material.alphaCutoff) << dissolve;
        EXPECT_TRUE(scene->warnings.empty()) << dissolve << ": " << scene->warnings.front();
    }
    // Below half, the mask cannot save it: glass, and a mask that cannot be read is no matter.
    for (const char* mask : {"ramp.png", "gone.png"}) {
        const auto scene =
            loadCard(dir / "card.obj", std::string("newmtl cut\nmap_d ") + mask + "\nd 0.3\nnewmtl bark\n");
        ASSERT_TRUE(scene) << scene.error();
        const Mesh* card = meshWearing(*scene, true);
        ASSERT_TRUE(card) << mask;
        EXPECT_TRUE(cutAwayWhole(*scene, *card)) << mask;
    }
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, AFileWhoseEveryFaceWouldDissolveIsReadOpaqueAndSaysSo) {
    const fs::path dir = test_support::scratchDir() / "obj_dissolve_all";
    fs::create_directories(dir);
    // `Tr 1` written for opacity (3ds Max once did), or `d 0` on every material: read as
    // written, nothing would be left to draw. A material no face wears does not count either way.
    for (const char* library : {"newmtl cut\nTr 1\nnewmtl bark\nTr 1\n", "newmtl cut\nd 0\nnewmtl bark\nd 0\n",
                                "newmtl cut\nd 0\nnewmtl bark\nd 0\nnewmtl unused\nd 1\n"}) {
        const auto scene = loadCard(dir / "card.obj", library);
        ASSERT_TRUE(scene) << scene.error();
        EXPECT_FALSE(meshWearing(*scene, true)) << library;
        ASSERT_EQ(scene->warnings.size(), 1u) << library;
        EXPECT_NE(scene->warnings.front().find("card.obj: every face wears a material that dissolves below half"),
                  std::string::npos)
            << scene->warnings.front();
    }
    // One opaque face is enough for the glass beside it to be glass; glass no face wears is
    // not named.
    const auto glass = loadCard(dir / "card.obj", "newmtl cut\nd 0\nnewmtl bark\nnewmtl spare\nd 0.2\n");
    ASSERT_TRUE(glass) << glass.error();
    const Mesh* pane = meshWearing(*glass, true);
    ASSERT_TRUE(pane);
    EXPECT_TRUE(cutAwayWhole(*glass, *pane));
    ASSERT_EQ(glass->warnings.size(), 1u);
    EXPECT_NE(glass->warnings.front().find("material 'cut' (d 0) dissolves below half"), std::string::npos)
        << glass->warnings.front();
    // A dissolve outside [0, 1] is read opaque, and named.
    const auto odd = loadCard(dir / "card.obj", "newmtl cut\nd 7\nnewmtl bark\nd -1\n");
    ASSERT_TRUE(odd) << odd.error();
    EXPECT_FALSE(meshWearing(*odd, true));
    ASSERT_EQ(odd->warnings.size(), 1u);
    EXPECT_NE(odd->warnings.front().find("material 'cut' and 1 more: a dissolve (d, or 1 − Tr) outside [0, 1]"),
              std::string::npos)
        << odd->warnings.front();
    fs::remove_all(dir);
}

TEST(ObjMaterialsTest, AnExportedCutCardReadsBackCutAtTheSameTexels) {
    // A mask of every alpha level, a factor of 0.8 and a cutoff of 0.3: an MTL holds neither, so
    // the export bakes both into the mask; read back, each texel is kept or cut as it was.
    Scene s;
    Mesh card;
    card.vertices = {{{0, 0, 0}, {0, 1, 0}, glm::vec3(0.3f, 0.6f, 0.2f), {0, 1}},
                     {{1, 0, 0}, {0, 1, 0}, glm::vec3(0.3f, 0.6f, 0.2f), {1, 1}},
                     {{1, 0, -1}, {0, 1, 0}, glm::vec3(0.3f, 0.6f, 0.2f), {1, 0}},
                     {{0, 0, -1}, {0, 1, 0}, glm::vec3(0.3f, 0.6f, 0.2f), {0, 0}}};
    card.indices = {0, 1, 2, 0, 2, 3};
    card.material = 0;
    card.computeBounds();
    s.meshes = {card};
    s.batches = {{0, {glm::mat4(1.0f)}, false}};
    Texture levels;
    levels.image = Image(16, 16);
    for (int i = 0; i < 256; ++i) levels.image.rgba[4 * size_t(i) + 3] = uint8_t(i);
    s.textures = {levels};
    s.materials = {{.name = "leaf",
                    .baseColorFactor = {1.0f, 1.0f, 1.0f, 0.8f},
                    .baseColorTexture = 0,
                    .alphaMode = AlphaMode::Mask,
                    .alphaCutoff = 0.3f,
                    .doubleSided = true}};
    const fs::path dir = test_support::scratchDir() / "obj_export_cut";
    fs::remove_all(dir);
    ASSERT_TRUE(exportScene(s, dir / "card.obj"));
    const auto back = loadScene(dir / "card.obj");
    ASSERT_TRUE(back) << back.error();
    EXPECT_TRUE(back->warnings.empty()) << back->warnings.front();
    const Mesh* cut = meshWearing(*back, true);
    ASSERT_TRUE(cut);
    const Material& material = *back->materialOf(*cut);
    const Image& mask = back->textures[size_t(material.baseColorTexture)].image;
    ASSERT_EQ(mask.rgba.size(), levels.image.rgba.size());
    int kept = 0;
    for (int i = 0; i < 256; ++i) {
        const bool wasKept = 0.8f * float(i) / 255.0f >= 0.3f;
        const bool isKept = float(mask.rgba[4 * size_t(i) + 3]) / 255.0f >= material.alphaCutoff;
        EXPECT_EQ(isKept, wasKept) << "alpha level " << i;
        kept += isKept;
    }
    EXPECT_EQ(kept, 256 - 96); // 0.8 i / 255 ≥ 0.3 from i = 96
    // The card's corners keep their texture coordinates: the far edge (z = −1) at the image's top.
    for (const Vertex& v : cut->vertices) EXPECT_NEAR(v.uv.y, v.position.z < -0.5f ? 0.0f : 1.0f, 1e-5f);
    fs::remove_all(dir);
}

} // namespace
} // namespace shadowkit::scene
