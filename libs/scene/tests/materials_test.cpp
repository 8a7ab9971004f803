// Materials and their images: glTF base colour textures with their samplers and transforms,
// alpha modes, images decoded within limits (and every broken one named in one line), the
// texture lookup the truth shares with GL, and mipmaps that keep an alpha test's coverage.
#include "shadowkit/scene/alpha_mask.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/material.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/texture_mips.h"

#include "gltf_test_files.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>
#include <webp/encode.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

// An image whose alpha is a checkerboard of `cells` × `cells` squares, colour a gradient.
scene::Image checkerAlpha(int size, int cells) {
    scene::Image image(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            uint8_t* p = image.pixel(x, y);
            p[0] = uint8_t(x * 255 / size), p[1] = uint8_t(y * 255 / size), p[2] = 40;
            p[3] = ((x * cells / size) + (y * cells / size)) % 2 == 0 ? 255 : 0;
        }
    return image;
}

std::vector<uint8_t> fileBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<uint8_t> pngBytes(const scene::Image& image) {
    const fs::path file = shadowkit::test_support::scratchDir() / "sk_material_image.png";
    EXPECT_TRUE(scene::writePng(image, file));
    auto bytes = fileBytes(file);
    fs::remove(file);
    return bytes;
}

using scene::testing::base64;

// A .gltf in `dir` holding one textured quad (positions, TEXCOORD_`set`, indices) whose
// material is `material` (JSON) and whose only image is `image` (JSON), with `extra` more
// top-level members (samplers, textures).
fs::path writeQuadGltf(const fs::path& dir, const std::string& material, const std::string& image, int set = 0,
                       const std::string& extra = R"("textures":[{"source":0}])") {
    std::vector<uint8_t> buffer;
    auto put = [&](const auto& values) {
        const size_t at = buffer.size();
        buffer.resize(at + sizeof(values));
        std::memcpy(buffer.data() + at, &values, sizeof(values));
    };
    put(std::array<float, 12>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    put(std::array<float, 8>{0, 1, 1, 1, 1, 0, 0, 0});
    put(std::array<uint16_t, 6>{0, 1, 2, 0, 2, 3});
    const fs::path file = dir / "quad.gltf";
    std::ofstream(file)
        << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_)" << set
        << R"(":1},"indices":2,"material":0}]}],)"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
        << R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},)"
        << R"({"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}],)"
        << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},)"
        << R"({"buffer":0,"byteOffset":80,"byteLength":12}],)"
        << R"("buffers":[{"byteLength":)" << buffer.size() << R"(,"uri":"data:application/octet-stream;base64,)"
        << base64(buffer) << R"("}],)"
        << R"("materials":[)" << material << R"(],"images":[)" << image << "]," << extra << "}";
    return file;
}

// Every field of a loaded material against the one it should be.
void expectMaterial(const scene::Material& actual, const scene::Material& expected) {
    EXPECT_EQ(actual.name, expected.name);
    EXPECT_EQ(actual.alphaMode, expected.alphaMode);
    EXPECT_FLOAT_EQ(actual.alphaCutoff, expected.alphaCutoff);
    EXPECT_EQ(actual.doubleSided, expected.doubleSided);
    EXPECT_EQ(actual.baseColorFactor, expected.baseColorFactor);
    EXPECT_EQ(actual.baseColorTexture, expected.baseColorTexture);
}

class MaterialsTest : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = shadowkit::test_support::scratchDir() / "sk_materials";
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }
    fs::path m_dir;
};

} // namespace

TEST_F(MaterialsTest, MaskedTexturedQuadLoadsWithItsMaterialSamplerAndTransformedUvs) {
    ASSERT_TRUE(scene::writePng(checkerAlpha(8, 2), m_dir / "leaf.png"));
    const fs::path file = writeQuadGltf(
        m_dir,
        R"({"name":"leaf","alphaMode":"MASK","alphaCutoff":0.3,"doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,1,0.8],)"
        R"("baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0],"scale":[2,2]}}}}})",
        R"({"uri":"leaf.png"})", 0,
        R"("samplers":[{"wrapS":33071,"wrapT":33648,"magFilter":9728,"minFilter":9729}],"textures":[{"source":0,"sampler":0}])");
    auto loaded = scene::loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_EQ(loaded->materials.size(), 1u);
    ASSERT_EQ(loaded->textures.size(), 1u);
    expectMaterial(loaded->materials[0], {.name = "leaf",
                                          .baseColorFactor = {1, 0.5f, 1, 0.8f},
                                          .baseColorTexture = 0,
                                          .alphaMode = scene::AlphaMode::Mask,
                                          .alphaCutoff = 0.3f,
                                          .doubleSided = true});
    const scene::Texture& t = loaded->textures[0];
    EXPECT_EQ(t.image.width, 8);
    EXPECT_EQ(t.image.rgba, checkerAlpha(8, 2).rgba); // PNG is lossless
    EXPECT_EQ(t.wrapS, scene::TextureWrap::ClampToEdge);
    EXPECT_EQ(t.wrapT, scene::TextureWrap::MirroredRepeat);
    EXPECT_TRUE(t.nearest);
    EXPECT_FALSE(t.mipmaps); // minFilter LINEAR: no mip levels
    const scene::Mesh& mesh = loaded->meshes[0];
    EXPECT_EQ(mesh.material, 0);
    EXPECT_EQ(loaded->materialOf(mesh), &loaded->materials[0]);
    // KHR_texture_transform: uv' = offset + scale · uv; the file's uv (1, 0) becomes (2.5, 0).
    EXPECT_EQ(mesh.vertices[2].uv, glm::vec2(2.5f, 0.0f));
    EXPECT_EQ(mesh.vertices[0].uv, glm::vec2(0.5f, 2.0f));
}

TEST_F(MaterialsTest, ImagesInBufferViewsAndDataUrisDecodeAndOpaqueIsTheDefault) {
    const std::vector<uint8_t> png = pngBytes(checkerAlpha(4, 2));
    const fs::path file = writeQuadGltf(m_dir, R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})",
                                        R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
    auto loaded = scene::loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->materials[0].alphaMode, scene::AlphaMode::Opaque);
    EXPECT_FALSE(loaded->materials[0].alphaTested());
    EXPECT_FALSE(loaded->materials[0].doubleSided);
    EXPECT_EQ(loaded->textures[0].image.rgba, checkerAlpha(4, 2).rgba);
    EXPECT_EQ(loaded->textures[0].wrapS, scene::TextureWrap::Repeat);
}

TEST_F(MaterialsTest, EveryBrokenImageIsOneLineNamingTheFileAndTheImage) {
    const std::vector<uint8_t> png = pngBytes(checkerAlpha(16, 2));
    std::vector<uint8_t> truncated(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));
    std::vector<uint8_t> badJpeg = {0xFF, 0xD8, 0xFF, 0x01, 0x02, 0x03, 0x04, 0x05};
    std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0, 0, 0, 0};
    const fs::path tall = m_dir / "tall.png";
    ASSERT_TRUE(scene::writePng(scene::Image(1, 65536), tall));
    const std::vector<uint8_t> tallBytes = fileBytes(tall);
    struct Case {
        std::string image, expected;
    };
    const Case cases[] = {
        {R"({"uri":"data:image/png;base64,)" + base64(truncated) + "\"}", "corrupt or truncated PNG"},
        {R"({"uri":"data:image/jpeg;base64,)" + base64(badJpeg) + "\"}", "JPEG"},
        {R"({"uri":"data:image/gif;base64,)" + base64(gif) + "\"}", "not a PNG, JPEG or WebP image"},
        {R"({"uri":"tall.png"})", "1×65536 PNG is over shadowkit's limits"},
        {R"({"uri":"missing.png"})", "image 0 'missing.png': cannot read it (a missing file?)"},
    };
    for (const Case& c : cases) {
        const fs::path file = writeQuadGltf(
            m_dir, R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})", c.image);
        auto loaded = scene::loadScene(file);
        ASSERT_FALSE(loaded) << c.expected;
        const std::string& message = loaded.error();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
        EXPECT_NE(message.find("image 0"), std::string::npos) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    // The decoder alone, on the same bytes: the limit is read from the header, before decoding.
    EXPECT_FALSE(scene::decodeImage(tallBytes, "tall"));
    EXPECT_FALSE(scene::decodeImage({}, "empty"));
    EXPECT_TRUE(scene::decodeImage(png, "whole"));
    // A Huffman table of 257 codes: Debian's stb_image 2.27 would write past its tables (fuzz_image).
    std::vector<uint8_t> dht = {0xFF, 0xD8, 0xFF, 0xC4, 0x01, 0x13, 0x00, 255, 2, 0, 0, 0,
                                0,    0,    0,    0,    0,    0,    0,    0,   0, 0, 0};
    dht.resize(dht.size() + 257, 1);
    auto huge = scene::decodeImage(dht, "dht");
    ASSERT_FALSE(huge);
    EXPECT_NE(huge.error().find("Huffman table"), std::string::npos) << huge.error();
    // A texture coordinate set the primitive lacks: refused where the alpha test needs it,
    // one warning where the material is opaque; and a cutoff out of range.
    const std::string pngUri = R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}";
    auto missingSet = scene::loadScene(writeQuadGltf(
        m_dir, R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}}})", pngUri));
    ASSERT_FALSE(missingSet);
    EXPECT_NE(missingSet.error().find("TEXCOORD_1"), std::string::npos) << missingSet.error();
    auto opaqueSet = scene::loadScene(
        writeQuadGltf(m_dir, R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}}})", pngUri));
    ASSERT_TRUE(opaqueSet) << opaqueSet.error();
    ASSERT_EQ(opaqueSet->warnings.size(), 1u);
    EXPECT_NE(opaqueSet->warnings[0].find("TEXCOORD_1"), std::string::npos) << opaqueSet->warnings[0];
    const fs::path badCutoff = writeQuadGltf(m_dir, R"({"alphaMode":"MASK","alphaCutoff":-2})",
                                             R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
    auto cutoff = scene::loadScene(badCutoff);
    ASSERT_FALSE(cutoff);
    EXPECT_NE(cutoff.error().find("alphaCutoff"), std::string::npos) << cutoff.error();
}

// Lossless WebP of an image (libwebp); the colour under fully transparent texels may differ.
std::vector<uint8_t> webpBytes(const scene::Image& image) {
    uint8_t* encoded = nullptr;
    const size_t size = WebPEncodeLosslessRGBA(image.rgba.data(), image.width, image.height, image.width * 4, &encoded);
    std::vector<uint8_t> bytes(encoded, encoded + size);
    WebPFree(encoded);
    return bytes;
}

// Alpha everywhere and colour where a texel is not fully transparent: what lossless WebP keeps.
void expectSameVisibleTexels(const scene::Image& actual, const scene::Image& expected) {
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    for (int y = 0; y < expected.height; ++y)
        for (int x = 0; x < expected.width; ++x) {
            const uint8_t *a = actual.pixel(x, y), *e = expected.pixel(x, y);
            ASSERT_EQ(a[3], e[3]) << x << "," << y;
            if (e[3] > 0) {
                ASSERT_TRUE(std::equal(a, a + 3, e)) << x << "," << y;
            }
        }
}

const std::string kMaskedTexture = R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})";
const std::string kOpaqueTexture = R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})";

TEST_F(MaterialsTest, WebpTexturesDecodeAndKtx2FallsBackToTheCoreImage) {
    const scene::Image checker = checkerAlpha(8, 2);
    // EXT_texture_webp with no core source (as a town exported for the web has it). tinygltf 2.7
    // takes data URIs of PNG, JPEG and octet-stream only; decodeImage goes by the bytes.
    const std::string webp = R"({"uri":"data:application/octet-stream;base64,)" + base64(webpBytes(checker)) + "\"}";
    auto loaded = scene::loadScene(writeQuadGltf(m_dir, kMaskedTexture, webp, 0,
                                                 R"("textures":[{"extensions":{"EXT_texture_webp":{"source":0}}}])"));
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_EQ(loaded->textures.size(), 1u);
    expectSameVisibleTexels(loaded->textures[0].image, checker);
    EXPECT_TRUE(loaded->warnings.empty());
    // KHR_texture_basisu: the KTX2 image cannot be decoded here, the core PNG source can.
    const std::vector<uint8_t> ktx2 = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n', 0, 0, 0, 0};
    const std::string images = R"({"uri":"data:application/octet-stream;base64,)" + base64(ktx2) +
                               R"("},{"uri":"data:image/png;base64,)" + base64(pngBytes(checker)) + "\"}";
    loaded = scene::loadScene(
        writeQuadGltf(m_dir, kMaskedTexture, images, 0,
                      R"("textures":[{"source":1,"extensions":{"KHR_texture_basisu":{"source":0}}}])"));
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->textures[0].image.rgba, checker.rgba);
    // KTX2 alone on a MASK material: its alpha is needed and cannot be had; the error says why.
    loaded = scene::loadScene(writeQuadGltf(m_dir, kMaskedTexture, images, 0,
                                            R"("textures":[{"extensions":{"KHR_texture_basisu":{"source":0}}}])"));
    ASSERT_FALSE(loaded);
    EXPECT_NE(loaded.error().find("KTX2"), std::string::npos) << loaded.error();
    EXPECT_NE(loaded.error().find("needs its alpha"), std::string::npos) << loaded.error();
    EXPECT_EQ(loaded.error().find('\n'), std::string::npos);
    // An extension's source that is no index (1e300 overflowed an int as tinygltf converts it)
    // is passed over for the core source.
    loaded = scene::loadScene(
        writeQuadGltf(m_dir, kMaskedTexture, images, 0,
                      R"("textures":[{"source":1,"extensions":{"EXT_texture_webp":{"source":1e300}}}])"));
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->textures[0].image.rgba, checker.rgba);
    // An animated or truncated WebP is an error of its own, not a crash.
    std::vector<uint8_t> cut = webpBytes(checker);
    cut.resize(cut.size() / 2);
    auto truncated = scene::decodeImage(cut, "cut");
    ASSERT_FALSE(truncated);
    EXPECT_NE(truncated.error().find("WebP"), std::string::npos) << truncated.error();
}

// The quad drawn twice, by two primitives: the first with material 0, the second with material 1.
fs::path withSecondPrimitive(const fs::path& file) {
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string first = R"("indices":2,"material":0})";
    const size_t at = text.find(first);
    if (at == std::string::npos) {
        ADD_FAILURE() << file << ": writeQuadGltf's primitive is not where this expects it";
        return file;
    }
    text.insert(at + first.size(), R"(,{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":1})");
    std::ofstream(file, std::ios::trunc) << text;
    return file;
}

TEST_F(MaterialsTest, AnUndecodableTextureOnOpaqueMaterialsIsOneWarningNotARefusedScene) {
    // Two opaque materials share a texture whose file is missing: the scene loads, untextured,
    // with one warning naming the image; shadows never read an opaque material's colour.
    auto loaded = scene::loadScene(
        withSecondPrimitive(writeQuadGltf(m_dir, kOpaqueTexture + "," + kOpaqueTexture, R"({"uri":"gone.png"})")));
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_EQ(loaded->warnings.size(), 1u);
    EXPECT_NE(loaded->warnings[0].find("image 0 'gone.png'"), std::string::npos) << loaded->warnings[0];
    EXPECT_EQ(loaded->warnings[0].find('\n'), std::string::npos);
    EXPECT_EQ(loaded->materials[0].baseColorTexture, -1);
    EXPECT_EQ(loaded->materials[1].baseColorTexture, -1);
    EXPECT_TRUE(loaded->textures.empty());
    // The same image on a MASK material is refused: its holes would be lost.
    auto masked = scene::loadScene(writeQuadGltf(m_dir, kMaskedTexture, R"({"uri":"gone.png"})"));
    ASSERT_FALSE(masked);
    EXPECT_NE(masked.error().find("gone.png"), std::string::npos) << masked.error();
    // The same MASK material, spare (no primitive uses it): not read, not refused.
    auto spare = scene::loadScene(writeQuadGltf(m_dir, "{}," + kMaskedTexture, R"({"uri":"gone.png"})"));
    ASSERT_TRUE(spare) << spare.error();
    EXPECT_TRUE(spare->warnings.empty());
    ASSERT_EQ(spare->materials.size(), 2u);
    EXPECT_EQ(spare->materials[1].alphaMode, scene::AlphaMode::Opaque);
    // A texture that names no image at all (the glTF Validator's material/valid.gltf): the
    // same rule, the texture named.
    auto sourceless =
        scene::loadScene(writeQuadGltf(m_dir, kMaskedTexture, R"({"uri":"gone.png"})", 0, R"("textures":[{}])"));
    ASSERT_FALSE(sourceless);
    EXPECT_NE(sourceless.error().find("texture 0 names no image"), std::string::npos) << sourceless.error();
    EXPECT_NE(sourceless.error().find("material 0 needs its alpha"), std::string::npos) << sourceless.error();
    EXPECT_TRUE(
        scene::loadScene(writeQuadGltf(m_dir, kOpaqueTexture, R"({"uri":"gone.png"})", 0, R"("textures":[{}])")));
}

TEST_F(MaterialsTest, AMaskWhoseAlphaNeverReachesItsCutoffIsNamedInAWarning) {
    // Blender's 22_factors.gltf: a BLEND cube at alpha 0.123, cast as MASK at 0.5, vanished
    // from every pass and every view compared nothing, unexplained.
    const std::string image = R"({"uri":"data:image/png;base64,)" + base64(pngBytes(checkerAlpha(4, 2))) + "\"}";
    const auto warningsOf = [&](const std::string& material) {
        auto loaded = scene::loadScene(writeQuadGltf(m_dir, material, image));
        EXPECT_TRUE(loaded) << loaded.error();
        return loaded ? loaded->warnings : std::vector<std::string>{};
    };
    const auto blend = warningsOf(R"({"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.123]}})");
    ASSERT_EQ(blend.size(), 1u);
    EXPECT_NE(blend[0].find("material 0 (BLEND, cast as MASK): its alpha is at most 0.123, below its cutoff 0.5: "
                            "cut away whole"),
              std::string::npos)
        << blend[0];
    // A checker of alpha 0 and 1 times 0.4: at most 0.4, under a cutoff of 0.5; over one of 0.3.
    const std::string masked = R"({"alphaMode":"MASK","alphaCutoff":CUT,"pbrMetallicRoughness":)"
                               R"({"baseColorFactor":[1,1,1,0.4],"baseColorTexture":{"index":0}}})";
    const auto at = [&](const std::string& cutoff) {
        std::string m = masked;
        m.replace(m.find("CUT"), 3, cutoff);
        return warningsOf(m);
    };
    ASSERT_EQ(at("0.5").size(), 1u);
    EXPECT_NE(at("0.5")[0].find("its alpha is at most 0.4, below its cutoff 0.5"), std::string::npos) << at("0.5")[0];
    EXPECT_TRUE(at("0.3").empty());
    // Opaque ignores alpha: no word.
    EXPECT_TRUE(warningsOf(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.1]}})").empty());
}

TEST_F(MaterialsTest, GlassLetsTheLightItTransmitsThroughAsAMask) {
    // KHR_materials_transmission (Blender writes it for every glass): a clear pane lets the sun
    // through; until it was read, every window kept the sun out of its room, in the maps and
    // in the truth alike.
    const std::string image = R"({"uri":"data:image/png;base64,)" + base64(pngBytes(checkerAlpha(4, 2))) + "\"}";
    const auto load = [&](const std::string& material) {
        return scene::loadScene(writeQuadGltf(m_dir, material, image));
    };
    const auto glass = [](const std::string& colour, const std::string& transmission, const std::string& mode = "") {
        return R"({"name":"glass",)" + mode + R"("pbrMetallicRoughness":{"baseColorFactor":)" + colour +
               R"(},"extensions":{"KHR_materials_transmission":)" + transmission + "}}";
    };

    // Clear glass: all of the light through, so alpha 0 against a cutoff of 0.5: cut away whole,
    // said once.
    auto clear = load(glass("[1,1,1,1]", R"({"transmissionFactor":1})"));
    ASSERT_TRUE(clear) << clear.error();
    expectMaterial(
        clear->materials[0],
        {.name = "glass", .baseColorFactor = {1, 1, 1, 0}, .alphaMode = scene::AlphaMode::Mask, .alphaCutoff = 0.5f});
    ASSERT_EQ(clear->warnings.size(), 1u);
    EXPECT_NE(clear->warnings[0].find("material 0 'glass': KHR_materials_transmission lets 100 % of the light "
                                      "through: taken out of its alpha, which its cutoff 0.5 then cuts"),
              std::string::npos)
        << clear->warnings[0];
    EXPECT_NE(clear->warnings[0].find("cut away whole"), std::string::npos) << clear->warnings[0];

    // Red glass lets through its base colour's luminance, 0.2126 · 0.9 + 0.7152 · 0.2 + 0.0722 ·
    // 0.1 = 0.342: it still stops most of the sun, and casts.
    auto red = load(glass("[0.9,0.2,0.1,1]", R"({"transmissionFactor":1})"));
    ASSERT_TRUE(red) << red.error();
    EXPECT_EQ(red->materials[0].alphaMode, scene::AlphaMode::Mask);
    EXPECT_NEAR(red->materials[0].baseColorFactor.a, 1.0 - (0.2126 * 0.9 + 0.7152 * 0.2 + 0.0722 * 0.1), 1e-6);
    ASSERT_EQ(red->warnings.size(), 1u);
    EXPECT_NE(red->warnings[0].find("lets 34.2 % of the light through"), std::string::npos) << red->warnings[0];
    EXPECT_EQ(red->warnings[0].find("cut away whole"), std::string::npos) << red->warnings[0];

    // A mask keeps its cutoff; its alpha loses what gets through.
    auto masked =
        load(glass("[1,1,1,0.8]", R"({"transmissionFactor":0.5})", R"("alphaMode":"MASK","alphaCutoff":0.3,)"));
    ASSERT_TRUE(masked) << masked.error();
    EXPECT_FLOAT_EQ(masked->materials[0].alphaCutoff, 0.3f);
    EXPECT_FLOAT_EQ(masked->materials[0].baseColorFactor.a, 0.4f);

    // An opaque material's alpha means nothing (glTF §3.9.4): made a mask, it must not start
    // cutting where its factor (0.2) or its colour texture (a checker of alpha 0 and 1) is low.
    auto coloured = load(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.2],"baseColorTexture":{"index":0}},)"
                         R"("extensions":{"KHR_materials_transmission":{"transmissionFactor":0.3}}})");
    ASSERT_TRUE(coloured) << coloured.error();
    const scene::Material& c = coloured->materials[0];
    EXPECT_EQ(c.alphaMode, scene::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(c.baseColorFactor.a, 0.7f);
    ASSERT_EQ(c.baseColorTexture, 1); // a copy, its alpha opaque
    for (size_t i = 3; i < coloured->textures[1].image.rgba.size(); i += 4)
        EXPECT_EQ(coloured->textures[1].image.rgba[i], 255);
    EXPECT_EQ(coloured->textures[0].image.rgba, checkerAlpha(4, 2).rgba); // the file's, untouched

    // Nothing through: the material as the file wrote it, and no word.
    auto none = load(glass("[1,1,1,1]", R"({"transmissionFactor":0})"));
    ASSERT_TRUE(none) << none.error();
    EXPECT_EQ(none->materials[0].alphaMode, scene::AlphaMode::Opaque);
    EXPECT_TRUE(none->warnings.empty());

    // What cannot be read is one line naming the material.
    auto beyond = load(glass("[1,1,1,1]", R"({"transmissionFactor":1.5})"));
    ASSERT_FALSE(beyond);
    EXPECT_NE(beyond.error().find("material 0 'glass': KHR_materials_transmission's transmissionFactor is not a "
                                  "number in [0, 1]"),
              std::string::npos)
        << beyond.error();
    auto nowhere = load(glass("[1,1,1,1]", R"({"transmissionFactor":1,"transmissionTexture":{"index":5}})"));
    ASSERT_FALSE(nowhere);
    EXPECT_NE(nowhere.error().find("transmissionTexture is not a reference to one of the file's textures"),
              std::string::npos)
        << nowhere.error();
    auto huge = load(glass("[1,1,1,1]", R"({"transmissionFactor":1,"transmissionTexture":{"index":1e300}})"));
    ASSERT_FALSE(huge); // not an int overflowing as it is converted
    EXPECT_NE(huge.error().find("is not a reference to one of the file's textures"), std::string::npos) << huge.error();
}

TEST_F(MaterialsTest, ATransmissionTexturesRedCutsTheSurfaceWhereItLetsTheLightThrough) {
    // The pattern in the red channel: 4 × 4 texels, red 255 (all through) on the squares where
    // (x + y) is odd, 0 elsewhere; its alpha all 255, so only the red can cut.
    scene::Image pattern(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            uint8_t* p = pattern.pixel(x, y);
            p[0] = (x + y) % 2 ? 255 : 0, p[1] = 90, p[2] = 40, p[3] = 255;
        }
    const std::string images = R"({"uri":"data:image/png;base64,)" + base64(pngBytes(pattern)) +
                               R"("},{"uri":"data:image/png;base64,)" + base64(pngBytes(checkerAlpha(4, 1))) + "\"}";
    const auto load = [&](const std::string& material, int set) {
        return scene::loadScene(
            writeQuadGltf(m_dir, material, images, set, R"("textures":[{"source":0},{"source":1}])"));
    };

    // The pattern alone, read through TEXCOORD_1 and its own transform: white texels whose alpha
    // is what they stop, the quad's uvs those of the pattern's reference.
    auto alone =
        load(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1]},"extensions":{"KHR_materials_transmission":)"
             R"({"transmissionFactor":1,"transmissionTexture":{"index":0,"texCoord":1,)"
             R"("extensions":{"KHR_texture_transform":{"scale":[2,2]}}}}}})",
             1);
    ASSERT_TRUE(alone) << alone.error();
    const scene::Material& m = alone->materials[0];
    EXPECT_EQ(m.alphaMode, scene::AlphaMode::Mask);
    ASSERT_EQ(m.baseColorTexture, 0);
    const scene::Image& cut = alone->textures[0].image;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(cut.pixel(x, y)[3], (x + y) % 2 ? 0 : 255) << x << ", " << y;
            EXPECT_EQ(cut.pixel(x, y)[0], 255);
        }
    EXPECT_EQ(alone->meshes[0].vertices[2].uv, glm::vec2(2.0f, 0.0f)); // the file's (1, 0), scaled
    ASSERT_EQ(alone->warnings.size(), 1u);
    EXPECT_NE(
        alone->warnings[0].find("lets 100 % of the light through where its transmission texture lets all through"),
        std::string::npos)
        << alone->warnings[0];

    // With a base colour texture read through the same coordinates: its alpha (a checker of one
    // square: 255 everywhere) times what the pattern stops, in a copy of it — the base texture
    // itself stays as it was for any other material.
    auto both = load(
        R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":1}},)"
        R"("extensions":{"KHR_materials_transmission":{"transmissionFactor":0.6,"transmissionTexture":{"index":0}}}})",
        0);
    ASSERT_TRUE(both) << both.error();
    ASSERT_EQ(both->textures.size(), 2u);
    ASSERT_EQ(both->materials[0].baseColorTexture, 1);
    EXPECT_EQ(both->textures[0].image.rgba, checkerAlpha(4, 1).rgba);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(both->textures[1].image.pixel(x, y)[3], (x + y) % 2 ? 102 : 255) << x << ", " << y;

    // Through other coordinates than the base colour's: taken at its mean, half the squares.
    auto apart = load(
        R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":1}},)"
        R"("extensions":{"KHR_materials_transmission":{"transmissionFactor":1,"transmissionTexture":{"index":0,"texCoord":1}}}})",
        0);
    ASSERT_TRUE(apart) << apart.error();
    EXPECT_FLOAT_EQ(apart->materials[0].baseColorFactor.a, 0.5f);
    ASSERT_EQ(apart->warnings.size(), 1u);
    EXPECT_NE(apart->warnings[0].find("taken at its mean, 50 %"), std::string::npos) << apart->warnings[0];
}

TEST_F(MaterialsTest, PercentEncodedUrisNameTheirFiles) {
    const scene::Image checker = checkerAlpha(4, 2);
    ASSERT_TRUE(scene::writePng(checker, m_dir / "leaf atlas 100%.png"));
    auto loaded = scene::loadScene(writeQuadGltf(m_dir, kMaskedTexture, R"({"uri":"leaf%20atlas%20100%25.png"})"));
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded->textures[0].image.rgba, checker.rgba);
}

TEST_F(MaterialsTest, ExportedGlbLoadsBackWithItsMaterialsTexturesAndUvs) {
    scene::Scene s;
    scene::Mesh plain, card;
    scene::addBox(plain, glm::mat4(1.0f), {1.0f, 1.0f, 1.0f}, glm::vec3(0.5f, 0.25f, 0.1f));
    scene::addCard(card, glm::mat4(1.0f), {0.0f, 1.0f}, {0.5f, 0.5f}, glm::vec3(0.5f, 0.8f, 0.4f));
    card.material = 0;
    for (scene::Mesh* m : {&plain, &card}) m->computeBounds();
    s.meshes = {plain, card};
    s.batches = {{0, {glm::mat4(1.0f)}, false}, {1, {glm::translate(glm::mat4(1.0f), {3.0f, 0.0f, 0.0f})}, false}};
    scene::Texture texture;
    texture.image = checkerAlpha(16, 4);
    texture.wrapS = scene::TextureWrap::ClampToEdge;
    s.textures = {texture};
    s.materials = {{.name = "leaf",
                    .baseColorFactor = {0.5f, 1.0f, 1.0f, 0.9f},
                    .baseColorTexture = 0,
                    .alphaMode = scene::AlphaMode::Mask,
                    .alphaCutoff = 0.4f,
                    .doubleSided = true}};
    const fs::path file = m_dir / "exported.glb";
    ASSERT_TRUE(scene::exportScene(s, file));
    auto loaded = scene::loadScene(file);
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_EQ(loaded->materials.size(), 1u);
    ASSERT_EQ(loaded->textures.size(), 1u);
    expectMaterial(loaded->materials[0], s.materials[0]);
    EXPECT_EQ(loaded->textures[0].image.rgba, texture.image.rgba);
    EXPECT_EQ(loaded->textures[0].wrapS, scene::TextureWrap::ClampToEdge);
    ASSERT_EQ(loaded->meshes.size(), 2u);
    const scene::Mesh& plainBack = loaded->meshes[0];
    const scene::Mesh& cardBack = loaded->meshes[1];
    EXPECT_EQ(plainBack.material, -1);
    EXPECT_EQ(cardBack.material, 0);
    ASSERT_EQ(cardBack.vertices.size(), card.vertices.size());
    for (size_t v = 0; v < card.vertices.size(); ++v) {
        EXPECT_EQ(cardBack.vertices[v].uv, card.vertices[v].uv);
        EXPECT_NEAR(glm::distance(cardBack.vertices[v].albedo, card.vertices[v].albedo), 0.0f, 1e-6f); // factor once
        EXPECT_NEAR(glm::distance(cardBack.vertices[v].position, card.vertices[v].position), 0.0f, 1e-6f);
    }
    // The card's instance is a node placed 3 m along x, not vertices moved there.
    ASSERT_EQ(loaded->batches.size(), 2u);
    ASSERT_EQ(loaded->batches[1].mesh, 1u);
    ASSERT_EQ(loaded->batches[1].worldFromObject.size(), 1u);
    EXPECT_EQ(loaded->batches[1].worldFromObject[0], s.batches[1].worldFromObject[0]);
}

TEST(TextureSamplingTest, Level0LookupIsGlsBilinearWithItsWrapModes) {
    scene::Texture t;
    t.image = scene::Image(2, 1);
    t.image.pixel(0, 0)[3] = 0;
    t.image.pixel(1, 0)[3] = 255;
    // Texel centres give the texels; half way between them, the mean.
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.25f, 0.5f}).a, 0.0f);
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.75f, 0.5f}).a, 1.0f);
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.5f, 0.5f}).a, 0.5f);
    // At u = 0 the left neighbour is texel 1 under REPEAT, texel 0 itself under CLAMP_TO_EDGE.
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.0f, 0.5f}).a, 0.5f);
    t.wrapS = scene::TextureWrap::ClampToEdge;
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.0f, 0.5f}).a, 0.0f);
    // MIRRORED_REPEAT: u in [1, 2) reads the texture backwards.
    t.wrapS = scene::TextureWrap::MirroredRepeat;
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {1.25f, 0.5f}).a, 1.0f);
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {1.75f, 0.5f}).a, 0.0f);
    // NEAREST: the texel under the point; huge and non-finite uvs stay finite.
    t.nearest = true;
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.49f, 0.5f}).a, 0.0f);
    EXPECT_FLOAT_EQ(scene::sampleLevel0(t, {0.51f, 0.5f}).a, 1.0f);
    EXPECT_TRUE(std::isfinite(scene::sampleLevel0(t, {1e30f, -1e30f}).a));
    EXPECT_TRUE(std::isfinite(scene::sampleLevel0(t, {NAN, 0.5f}).a));
}

TEST(TextureSamplingTest, AMaterialCoversNothingExactlyWhereTheTruthsAlphaTestCoversNoPoint) {
    // A texture whose largest alpha is 153 (0.6), at one texel of 4 × 4, the rest 40.
    std::vector<scene::Texture> textures(1);
    textures[0].image = scene::Image(4, 4);
    for (size_t i = 3; i < textures[0].image.rgba.size(); i += 4) textures[0].image.rgba[i] = 40;
    textures[0].image.pixel(2, 1)[3] = 153;
    EXPECT_FLOAT_EQ(scene::largestAlpha(textures[0].image), 0.6f);
    struct Case {
        scene::AlphaMode mode;
        int32_t texture;
        float factor, cutoff;
        bool nothing;
    } cases[] = {
        {scene::AlphaMode::Opaque, -1, 0.0f, 0.5f, false}, // alpha ignored
        {scene::AlphaMode::Mask, -1, 0.49f, 0.5f, true},
        {scene::AlphaMode::Mask, -1, 0.5f, 0.5f, false},  // covered where alpha ≥ cutoff
        {scene::AlphaMode::Blend, -1, 0.12f, 0.5f, true}, // cast as MASK
        {scene::AlphaMode::Mask, 0, 1.0f, 0.5f, false},   // the one texel at 0.6
        {scene::AlphaMode::Mask, 0, 0.8f, 0.5f, true},    // 0.48 at most
        {scene::AlphaMode::Mask, 0, 0.8f, 0.3f, false},
    };
    for (const Case& c : cases) {
        const scene::Material material{.baseColorFactor = {1.0f, 1.0f, 1.0f, c.factor},
                                       .baseColorTexture = c.texture,
                                       .alphaMode = c.mode,
                                       .alphaCutoff = c.cutoff};
        const std::string what = "factor " + std::to_string(c.factor) + ", cutoff " + std::to_string(c.cutoff) +
                                 (c.texture >= 0 ? ", textured" : "");
        EXPECT_EQ(scene::coversNothing(material, textures), c.nothing) << what;
        if (!material.alphaTested()) continue;
        // The ray-traced truth's own test (AlphaMask, level 0 as GL samples it) agrees: no point
        // of a surface that covers nothing is covered, and the texel centre of the largest alpha
        // is where one that covers something is.
        const scene::AlphaMask mask(c.texture >= 0 ? textures[0] : scene::Texture{}, c.factor, c.cutoff);
        bool anyCovered = false;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                anyCovered |= mask.covers({(float(x) + 0.5f) / 32.0f, (float(y) + 0.5f) / 32.0f});
        anyCovered |= mask.covers({2.5f / 4.0f, 1.5f / 4.0f});
        EXPECT_EQ(anyCovered, !c.nothing) << what;
    }
}

TEST(TextureMipsTest, AlphaTestedMipsKeepTheCoverageThatBoxFilteringLoses) {
    // Foliage-like alpha: round leaves of alpha 1 covering about 30 % of a 256² texture.
    scene::Image leaves(256, 256);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> at(0.0f, 256.0f);
    for (int leaf = 0; leaf < 90; ++leaf) {
        const float cx = at(random), cy = at(random);
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x)
                if ((float(x) - cx) * (float(x) - cx) + (float(y) - cy) * (float(y) - cy) < 81.0f)
                    leaves.pixel(x, y)[3] = 255;
    }
    const double coverage = scene::sampledAlphaCoverage(leaves, 0.5f);
    ASSERT_GT(coverage, 0.2);
    ASSERT_LT(coverage, 0.4);
    const std::vector<scene::Image> kept = scene::buildMipChain(leaves, 0.5f);
    const std::vector<scene::Image> boxed = scene::buildMipChain(leaves, std::nullopt);
    ASSERT_EQ(kept.size(), 9u); // 256 … 1
    ASSERT_EQ(boxed.size(), 9u);
    EXPECT_EQ(kept[8].width, 1);
    // Down to 8×8 texels (256 samples: coverage steps of 0.4 %) every level keeps level 0's
    // bilinear coverage within 3 points; box filtering loses it — the canopy that thins with distance.
    for (size_t level = 1; level <= 5; ++level) {
        EXPECT_NEAR(scene::sampledAlphaCoverage(kept[level], 0.5f), coverage, 0.03) << "level " << level;
    }
    EXPECT_LT(scene::sampledAlphaCoverage(boxed[5], 0.5f), 0.5 * coverage);
    EXPECT_EQ(scene::alphaCoverage(boxed[8], 0.5f), 0.0); // 1×1: the mean alpha, under the cutoff
    // Colour is the box filter's either way.
    EXPECT_EQ(kept[3].pixel(2, 2)[0], boxed[3].pixel(2, 2)[0]);
}

TEST(MeshBuilderTest, ACardSpansItsAtlasCellFromBottomLeftToTopRight) {
    scene::Mesh mesh;
    scene::addCard(mesh, glm::mat4(1.0f), {0.25f, 0.5f}, {0.5f, 0.0f}, glm::vec3(1.0f));
    ASSERT_EQ(mesh.vertices.size(), 4u);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.vertices[0].position, glm::vec3(-0.5f, 0, 0));
    EXPECT_EQ(mesh.vertices[0].uv, glm::vec2(0.25f, 0.5f));
    EXPECT_EQ(mesh.vertices[2].position, glm::vec3(0.5f, 1, 0));
    EXPECT_EQ(mesh.vertices[2].uv, glm::vec2(0.5f, 0.0f));
    // Counter-clockwise seen from +z, the side its normal faces.
    const glm::vec3 a = mesh.vertices[mesh.indices[0]].position, b = mesh.vertices[mesh.indices[1]].position,
                    c = mesh.vertices[mesh.indices[2]].position;
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
}
