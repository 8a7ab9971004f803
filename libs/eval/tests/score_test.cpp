// shadowkit score's scoring (eval/score.h): another renderer's mask against the truth, and the
// mask files it reads (16-bit PNG, .npy), which come from outside.
#include "shadowkit/eval/npy.h"
#include "shadowkit/eval/score.h"
#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

using namespace shadowkit;

namespace {

// Eight pixels: four lit and two shadowed surfaces facing the sun, the sky, one facing away.
eval::TruthBuffers eightPixels() {
    eval::TruthBuffers t;
    t.width = 8;
    t.height = 1;
    t.surfaceId = {1, 1, 2, 2, 3, 3, 0, 4};
    t.viewDepth = {10, 11, 12, 13, 14, 15, 0, 16};
    t.facesLight = {1, 1, 1, 1, 1, 1, 0, 0};
    t.lit = {1, 1, 1, 1, 0, 0, 0, 0};
    return t;
}

std::filesystem::path tempFile(const std::string& name) { return shadowkit::test_support::scratchDir() / name; }

void writeBytes(const std::filesystem::path& file, const std::string& bytes) {
    const core::Status written = scene::writeFile(file, bytes);
    ASSERT_TRUE(written) << written.error();
}

// A PNG of 16-bit grey pixels, its image data in one stored (uncompressed) deflate block, so
// the test needs no zlib: ISO 15948 §5 (chunks and their CRC-32), RFC 1950/1951 (zlib, stored).
std::string greyPng16(int width, int height, const std::vector<uint16_t>& values) {
    auto crc32 = [](const std::string& bytes) {
        uint32_t crc = 0xFFFFFFFFu;
        for (unsigned char b : bytes) {
            crc ^= b;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
        return crc ^ 0xFFFFFFFFu;
    };
    auto be32 = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16 & 0xFF), char(v >> 8 & 0xFF), char(v & 0xFF)};
    };
    auto chunk = [&](const std::string& type, const std::string& data) {
        return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
    };
    std::string raw; // each row: filter byte 0, then big-endian samples
    for (int y = 0; y < height; ++y) {
        raw += '\0';
        for (int x = 0; x < width; ++x) {
            const uint16_t v = values[size_t(y * width + x)];
            raw += char(v >> 8), raw += char(v & 0xFF);
        }
    }
    uint32_t a = 1, b = 0; // Adler-32 of the raw bytes
    for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
    const auto length = uint16_t(raw.size());
    std::string zlib = {char(0x78),
                        char(0x01),
                        char(0x01),
                        char(length & 0xFF),
                        char(length >> 8),
                        char(~length & 0xFF),
                        char((~length >> 8) & 0xFF)};
    zlib += raw + be32(b << 16 | a);
    const std::string header =
        be32(uint32_t(width)) + be32(uint32_t(height)) + std::string{16, 0, 0, 0, 0}; // 16-bit grey
    return std::string("\x89PNG\r\n\x1A\n", 8) + chunk("IHDR", header) + chunk("IDAT", zlib) + chunk("IEND", "");
}

} // namespace

TEST(ScoreTest, AMaskIsClassedAsTheRasterisedTermWouldBe) {
    const eval::TruthBuffers truth = eightPixels();
    eval::ShadowMask mask{8, 1, {1, 1, 1, 1, 0, 0, 1, 0}, {}};
    auto right = eval::scoreMask(mask, truth);
    ASSERT_TRUE(right) << right.error();
    EXPECT_EQ(right->figures.validPx, 6); // the sky and the surface facing away are not counted
    EXPECT_EQ(right->figures.wrongPct, 0.0);
    // One lit pixel drawn shadowed and one shadowed drawn lit (0.49 and 0.5: the threshold).
    mask.visibility = {1, 0.49f, 1, 1, 0.5f, 0, 1, 0};
    auto wrong = eval::scoreMask(mask, truth);
    ASSERT_TRUE(wrong);
    using P = eval::PixelClass;
    const std::vector<P> classes = {P::LitCorrect, P::FalseShadow,   P::LitCorrect,   P::LitCorrect,
                                    P::FalseLit,   P::ShadowCorrect, P::NotEvaluated, P::NotEvaluated};
    EXPECT_EQ(wrong->classes, classes);
    EXPECT_DOUBLE_EQ(wrong->figures.falseShadowPct, 100.0 / 6.0);
    EXPECT_DOUBLE_EQ(wrong->figures.falseLitPct, 100.0 / 6.0);
    // No shadow map is known: no sampling figures.
    EXPECT_TRUE(std::isnan(wrong->pixelsPerTexel[0]));
    EXPECT_EQ(wrong->figures.pixelsPerTexelP50, 0.0);
    EXPECT_EQ(wrong->figures.undersampledPct, 0.0);
}

TEST(ScoreTest, PixelsTheMaskDidNotDrawAreExcludedAndAnotherCameraIsRefused) {
    const eval::TruthBuffers truth = eightPixels();
    // Pixel 1 not drawn (a surface the engine lost): excluded, however it is shaded.
    eval::ShadowMask mask{8, 1, {1, 0, 1, 1, 0, 0, 1, 0}, {1, 0, 1, 1, 1, 1, 0, 1}};
    auto scored = eval::scoreMask(mask, truth, {.maxDrawnMismatch = 0.2});
    ASSERT_TRUE(scored) << scored.error();
    EXPECT_EQ(scored->classes[1], eval::PixelClass::Excluded);
    EXPECT_EQ(scored->figures.excludedPx, 1);
    EXPECT_EQ(scored->figures.validPx, 5);
    EXPECT_EQ(scored->figures.wrongPct, 0.0);
    // One pixel in eight disagreeing is 12.5 %: over the default's 2 %.
    auto refused = eval::scoreMask(mask, truth);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("12.5 %"), std::string::npos) << refused.error();
    // Another size is refused, naming both.
    mask = {4, 2, std::vector<float>(8, 1.0f), {}};
    auto resized = eval::scoreMask(mask, truth);
    ASSERT_FALSE(resized);
    EXPECT_NE(resized.error().find("4×2"), std::string::npos) << resized.error();
    EXPECT_NE(resized.error().find("8×1"), std::string::npos) << resized.error();
}

TEST(ScoreTest, MasksLoadFromSixteenBitPngsAtTheirFullDepth) {
    const auto file = tempFile("shadowkit_mask16.png");
    // 0x8001 / 65535 is 0.500008: one step above a half, which 8 bits cannot hold.
    writeBytes(file, greyPng16(3, 2, {0, 0x8001, 65535, 65535, 0x7FFF, 1}));
    auto mask = eval::loadShadowMask(file);
    ASSERT_TRUE(mask) << mask.error();
    ASSERT_EQ(mask->width, 3);
    ASSERT_EQ(mask->height, 2);
    EXPECT_FLOAT_EQ(mask->visibility[1], float(0x8001) / 65535.0f);
    EXPECT_GT(mask->visibility[1], 0.5f);
    EXPECT_LT(mask->visibility[4], 0.5f);
    EXPECT_TRUE(mask->drawn.empty()); // no alpha: every pixel counts as drawn
    std::filesystem::remove(file);
}

TEST(ScoreTest, EightBitPngsGiveTheirRedChannelAndAlphaMarksWhatWasDrawn) {
    const auto file = tempFile("shadowkit_mask8.png");
    scene::Image image(2, 1);
    const uint8_t lit[4] = {255, 0, 0, 255}, nothing[4] = {0, 255, 255, 0};
    std::memcpy(image.pixel(0, 0), lit, 4);
    std::memcpy(image.pixel(1, 0), nothing, 4);
    ASSERT_TRUE(scene::writePng(image, file));
    auto mask = eval::loadShadowMask(file);
    ASSERT_TRUE(mask) << mask.error();
    EXPECT_EQ(mask->visibility, (std::vector<float>{1.0f, 0.0f}));
    EXPECT_EQ(mask->drawn, (std::vector<uint8_t>{1, 0}));
    std::filesystem::remove(file);
}

TEST(ScoreTest, NpyMasksLoadAndHostileOnesAreRefusedInOneLine) {
    const auto file = tempFile("shadowkit_mask.npy");
    const std::vector<float> values = {0.0f, 0.25f, 1.0f, 0.75f, 0.5f, 1.0f};
    ASSERT_TRUE(eval::writeNpy(file, values, {2, 3}));
    auto mask = eval::loadShadowMask(file);
    ASSERT_TRUE(mask) << mask.error();
    EXPECT_EQ(mask->width, 3);
    EXPECT_EQ(mask->height, 2);
    EXPECT_EQ(mask->visibility, values);

    auto refused = [&](const std::string& what) {
        auto m = eval::loadShadowMask(file);
        EXPECT_FALSE(m) << what;
        if (!m) {
            EXPECT_EQ(m.error().find('\n'), std::string::npos) << m.error();
            EXPECT_NE(m.error().find(file.string()), std::string::npos) << m.error();
            EXPECT_LT(m.error().size(), file.string().size() + 200) << "a line, not a page: " << what;
        }
    };
    ASSERT_TRUE(eval::writeNpy(file, std::vector<float>{0.5f, 1.5f}, {1, 2}));
    refused("a value past 1");
    ASSERT_TRUE(eval::writeNpy(file, std::vector<float>{0.5f, NAN}, {1, 2}));
    refused("NaN");
    ASSERT_TRUE(eval::writeNpy(file, std::vector<float>(8, 1.0f), {2, 2, 2}));
    refused("three dimensions");
    ASSERT_TRUE(eval::writeNpy(file, std::vector<uint32_t>(4, 1u), {2, 2}));
    refused("uint32");
    ASSERT_TRUE(eval::writeNpy(file, std::vector<float>(6, 1.0f), {2, 3}));
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    writeBytes(file, bytes.substr(0, bytes.size() - 3));
    refused("truncated data");
    writeBytes(file, bytes.substr(0, 9));
    refused("truncated header");
    std::string huge = bytes;
    huge.replace(huge.find("(2,3)"), 5, "(99999,99999)");
    writeBytes(file, huge);
    refused("a shape past the limits");
    // Headers written by hand, each over 24 bytes of float32 data (a valid 2 × 3 mask).
    const auto withHeader = [&](const std::string& dict) {
        const std::string header = dict + "\n";
        std::string npy = std::string("\x93NUMPY\x01\x00", 8) + char(header.size() & 0xff) + char(header.size() >> 8);
        writeBytes(file, npy + header + bytes.substr(bytes.size() - 24));
    };
    withHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }");
    EXPECT_TRUE(eval::loadShadowMask(file)) << "the hand-written header itself";
    // libstdc++'s std::regex recursed once a character and overflowed the stack on this one.
    withHeader("{'descr': '" + std::string(60000, 'x') + "', 'fortran_order': False, 'shape': (2, 3), }");
    refused("a 60,000-character dtype");
    withHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::string(60000, ' ') + "2, 3), }");
    EXPECT_TRUE(eval::loadShadowMask(file)) << "a shape after 60,000 spaces";
    withHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, x, 3), }"); // once read as (2, 3)
    refused("a dimension that is not a number");
    withHeader("{'descr': '<f4', 'shape': (2, 3), }");
    refused("no fortran_order");
    withHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2,\n }\n 'shape': (2, 3), }"); // fuzz_npy
    refused("a shape running over a newline to the next bracket");
    std::filesystem::remove(file);
}
