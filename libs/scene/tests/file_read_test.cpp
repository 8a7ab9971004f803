// Files read whole (file_read.h), and the readers that go through it: what a file from outside
// names — a directory, a pipe, something too large — is one line naming it, never a crash, a
// request for 2^63 bytes or a wait for a writer that never comes. The scratch directory lies
// under the working directory (the build tree, on a disk) rather than in /tmp, which may be a
// tmpfs: there a seek to a directory's end fails cleanly, and tinygltf's own reader survived
// what it does not survive on ext4.
#include "shadowkit/scene/file_read.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene_io.h"

#include "gltf_test_files.h"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

const std::string kEmbedded = "(embedded)";

class FileReadTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::current_path() / (std::string("shadowkit_file_read_") + test->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir / "textures");
        ASSERT_EQ(::mkfifo((m_dir / "pipe").c_str(), 0600), 0) << std::strerror(errno);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    void write(const std::string& name, const std::string& bytes) const {
        std::ofstream(m_dir / name, std::ios::binary) << bytes;
    }

    // A .gltf of one triangle whose buffer is `bufferUri` (kEmbedded: the triangle's 60 bytes
    // behind a data URI) and whose material, `alphaMode`, has a texture from `imageUri`.
    fs::path writeTriangle(const std::string& bufferUri, const std::string& imageUri,
                           const std::string& alphaMode) const {
        std::vector<uint8_t> buffer(60);
        const std::array<float, 9> positions{0, 0, 0, 1, 0, 0, 0, 1, 0};
        const std::array<float, 6> uvs{0, 0, 1, 0, 0, 1};
        std::memcpy(buffer.data(), positions.data(), 36);
        std::memcpy(buffer.data() + 36, uvs.data(), 24);
        const std::string uri = bufferUri == kEmbedded
                                    ? "data:application/octet-stream;base64," + scene::testing::base64(buffer)
                                    : bufferUri;
        const fs::path file = m_dir / "triangle.gltf";
        std::ofstream(file)
            << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
            << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
            << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
            << R"("min":[0,0,0],"max":[1,1,0]},)"
            << R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],)"
            << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)"
            << R"({"buffer":0,"byteOffset":36,"byteLength":24}],)"
            << R"("buffers":[{"byteLength":60,"uri":")" << uri << R"("}],)"
            << R"("materials":[{"alphaMode":")" << alphaMode
            << R"(","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
            << R"("textures":[{"source":0}],"images":[{"uri":")" << imageUri << R"("}]})";
        return file;
    }

    fs::path m_dir;
};

void expectOneLine(const std::string& message, const std::string& names, const std::string& says) {
    EXPECT_NE(message.find(names), std::string::npos) << message;
    EXPECT_NE(message.find(says), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

} // namespace

TEST_F(FileReadTest, ARegularFileIsReadWholeAndAnythingElseIsNamedInOneLine) {
    const std::string bytes("glTF\0\x01\x02 with a NUL inside\n", 26);
    write("whole.bin", bytes);
    auto whole = scene::readFile(m_dir / "whole.bin");
    ASSERT_TRUE(whole) << whole.error();
    EXPECT_EQ(*whole, bytes);
    write("empty.json", "");
    auto empty = scene::readFile(m_dir / "empty.json");
    ASSERT_TRUE(empty) << empty.error();
    EXPECT_TRUE(empty->empty());
    fs::create_symlink(m_dir / "whole.bin", m_dir / "link.bin");
    auto linked = scene::readFile(m_dir / "link.bin");
    ASSERT_TRUE(linked) << linked.error();
    EXPECT_EQ(*linked, bytes);

    auto directory = scene::readFile(m_dir / "textures");
    ASSERT_FALSE(directory);
    expectOneLine(directory.error(), (m_dir / "textures").string(), "a directory, not a file");
    auto pipe = scene::readFile(m_dir / "pipe"); // no writer: a plain open would wait here forever
    ASSERT_FALSE(pipe);
    expectOneLine(pipe.error(), (m_dir / "pipe").string(), "a device, pipe or socket, not a file");
    auto device = scene::readFile("/dev/zero"); // endless: read whole, it would never end
    ASSERT_FALSE(device);
    expectOneLine(device.error(), "/dev/zero", "not a file");
    auto missing = scene::readFile(m_dir / "missing.json");
    ASSERT_FALSE(missing);
    expectOneLine(missing.error(), (m_dir / "missing.json").string(), "cannot be read (No such file or directory)");
    auto large = scene::readFile(m_dir / "whole.bin", 25);
    ASSERT_FALSE(large);
    expectOneLine(large.error(), (m_dir / "whole.bin").string(), "26 bytes, over the 25 bytes limit");
    EXPECT_TRUE(scene::readFile(m_dir / "whole.bin", 26));
}

// tinygltf 2.7's own reader took a URI of "" or "textures/" for the file's directory, whose
// size a seek on ext4 reports as 2^63 − 1: std::bad_alloc out of the loader, the program killed
// (found on a public regression file of tinygltf's, an image URI that percent-decodes to "").
TEST_F(FileReadTest, AGltfUriNamingADirectoryOrAPipeIsRefusedInOneLine) {
    const std::string file = (m_dir / "triangle.gltf").string();
    const std::pair<std::string, std::string> uris[] = {{"", "neither a uri nor a buffer view"},
                                                        {"textures/", "'textures/': a directory, not a file"},
                                                        {"%!QAAAQAAA5", "cannot read it"},
                                                        {"pipe", "'pipe': a device, pipe or socket, not a file"}};
    for (const auto& [uri, why] : uris) {
        // The image on an alpha-tested material is needed: an error naming the scene, the image and why.
        auto masked = scene::loadScene(writeTriangle(kEmbedded, uri, "MASK"));
        ASSERT_FALSE(masked) << "image uri '" << uri << "'";
        expectOneLine(masked.error(), file + ": image 0", why);
        // On an opaque material it is not: one warning, and the triangle.
        auto opaque = scene::loadScene(writeTriangle(kEmbedded, uri, "OPAQUE"));
        ASSERT_TRUE(opaque) << "image uri '" << uri << "': " << opaque.error();
        EXPECT_EQ(opaque->warnings.size(), 1u)
            << "image uri '" << uri << "': " << ::testing::PrintToString(opaque->warnings);
        // A buffer is always needed.
        auto buffer = scene::loadScene(writeTriangle(uri, "textures/", "OPAQUE"));
        ASSERT_FALSE(buffer) << "buffer uri '" << uri << "'";
        EXPECT_NE(buffer.error().find(file), std::string::npos) << buffer.error();
        EXPECT_EQ(buffer.error().find('\n'), std::string::npos) << buffer.error();
    }
    auto directoryBuffer = scene::loadScene(writeTriangle("textures", "", "OPAQUE"));
    ASSERT_FALSE(directoryBuffer);
    EXPECT_NE(directoryBuffer.error().find("a directory, not a file"), std::string::npos) << directoryBuffer.error();
    auto pipeBuffer = scene::loadScene(writeTriangle("pipe", "", "OPAQUE"));
    ASSERT_FALSE(pipeBuffer);
    EXPECT_NE(pipeBuffer.error().find("pipe"), std::string::npos) << pipeBuffer.error();
    // The scene file itself, a pipe named .glb: refused, not waited on.
    ASSERT_EQ(::mkfifo((m_dir / "scene.glb").c_str(), 0600), 0);
    auto pipeScene = scene::loadScene(m_dir / "scene.glb");
    ASSERT_FALSE(pipeScene);
    expectOneLine(pipeScene.error(), (m_dir / "scene.glb").string(), "not a file");
}

TEST_F(FileReadTest, AnObjWhoseMaterialLibraryIsAPipeLoadsWithoutItsMaterials) {
    write("lib.mtl", "newmtl red\nKd 1 0 0\n");
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    write("red.obj", "mtllib lib.mtl\n" + triangle + "usemtl red\nf 1 2 3\n");
    write("piped.obj", "mtllib pipe\n" + triangle + "usemtl red\nf 1 2 3\n");
    write("boxed.obj", "mtllib textures\n" + triangle + "usemtl red\nf 1 2 3\n");
    auto red = scene::loadScene(m_dir / "red.obj");
    ASSERT_TRUE(red) << red.error();
    EXPECT_EQ(red->meshes[0].vertices[0].albedo, glm::vec3(1, 0, 0)); // the library beside the file is read
    for (const char* name : {"piped.obj", "boxed.obj"}) {
        auto loaded = scene::loadScene(m_dir / name); // a pipe: tinyobjloader's own reader waited here
        ASSERT_TRUE(loaded) << name << ": " << loaded.error();
        EXPECT_EQ(loaded->meshes[0].vertices[0].albedo, glm::vec3(0.7f)) << name; // no material: light grey
    }
}

namespace {

// `text` (UTF-8, every code point below U+10000 or a four-byte one) as UTF-16 behind its mark.
std::string utf16(const std::u16string& text, bool bigEndian) {
    std::string bytes = bigEndian ? "\xFE\xFF" : "\xFF\xFE";
    for (const char16_t unit : text) {
        const char high = char(unit >> 8), low = char(unit & 0xFF);
        bytes += bigEndian ? high : low;
        bytes += bigEndian ? low : high;
    }
    return bytes;
}

} // namespace

// OBJ and MTL files come from editors that write a byte-order mark (Notepad's UTF-8) or UTF-16
// (assimp-testmodels' box_UTF16BE.obj). Before readTextFile the mark glued itself to the first
// line, so `v 0 0 0` was no vertex and the face naming it was refused; UTF-16 had no faces at all.
TEST_F(FileReadTest, TextWithAByteOrderMarkOrInUtf16ReadsAsItsUtf8) {
    // é (two UTF-8 bytes), € (three) and 𝄞 (four: a surrogate pair in UTF-16) in a comment.
    const std::string utf8 = "# caf\xC3\xA9 \xE2\x82\xAC \xF0\x9D\x84\x9E\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::u16string units = u"# caf\u00E9 \u20AC \U0001D11E\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::pair<const char*, std::string> files[] = {{"plain.obj", utf8},
                                                         {"bom.obj", "\xEF\xBB\xBF" + utf8},
                                                         {"le.obj", utf16(units, false)},
                                                         {"be.obj", utf16(units, true)}};
    for (const auto& [name, bytes] : files) {
        write(name, bytes);
        const auto text = scene::readTextFile(m_dir / name);
        ASSERT_TRUE(text) << name << ": " << text.error();
        EXPECT_EQ(*text, utf8) << name;
        const auto model = scene::loadScene(m_dir / name);
        ASSERT_TRUE(model) << name << ": " << model.error();
        EXPECT_EQ(model->triangleCount(), 1u) << name;
        EXPECT_EQ(model->wsBounds().max, glm::dvec3(1, 1, 0)) << name;
    }
    // Bytes without a mark are left as they are, whatever they hold.
    write("raw.bin", std::string("v \xFF\xFE 1\n", 7));
    EXPECT_EQ(*scene::readTextFile(m_dir / "raw.bin"), std::string("v \xFF\xFE 1\n", 7));
}

TEST_F(FileReadTest, Utf16ThatIsNotIsRefusedInOneLineNamingTheFile) {
    write("odd.obj", utf16(u"v 0 0 0\n", false) + "v");
    expectOneLine(scene::readTextFile(m_dir / "odd.obj").error(), "odd.obj", "UTF-16 text of an odd number of bytes");
    std::string lowFirst = utf16(u"v 0 0 0\n", true);
    lowFirst += std::string("\xDC\x00", 2); // a low surrogate with no high one before it, at byte 18
    write("low.obj", lowFirst);
    expectOneLine(scene::readTextFile(m_dir / "low.obj").error(), "low.obj", "lone surrogate at byte 18");
    std::string highLast = utf16(u"v", false);
    highLast += "\x3D\xD8"; // a high surrogate with nothing after it, at byte 4
    write("high.obj", highLast);
    expectOneLine(scene::loadScene(m_dir / "high.obj").error(), "high.obj", "lone surrogate at byte 4");
}
