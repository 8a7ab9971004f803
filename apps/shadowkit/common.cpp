#include "commands.h"

#include <fmt/format.h>

namespace shadowkit::app {

int fail(const std::string& message) {
    fmt::print(stderr, "shadowkit: error: {}\n", message);
    return 1;
}

} // namespace shadowkit::app
