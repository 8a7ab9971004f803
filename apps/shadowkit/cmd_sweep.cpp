// shadowkit sweep: grids of eval configurations, resumable, here or on a Dask cluster. The
// sweep is the Python package shadowkit.sweep (its Dask runner needs Python, and one
// implementation serves both doors); this command finds that package and a Python to run it,
// and hands over with SHADOWKIT naming this very program, so the cells run the build the user
// called.
#include "commands.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace shadowkit::app {
namespace {

namespace fs = std::filesystem;

// The package: beside an installed program (a relocatable prefix), else in the build tree that
// built this program; empty when neither has it (built without pybind11).
fs::path pythonPackageRoot(const fs::path& exe) {
    std::error_code ec;
    for (const fs::path& root :
         {(exe.parent_path() / SHADOWKIT_PYTHON_FROM_BIN).lexically_normal(), fs::path(SHADOWKIT_BUILD_PYTHON_DIR)})
        if (fs::exists(root / "shadowkit" / "sweep" / "__main__.py", ec)) return root;
    return {};
}

int runSweep(const std::vector<std::string>& arguments) {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return fail("sweep: cannot find this program's own path (/proc/self/exe)");
    const fs::path root = pythonPackageRoot(exe);
    if (root.empty())
        return fail("sweep: the Python package shadowkit.sweep is not built or installed (it needs pybind11-dev and "
                    "python3-dev at build time)");
    std::string path = root.string();
    if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
    setenv("PYTHONPATH", path.c_str(), 1);
    setenv("SHADOWKIT", exe.c_str(), 1);
    // $SHADOWKIT_PYTHON, else Debian's python3 (the one python3-distributed and python3-matplotlib
    // install into), else the first python3 on PATH.
    std::string python = "python3";
    if (const char* chosen = std::getenv("SHADOWKIT_PYTHON"); chosen && *chosen)
        python = chosen;
    else if (access("/usr/bin/python3", X_OK) == 0)
        python = "/usr/bin/python3";
    std::vector<std::string> argv = {python, "-m", "shadowkit.sweep"};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    std::vector<char*> raw;
    for (std::string& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    std::fflush(stdout);
    execvp(raw[0], raw.data());
    return fail(fmt::format("sweep: cannot run {} ({})", python, std::strerror(errno)));
}

} // namespace

Command addSweepCommand(CLI::App& app) {
    auto arguments = std::make_shared<std::vector<std::string>>();
    CLI::App* cmd = app.add_subcommand(
        "sweep", "Measure a grid of eval configurations against truth, resumable, here or on a Dask cluster "
                 "(python3 -m shadowkit.sweep; shadowkit sweep --help for its options)");
    cmd->prefix_command(); // every argument is the sweep's, --help included
    cmd->set_help_flag();
    return {cmd, [cmd, arguments] {
                *arguments = cmd->remaining();
                return runSweep(*arguments);
            }};
}

} // namespace shadowkit::app
