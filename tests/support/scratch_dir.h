// Where a test writes its files. CTest runs each test as a process of its own, several at
// once (`ctest -j`), so a file name two tests share is a race: one test reads the other's file
// half-written, or finds it removed (the two MeshMergeTest cases both wrote
// shadowkit_town.gltf, and both failed together on a faster machine). Each test process gets a
// directory of its own under the system's temporary directory, removed with all it holds when
// the process ends.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace shadowkit::test_support {

class ScratchDir {
public:
    ScratchDir() : m_path(std::filesystem::temp_directory_path() / ("shadowkit-test-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(m_path);
        std::filesystem::create_directories(m_path);
    }
    ~ScratchDir() {
        std::error_code ignored; // a process ending cannot report a directory it could not remove
        std::filesystem::remove_all(m_path, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

// This process's scratch directory, made on first use.
inline const std::filesystem::path& scratchDir() {
    static const ScratchDir dir;
    return dir.path();
}

} // namespace shadowkit::test_support
