#include "shadowkit/scene/file_write.h"

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace shadowkit::scene {

namespace fs = std::filesystem;

namespace {

core::Error cannotWrite(const fs::path& file, const std::string& why) {
    return core::makeError(file.string() + ": cannot write (" + why + ")");
}

// Writes all of `bytes` to an open descriptor (write() may write less than asked). Returns 0 or
// the errno of the first failure.
int writeAll(int fd, std::string_view bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : EIO;
        done += size_t(n);
    }
    return 0;
}

} // namespace

core::Status prepareOutputDirectory(const fs::path& file) {
    const fs::path dir = file.parent_path();
    if (dir.empty()) return core::Ok{};
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return core::Ok{};
    fs::create_directories(dir, ec);
    if (ec) return cannotWrite(file, "cannot create directory '" + dir.string() + "': " + ec.message());
    return core::Ok{};
}

core::Status writeFile(const fs::path& file, std::string_view bytes) {
    return writeFileInPieces(file, [bytes](const ByteSink& write) { write(bytes); });
}

core::Status writeFileInPieces(const fs::path& file, const std::function<void(const ByteSink&)>& produce) {
    if (file.empty()) return core::makeError("cannot write a file with an empty name");
    // Each piece written as it comes; the first failure's errno kept, and later pieces refused.
    int error = 0;
    const auto writeTo = [&error, &produce](int fd) {
        produce([fd, &error](std::string_view piece) {
            if (error == 0) error = writeAll(fd, piece);
            return error == 0;
        });
    };
    std::error_code ec;
    const fs::file_status existing = fs::status(file, ec);
    if (fs::exists(existing) && !fs::is_regular_file(existing)) {
        if (fs::is_directory(existing)) return cannotWrite(file, "it is a directory");
        const int fd = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd < 0) return cannotWrite(file, std::strerror(errno));
        writeTo(fd);
        if (::close(fd) != 0 && error == 0) return cannotWrite(file, std::strerror(errno));
        if (error != 0) return cannotWrite(file, std::strerror(error));
        return core::Ok{};
    }
    if (auto s = prepareOutputDirectory(file); !s) return s;

    // The temporary file lives in the target's directory, so the rename stays on one file
    // system and is atomic; the process id keeps two writers of the same name apart.
    fs::path temporary = file;
    std::string name = file.filename().string();
    name.insert(0, 1, '.');
    name.append(".tmp-").append(std::to_string(::getpid()));
    temporary.replace_filename(name);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) return cannotWrite(file, std::strerror(errno));
    writeTo(fd);
    // A full disk on a delayed-allocation file system reports only at fsync.
    if (error == 0 && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error == 0 && ::rename(temporary.c_str(), file.c_str()) != 0) error = errno;
    if (error != 0) {
        ::unlink(temporary.c_str());
        return cannotWrite(file, std::strerror(error));
    }
    return core::Ok{};
}

} // namespace shadowkit::scene
