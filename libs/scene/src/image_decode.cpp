// PNG and JPEG decoding through stb_image (libstb-dev), the one translation unit that holds
// its implementation, and WebP through libwebp (EXT_texture_webp, as common in the wild as the
// two formats glTF itself allows, §3.8.4). Decoded bytes come from files we did not write: the
// header is read and checked against the limits before anything is allocated. KTX2 (the
// container of KHR_texture_basisu) is recognised and named: no Debian library decodes Basis
// Universal, so the glTF reader falls back to the texture's PNG or JPEG or does without it.
//
// Debian 12's stb_image is v2.27, whose JPEG reader writes past its Huffman tables when a DHT
// segment declares more than 256 codes (fuzz_image found it; v2.28 added the check). Until the
// package has it, every DHT segment is checked here before stb sees the file; likewise a PNG's
// chunk list (below), and its JPEG bit reader's refill (next).
#include "shadowkit/scene/image.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#define STB_IMAGE_STATIC // private to this file: libtinygltf may carry its own copy
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
// Zeroed allocations: a JPEG scan may name a Huffman table no DHT defined, and stb 2.27 then
// decodes with the table's uninitialised memory (indices out of bounds, fuzz_image). A zeroed
// table has no codes: decoding with it fails cleanly.
#define STBI_MALLOC(bytes) std::calloc(1, bytes)
#define STBI_REALLOC(pointer, bytes) std::realloc(pointer, bytes)
#define STBI_FREE(pointer) std::free(pointer)
// stb 2.27's JPEG bit reader takes some codes (its fast AC path) without checking that its buffer
// holds them. When a refill stops at a marker that cuts a scan short (a corrupt file), the count of
// buffered bits goes negative and the next refill shifts by `24 - code_bits` >= 32, which is
// undefined (fuzz_image, fuzz/corpus/image/scan-cut-by-marker.jpg). Every refill is routed through
// refillJpegBits() below, which does what 2.28 does there: reads on as zeros. The renaming works
// on the first token inside the parentheses: the definition's `stbi__jpeg *j` becomes
// stbRefillJpegBits, stb's own refill, and the calls' `j` or `z` become refillJpegBits; a call
// with any other argument fails to compile rather than escape the check.
template <class Jpeg>
static void refillJpegBits(Jpeg* jpeg);
#define stbi__grow_buffer_unsafe(first) SHADOWKIT_STB_REFILL_##first)
#define SHADOWKIT_STB_REFILL_stbi__jpeg stbRefillJpegBits(stbi__jpeg
#define SHADOWKIT_STB_REFILL_j refillJpegBits(j
#define SHADOWKIT_STB_REFILL_z refillJpegBits(z
// Likewise a progressive JPEG's DC scan: stb 2.27 adds each block's difference to the component's
// predictor with no bound, and a corrupt scan drives it past what `dc << succ_low` holds in an int
// (signed overflow, undefined; fuzz_image in CI, fuzz/corpus/image/dc-predictor-overflow.jpg).
// Every DC block goes through decodeBlockProgDc() below, which refuses a predictor outside
// ±2^15 first, as 2.28 refuses the overflow itself: then |dc| < 2^16 (a difference has at most
// 15 bits) and dc · 2^13 (succ_low <= 13, checked at the SOS) fits. A real JPEG's DC predictor
// stays within 11 bits.
template <class Jpeg, class Huffman>
static int decodeBlockProgDc(Jpeg* jpeg, short* data, Huffman* hdc, int b);
#define stbi__jpeg_decode_block_prog_dc(first, ...) SHADOWKIT_STB_PROG_DC_##first, __VA_ARGS__)
#define SHADOWKIT_STB_PROG_DC_stbi__jpeg stbDecodeBlockProgDc(stbi__jpeg
#define SHADOWKIT_STB_PROG_DC_z decodeBlockProgDc(z
// And a baseline JPEG's blocks: the same unbounded predictor, then `dc * dequant[0]` in an int. A
// DQT of 16-bit precision (which the standard allows for 12-bit samples only, and 2.27 takes for
// 8-bit) holds quantisers up to 65535, and a DC of 49151 times 65535 overflows
// (fuzz/corpus/image/dc-dequant-overflow.jpg). Every block goes through decodeBlock() below,
// which refuses a predictor outside ±2^15 and a DC quantiser of 2^15 or more: then |dc| < 2^16
// and |dc · q| < 2^31. 2.28 refuses any product outside a short. The AC products fit as they
// are: (2^15 − 1) · (2^16 − 1) < 2^31.
template <class Jpeg, class Huffman, class FastAc, class Quantiser>
static int decodeBlock(Jpeg* jpeg, short* data, Huffman* hdc, Huffman* hac, FastAc* fac, int b, Quantiser* dequant);
#define stbi__jpeg_decode_block(first, ...) SHADOWKIT_STB_BLOCK_##first, __VA_ARGS__)
#define SHADOWKIT_STB_BLOCK_stbi__jpeg stbDecodeBlock(stbi__jpeg
#define SHADOWKIT_STB_BLOCK_z decodeBlock(z
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#undef stbi__grow_buffer_unsafe
#undef SHADOWKIT_STB_REFILL_stbi__jpeg
#undef SHADOWKIT_STB_REFILL_j
#undef SHADOWKIT_STB_REFILL_z
#undef stbi__jpeg_decode_block_prog_dc
#undef SHADOWKIT_STB_PROG_DC_stbi__jpeg
#undef SHADOWKIT_STB_PROG_DC_z
#undef stbi__jpeg_decode_block
#undef SHADOWKIT_STB_BLOCK_stbi__jpeg
#undef SHADOWKIT_STB_BLOCK_z

template <class Jpeg>
static void refillJpegBits(Jpeg* jpeg) {
    // A negative count: every buffered bit was taken, then zeros past them; the buffer is empty.
    if (jpeg->code_bits < 0) jpeg->code_bits = 0;
    stbRefillJpegBits(jpeg);
}

// A DC predictor within ±2^15 (see above): a real JPEG's stays within 11 bits.
template <class Jpeg>
static bool dcPredictorInRange(const Jpeg* jpeg, int b) {
    constexpr int kMaxPredictor = 1 << 15;
    const int predictor = jpeg->img_comp[b].dc_pred;
    return predictor > -kMaxPredictor && predictor < kMaxPredictor;
}

template <class Jpeg, class Huffman>
static int decodeBlockProgDc(Jpeg* jpeg, short* data, Huffman* hdc, int b) {
    if (!dcPredictorInRange(jpeg, b)) return stbi__err("bad DC", "Corrupt JPEG");
    return stbDecodeBlockProgDc(jpeg, data, hdc, b);
}

template <class Jpeg, class Huffman, class FastAc, class Quantiser>
static int decodeBlock(Jpeg* jpeg, short* data, Huffman* hdc, Huffman* hac, FastAc* fac, int b, Quantiser* dequant) {
    if (!dcPredictorInRange(jpeg, b)) return stbi__err("bad DC", "Corrupt JPEG");
    if (dequant[0] >= 1 << 15) return stbi__err("bad DC quantiser", "Corrupt JPEG");
    return stbDecodeBlock(jpeg, data, hdc, hac, fac, b, dequant);
}

#include <webp/decode.h>

namespace shadowkit::scene {

namespace {

// Whether every Huffman table a JPEG could define holds at most 256 codes (ITU T.81 §B.2.4.2:
// a DHT segment is a length, then tables of class/id, 16 counts and the counted symbols). Every
// 0xFF 0xC4 in the file is read as stb would read a DHT segment there — table after table while
// the length lasts, bytes past the end read as 0 — a superset of the segments stb can reach
// (it skips stray bytes between markers), so none escapes the check.
bool jpegHuffmanTablesFit(std::span<const uint8_t> b) {
    auto at = [&](size_t k) -> size_t { return k < b.size() ? b[k] : 0; };
    for (size_t i = 0; i + 1 < b.size(); ++i) {
        if (b[i] != 0xFF || b[i + 1] != 0xC4) continue;
        long remaining = long(at(i + 2) << 8 | at(i + 3)) - 2;
        for (size_t t = i + 4; remaining > 0 && t < b.size();) {
            size_t codes = 0;
            for (size_t k = 1; k <= 16; ++k) codes += at(t + k);
            if (codes > 256) return false;
            remaining -= long(17 + codes);
            t += 17 + codes;
        }
    }
    return true;
}

// What is wrong with a PNG's chunk list before stb reads it, or nullptr. Chunks: a 4-byte
// big-endian length, a 4-byte type, the data and a 4-byte CRC (ISO 15948 §5.3). stb 2.27 grows
// its buffer to an IDAT chunk's declared length before it finds the bytes missing (2 GiB for a
// 100-byte file, fuzz_image), and copies an empty first IDAT with memcpy(nullptr, p, 0), which
// is undefined; no encoder writes either, so both are refused as corrupt.
const char* pngChunkProblem(std::span<const uint8_t> b) {
    bool sawData = false;
    for (size_t i = 8; i + 8 <= b.size();) {
        const size_t length = size_t(b[i]) << 24 | size_t(b[i + 1]) << 16 | size_t(b[i + 2]) << 8 | b[i + 3];
        const auto type = b.subspan(i + 4, 4);
        if (length > b.size() - (i + 8)) return "a chunk runs past the end of the file";
        const bool data = std::equal(type.begin(), type.end(), "IDAT");
        if (data && !sawData && length == 0) return "an empty first IDAT chunk";
        sawData = sawData || data;
        if (std::equal(type.begin(), type.end(), "IEND")) break;
        i += 12 + length;
    }
    return nullptr;
}

// stb's reason for a failure, printable: it can quote the file's bytes (an unknown PNG chunk's
// type), and an error stays one line.
std::string failureReason() {
    std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "unknown";
    for (char& c : reason)
        if (c < 0x20 || c > 0x7E) c = '?';
    return reason;
}

// The image's size against shadowkit's limits (image.h), or an error naming it.
core::Status checkSize(const std::string& name, const char* format, int width, int height) {
    if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
        int64_t(width) * height > kMaxImageTexels)
        return core::makeError(name + ": " + std::to_string(width) + "×" + std::to_string(height) + " " + format +
                               " is over shadowkit's limits (sides up to " + std::to_string(kMaxImageSide) +
                               ", 2^26 texels)");
    return core::Ok{};
}

// WebP (RIFF container, "WEBP" form type): lossy, lossless, with or without alpha; animated
// WebP has no single image to take and is refused.
core::Result<Image> decodeWebp(std::span<const uint8_t> bytes, const std::string& name) {
    WebPBitstreamFeatures features{};
    if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK)
        return core::makeError(name + ": unreadable WebP header");
    if (features.has_animation) return core::makeError(name + ": an animated WebP, not one image");
    if (auto s = checkSize(name, "WebP", features.width, features.height); !s) return s.errorInfo();
    Image image(features.width, features.height);
    if (!WebPDecodeRGBAInto(bytes.data(), bytes.size(), image.rgba.data(), image.rgba.size(), image.width * 4))
        return core::makeError(name + ": corrupt or truncated WebP");
    return image;
}

// PNG's eight-byte signature (ISO 15948 §5.2).
bool isPng(std::span<const uint8_t> bytes) {
    static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    return bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin());
}

// The checks before stb reads a PNG or JPEG: the encoded size, the PNG's chunk list or the
// JPEG's Huffman tables, the header and the decoded size against the limits. Sets the header's
// width, height and channels.
core::Status checkStbInput(std::span<const uint8_t> bytes, const std::string& name, bool png, int& width, int& height,
                           int& channels) {
    const char* format = png ? "PNG" : "JPEG";
    if (const char* problem = png ? pngChunkProblem(bytes) : nullptr)
        return core::makeError(name + ": corrupt or truncated PNG (" + problem + ")");
    if (!png && !jpegHuffmanTablesFit(bytes))
        return core::makeError(name + ": corrupt JPEG (a Huffman table with more than 256 codes)");
    // stb's own side limit (2^24) is left alone: ours is checked here, with a message that says so.
    if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &width,
                               &height, &channels))
        return core::makeError(name + ": unreadable " + format + " header (" + failureReason() + ")");
    return checkSize(name, format, width, height);
}

// The size every decoder accepts before it looks at the bytes.
core::Status checkEncodedSize(std::span<const uint8_t> bytes, const std::string& name) {
    if (bytes.empty()) return core::makeError(name + ": the image is empty");
    if (bytes.size() > size_t(1) << 30) return core::makeError(name + ": the encoded image is over 1 GiB");
    return core::Ok{};
}

} // namespace

core::Result<LevelImage> decodeLevels(std::span<const uint8_t> bytes, std::string_view what) {
    const std::string name(what);
    if (auto s = checkEncodedSize(bytes, name); !s) return s.errorInfo();
    if (!isPng(bytes)) return core::makeError(name + ": not a PNG (a mask must be lossless: PNG of 8 or 16 bits)");
    int width = 0, height = 0, channels = 0;
    if (auto s = checkStbInput(bytes, name, true, width, height, channels); !s) return s.errorInfo();
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = static_cast<int>(bytes.size());
    const bool sixteen = stbi_is_16_bit_from_memory(data, length) != 0;
    const bool alpha = channels == 2 || channels == 4;
    const size_t n = size_t(width) * size_t(height);
    LevelImage image{width, height, std::vector<float>(n), alpha ? std::vector<float>(n) : std::vector<float>()};
    // Decoded with the file's own channels, so grey stays one channel and alpha is where it is.
    int w = 0, h = 0, c = 0;
    auto fill = [&](const auto* pixels, float scale) {
        if (w != width || h != height) return; // not what its header said: left at zero, refused below
        for (size_t i = 0; i < n; ++i) {
            image.level[i] = float(pixels[i * size_t(channels)]) * scale;
            if (alpha) image.alpha[i] = float(pixels[i * size_t(channels) + size_t(channels - 1)]) * scale;
        }
    };
    if (sixteen) {
        stbi_us* pixels = stbi_load_16_from_memory(data, length, &w, &h, &c, channels);
        if (!pixels) return core::makeError(name + ": corrupt or truncated PNG (" + failureReason() + ")");
        fill(pixels, 1.0f / 65535.0f);
        stbi_image_free(pixels);
    } else {
        stbi_uc* pixels = stbi_load_from_memory(data, length, &w, &h, &c, channels);
        if (!pixels) return core::makeError(name + ": corrupt or truncated PNG (" + failureReason() + ")");
        fill(pixels, 1.0f / 255.0f);
        stbi_image_free(pixels);
    }
    if (w != width || h != height || c != channels)
        return core::makeError(name + ": corrupt PNG (its pixels are not what its header declares)");
    return image;
}

core::Result<Image> decodeImage(std::span<const uint8_t> bytes, std::string_view what) {
    const std::string name(what);
    if (auto s = checkEncodedSize(bytes, name); !s) return s.errorInfo();
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = static_cast<int>(bytes.size());
    // The signatures: PNG's, JPEG's start-of-image marker and the next marker's 0xFF.
    const bool png = isPng(bytes);
    const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
    // WebP: "RIFF", a 4-byte size, "WEBP"; KTX2: its 12-byte identifier («KTX 20»\r\n\x1A\n).
    const auto at = [&](size_t offset, std::string_view tag) {
        return bytes.size() >= offset + tag.size() &&
               std::equal(tag.begin(), tag.end(), bytes.begin() + std::ptrdiff_t(offset),
                          [](char t, uint8_t b) { return uint8_t(t) == b; }); // bytes past 0x7F, unsigned
    };
    if (at(0, "RIFF") && at(8, "WEBP")) return decodeWebp(bytes, name);
    if (at(0, "\xABKTX 20\xBB\r\n\x1A\n"))
        return core::makeError(name + ": a KTX2 (Basis Universal) texture, which shadowkit cannot decode");
    if (!png && !jpeg) return core::makeError(name + ": not a PNG, JPEG or WebP image");
    const char* format = png ? "PNG" : "JPEG";
    int width = 0, height = 0, channels = 0;
    if (auto s = checkStbInput(bytes, name, png, width, height, channels); !s) return s.errorInfo();
    int w = 0, h = 0;
    stbi_uc* pixels = stbi_load_from_memory(data, length, &w, &h, &channels, 4);
    if (!pixels) return core::makeError(name + ": corrupt or truncated " + format + " (" + failureReason() + ")");
    Image image(w, h);
    std::copy(pixels, pixels + image.rgba.size(), image.rgba.begin());
    stbi_image_free(pixels);
    return image;
}

} // namespace shadowkit::scene
