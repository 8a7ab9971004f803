// Where the command line and the viewer find their data (views.json, camera paths, golden
// figures): a program's question, answered here rather than in libs/scene, which takes paths.
#include "common.h"

#include <cstdlib>
#include <system_error>

namespace shadowkit::app {

std::filesystem::path dataDirectory() {
    if (const char* env = std::getenv("SHADOWKIT_DATA_DIR")) return env;
    // An installed program, wherever its tree was moved: share/shadowkit relative to its bin/.
    // Checked before the source tree, so an install never reads a checkout's newer data.
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path beside = (exe.parent_path() / SHADOWKIT_DATA_FROM_BIN).lexically_normal();
        if (std::filesystem::exists(beside / "views.json", ec)) return beside;
    }
    const std::filesystem::path source = SHADOWKIT_SOURCE_DATA_DIR;
    if (std::filesystem::exists(source / "views.json", ec)) return source;
    return SHADOWKIT_INSTALL_DATA_DIR;
}

} // namespace shadowkit::app
