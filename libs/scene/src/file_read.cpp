#include "shadowkit/scene/file_read.h"

#include <cerrno>
#include <cstring>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace shadowkit::scene {

namespace {

// The descriptor closed on every return.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

// "26 bytes", "4,096 MiB" (rounded up: a size just over a limit never reads as equal to it).
std::string sizeText(uintmax_t bytes) {
    const bool small = bytes < (uintmax_t(1) << 20);
    const std::string digits = std::to_string(small ? bytes : (bytes + (uintmax_t(1) << 20) - 1) >> 20);
    std::string text;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
        text += digits[i];
    }
    return text.append(small ? " bytes" : " MiB");
}

// "NAME: WHY", the one form of every refusal.
core::Error refused(const std::filesystem::path& file, const std::string& why) {
    std::string message = file.string();
    message.append(": ").append(why);
    return core::makeError(message);
}

// A failed open, fstat or read, with errno's reason.
core::Error cannotRead(const std::filesystem::path& file) {
    return refused(file, std::string("cannot be read (") + std::strerror(errno) + ")");
}

// UTF-8 of the UTF-16 `units` (the bytes after the mark), or why they are not UTF-16; `offset`
// is where they start in the file, for the message.
core::Result<std::string> utf8FromUtf16(const std::filesystem::path& file, std::string_view units, bool bigEndian,
                                        size_t offset) {
    if (units.size() % 2 != 0) return refused(file, "UTF-16 text of an odd number of bytes");
    auto unit = [&](size_t i) {
        const auto first = uint32_t(uint8_t(units[i])), second = uint32_t(uint8_t(units[i + 1]));
        return bigEndian ? first << 8 | second : second << 8 | first;
    };
    auto lone = [&](size_t i) {
        return refused(file, "UTF-16 text with a lone surrogate at byte " + std::to_string(offset + i));
    };
    std::string text;
    text.reserve(units.size() / 2);
    for (size_t i = 0; i < units.size(); i += 2) {
        uint32_t c = unit(i);
        if (c >= 0xDC00 && c < 0xE000) return lone(i); // a low surrogate first
        if (c >= 0xD800 && c < 0xDC00) {               // a high one: its low one follows
            const uint32_t low = i + 3 < units.size() ? unit(i + 2) : 0;
            if (low < 0xDC00 || low >= 0xE000) return lone(i);
            c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
            i += 2;
        }
        if (c < 0x80) {
            text += char(c);
        } else if (c < 0x800) {
            text += char(0xC0 | c >> 6), text += char(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            text += char(0xE0 | c >> 12), text += char(0x80 | (c >> 6 & 0x3F)), text += char(0x80 | (c & 0x3F));
        } else {
            text += char(0xF0 | c >> 18), text += char(0x80 | (c >> 12 & 0x3F)), text += char(0x80 | (c >> 6 & 0x3F)),
                text += char(0x80 | (c & 0x3F));
        }
    }
    return text;
}

} // namespace

core::Result<std::string> readFile(const std::filesystem::path& file, uintmax_t maxBytes) {
    // O_NONBLOCK: opening a pipe with no writer returns at once instead of waiting for one; on
    // a regular file it changes nothing. The type is then read from the open descriptor, so a
    // file swapped for a pipe between a check and the open cannot slip through.
    const Descriptor in{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (in.fd < 0) return cannotRead(file);
    struct stat status {};
    if (::fstat(in.fd, &status) != 0) return cannotRead(file);
    if (S_ISDIR(status.st_mode)) return refused(file, "a directory, not a file");
    if (!S_ISREG(status.st_mode)) return refused(file, "a device, pipe or socket, not a file");
    const auto size = static_cast<uintmax_t>(status.st_size);
    if (size > maxBytes) return refused(file, sizeText(size) + ", over the " + sizeText(maxBytes) + " limit");
    std::string bytes(size, '\0');
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(in.fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return cannotRead(file);
        if (n == 0) return refused(file, "shorter than its size said (changed while read?)");
        done += size_t(n);
    }
    return bytes;
}

core::Result<std::string> readTextFile(const std::filesystem::path& file, uintmax_t maxBytes) {
    auto bytes = readFile(file, maxBytes);
    if (!bytes) return bytes;
    const std::string_view view(*bytes);
    if (view.starts_with("\xEF\xBB\xBF")) return std::string(view.substr(3));
    if (view.starts_with("\xFE\xFF")) return utf8FromUtf16(file, view.substr(2), /*bigEndian=*/true, 2);
    if (view.starts_with("\xFF\xFE")) return utf8FromUtf16(file, view.substr(2), /*bigEndian=*/false, 2);
    return bytes;
}

} // namespace shadowkit::scene
