// Models we did not make: every glTF 2.0 and OBJ file of Debian's assimp-testmodels (Khronos
// samples, exporters' output, and files made broken on purpose — infinite positions, indices
// out of range, missing buffers, recursive nodes, Draco, wrong JSON types) loaded as a user
// would load them. Each either loads into finite, non-empty geometry or is refused with one
// line naming the file; none crashes, hangs or loads NaNs (run under the sanitizers in CI).
//
// And the image fuzzer's seeds (fuzz/corpus/image), which keep every input that once crashed a
// decoder: each decodes whole (four bytes for each of its width × height texels) or is refused in
// one line naming it.
#include "shadowkit/core/conventions.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

// assimp-testmodels' models (tools/install-deps.sh installs the package).
const fs::path kCorpus = "/usr/share/assimp/models";

std::vector<fs::path> corpusFiles() {
    std::vector<fs::path> files;
    for (const char* dir : {"glTF2", "OBJ"}) {
        std::error_code ec;
        for (fs::recursive_directory_iterator it(kCorpus / dir, ec), end; !ec && it != end; it.increment(ec)) {
            std::string ext = it->path().extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
            if (it->is_regular_file() && (ext == ".gltf" || ext == ".glb" || ext == ".obj"))
                files.push_back(it->path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace

TEST(CorpusTest, EveryPublicTestModelLoadsFiniteOrIsRefusedInOneLineNamingIt) {
    const std::vector<fs::path> files = corpusFiles();
    if (files.empty()) GTEST_SKIP() << kCorpus << " is missing: install assimp-testmodels (tools/install-deps.sh)";
    size_t loaded = 0, refused = 0;
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        const auto scene = scene::loadScene(file);
        if (!scene) {
            ++refused;
            EXPECT_NE(scene.error().find(file.string()), std::string::npos) << scene.error();
            EXPECT_EQ(scene.error().find('\n'), std::string::npos) << scene.error();
            if (file.parent_path().filename() == "draco") {
                EXPECT_NE(scene.error().find("Draco"), std::string::npos) << "why, not how: " << scene.error();
            }
            continue;
        }
        ++loaded;
        EXPECT_GT(scene->triangleCount(), 0u);
        const core::Aabb bounds = scene->wsBounds();
        EXPECT_TRUE(core::isFinite(bounds.min) && core::isFinite(bounds.max));
        for (const std::string& warning : scene->warnings) EXPECT_EQ(warning.find('\n'), std::string::npos);
    }
    // Most of the corpus is well-formed: a reader that refuses everything must not pass.
    EXPECT_GT(loaded, refused) << loaded << " loaded, " << refused << " refused";
    std::printf("corpus: %zu files, %zu loaded, %zu refused\n", files.size(), loaded, refused);
}

TEST(CorpusTest, EveryImageFuzzSeedDecodesWholeOrIsRefusedInOneLine) {
    const fs::path dir = fs::path(SHADOWKIT_FUZZ_CORPUS_DIR) / "image";
    size_t decoded = 0, refused = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        SCOPED_TRACE(entry.path().string());
        std::ifstream in(entry.path(), std::ios::binary);
        const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ASSERT_FALSE(bytes.empty());
        const auto image = scene::decodeImage(bytes, "seed");
        if (!image) {
            ++refused;
            EXPECT_EQ(image.error().rfind("seed: ", 0), 0u) << image.error();
            EXPECT_EQ(image.error().find('\n'), std::string::npos) << image.error();
            continue;
        }
        ++decoded;
        ASSERT_GT(image->width, 0);
        ASSERT_GT(image->height, 0);
        EXPECT_EQ(image->rgba.size(), size_t(image->width) * size_t(image->height) * 4);
    }
    // The seeds hold well-formed images of every format too: a decoder refusing all must not pass.
    EXPECT_GE(decoded, 8u) << decoded << " decoded, " << refused << " refused";
    EXPECT_GE(refused, 5u) << decoded << " decoded, " << refused << " refused";
}
