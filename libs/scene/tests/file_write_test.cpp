// Files written whole or not at all (file_write.h): every failure the writers meet in the wild
// — a full disk, a missing or impossible directory, a file-size limit hit mid-write — is an
// error naming the file, and never leaves a partial file under the final name.
#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/resource.h>
#include <sys/stat.h>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = shadowkit::test_support::scratchDir() / ("shadowkit_file_write_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readAll(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Entries of `dir` other than `keep`: a temporary file left behind shows up here.
int strayEntries(const fs::path& dir, const fs::path& keep) {
    int n = 0;
    for (const auto& entry : fs::directory_iterator(dir)) n += entry.path() != keep;
    return n;
}

bool isCharacterDevice(const char* path) {
    struct stat st {};
    return ::stat(path, &st) == 0 && S_ISCHR(st.st_mode);
}

// Caps the size of any file this process writes (RLIMIT_FSIZE): a write past it fails with
// EFBIG, exactly as a full disk fails mid-file. SIGXFSZ is ignored meanwhile so the write
// returns the error instead of killing the test.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &old_);
        previous_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit capped = old_;
        capped.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &capped);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old_);
        std::signal(SIGXFSZ, previous_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit old_{};
    void (*previous_)(int) = nullptr;
};

} // namespace

TEST(FileWrite, RoundTripCreatesMissingDirectoriesAndLeavesNoTemporary) {
    const fs::path dir = scratch("round_trip");
    const fs::path file = dir / "a" / "b" / "out.bin";
    std::string bytes(100000, '\0');
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 7919 % 251);
    ASSERT_TRUE(scene::writeFile(file, bytes)) << "a new file in directories that do not exist yet";
    EXPECT_EQ(readAll(file), bytes);
    EXPECT_EQ(strayEntries(file.parent_path(), file), 0);
    ASSERT_TRUE(scene::writeFile(file, "shorter")) << "an existing file is replaced";
    EXPECT_EQ(readAll(file), "shorter");
}

TEST(FileWrite, AFailureMidFileKeepsTheOldFileWholeAndLeavesNoTemporary) {
    const fs::path dir = scratch("mid_file");
    const fs::path file = dir / "results.json";
    ASSERT_TRUE(scene::writeFile(file, "old results\n"));
    const std::string big(64 * 1024, 'x');
    core::Status status = core::Ok{};
    {
        FileSizeLimit limit(4096); // the write stops 4 KiB into 64 KiB, as a disk that fills
        status = scene::writeFile(file, big);
    }
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find(file.string()), std::string::npos) << status.error();
    EXPECT_EQ(status.error().find('\n'), std::string::npos) << "one line";
    EXPECT_EQ(readAll(file), "old results\n") << "the final name holds the old file, not a cut new one";
    EXPECT_EQ(strayEntries(dir, file), 0) << "the temporary file is removed";
}

TEST(FileWrite, InPiecesTheFileIsTheirConcatenationAndAFailedPieceStopsTheProducer) {
    const fs::path dir = scratch("pieces");
    const fs::path file = dir / "scene.obj";
    std::string expected;
    ASSERT_TRUE(scene::writeFileInPieces(file, [&expected](const scene::ByteSink& write) {
        for (int i = 0; i < 1000; ++i) {
            const std::string piece = "piece " + std::to_string(i) + std::string(size_t(i % 37), '.') + "\n";
            expected += piece;
            ASSERT_TRUE(write(piece));
        }
    }));
    EXPECT_EQ(readAll(file), expected);
    EXPECT_EQ(strayEntries(dir, file), 0);

    // Cut 4 KiB in, as a disk that fills: the sink says so, the producer stops, the old file stays.
    int handed = 0, refused = 0;
    core::Status status = core::Ok{};
    {
        FileSizeLimit limit(4096);
        status = scene::writeFileInPieces(file, [&](const scene::ByteSink& write) {
            for (int i = 0; i < 1000 && refused == 0; ++i, ++handed)
                if (!write(std::string(1024, 'x'))) ++refused;
        });
    }
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find(file.string()), std::string::npos) << status.error();
    EXPECT_EQ(refused, 1);
    EXPECT_LE(handed, 5) << "the sink refused the piece that crossed the limit";
    EXPECT_EQ(readAll(file), expected) << "the final name holds the old file";
    EXPECT_EQ(strayEntries(dir, file), 0) << "the temporary file is removed";
}

TEST(FileWrite, AFullDeviceIsAnErrorAndStaysADevice) {
    if (!isCharacterDevice("/dev/full")) GTEST_SKIP() << "no /dev/full here";
    const core::Status status = scene::writeFile("/dev/full", "anything");
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find("/dev/full: cannot write"), std::string::npos) << status.error();
    EXPECT_TRUE(isCharacterDevice("/dev/full")) << "a device is written in place, never renamed over";
    // The writers of every format go through writeFile.
    scene::Image image(4, 4);
    EXPECT_FALSE(scene::writePng(image, "/dev/full"));
}

TEST(FileWrite, APictureNamedForAnotherFormatIsRefusedBeforeAnythingIsWritten) {
    const fs::path dir = scratch("picture_names");
    const scene::Image image(4, 4);
    for (const char* name : {"shot.jpg", "shot.JPEG", "shot.webp"}) {
        const core::Status status = scene::writePng(image, dir / name);
        ASSERT_FALSE(status) << name;
        EXPECT_NE(status.error().find(std::string(name) + ": pictures are written as PNG: name it .png"),
                  std::string::npos)
            << status.error();
        EXPECT_FALSE(fs::exists(dir / name)) << name;
    }
    // PNG under its own name in any case, and under a name with no extension (a device, a pipe).
    for (const char* name : {"shot.png", "shot.PNG", "shot"}) {
        ASSERT_TRUE(scene::writePng(image, dir / name)) << name;
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3) << "nothing else, no temporary";
}

TEST(FileWrite, AnImpossibleDirectoryOrADirectoryTargetIsAnErrorNamingTheFile) {
    const fs::path dir = scratch("impossible");
    const fs::path plain = dir / "plain_file";
    ASSERT_TRUE(scene::writeFile(plain, "x"));
    const fs::path underFile = plain / "sub" / "out.png";
    const core::Status status = scene::writeFile(underFile, "y");
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find(underFile.string()), std::string::npos) << status.error();
    EXPECT_FALSE(scene::prepareOutputDirectory(underFile));
    EXPECT_FALSE(scene::writeFile(dir, "z")) << "a directory is not replaced by a file";
    EXPECT_TRUE(fs::is_directory(dir));
}

TEST(FileWrite, EveryExportFormatFailsOnAFullDiskAndWritesWholeOtherwise) {
    scene::ForestOptions o;
    o.trees = 3;
    o.terrainSize = 50;
    o.terrainResolution = 4;
    const scene::Scene forest = scene::makeForest(o);
    const fs::path dir = scratch("export");
    for (const char* name : {"x.glb", "x.obj"}) {
        const fs::path file = dir / name;
        ASSERT_TRUE(scene::exportScene(forest, file)) << name;
        const auto back = scene::loadScene(file);
        ASSERT_TRUE(back) << name << ": " << back.error();
        EXPECT_EQ(back->triangleCount(), forest.triangleCount()) << name;
        const std::string before = readAll(file);
        core::Status status = core::Ok{};
        {
            FileSizeLimit limit(before.size() / 2);
            status = scene::exportScene(forest, file);
        }
        EXPECT_FALSE(status) << name << " past a file-size limit";
        EXPECT_EQ(readAll(file), before) << name;
    }
}
