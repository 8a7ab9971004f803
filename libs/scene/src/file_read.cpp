#include "shadowkit/scene/file_read.h"

#include <cerrno>
#include <cstring>

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

} // namespace shadowkit::scene
