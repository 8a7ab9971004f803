// `--state` files (what shadowkit-viewer saves with Ctrl+S) through loadState and expandState, as
// the command line reads them before parsing, then the words they become through the option
// groups of `render` (parseCell: every vector, size, light and technique option): a state read is
// only options a frame takes — spelled as long options, never help, version or another state —
// a flag given beside it wins over the file's, and a bad file gives an error with a message.
#include "fuzz_support.h"

#include "configs.h"
#include "state.h"

#include <algorithm>
#include <cstdlib>

namespace {
void hasMessage(const shadowkit::core::Error& e) {
    if (e.message.empty()) std::abort();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace shadowkit;
    if (size > 8192) return 0;
    const std::string file = fuzz::writeInput(data, size, ".json").string();
    const auto words = app::expandState({"render", "--map-size=64", "--state", file, "--size=32x18"});
    if (!words) return hasMessage(words.errorInfo()), 0;
    // The command and the given flags stay where they were, the file's options between them.
    if (words->size() < 3 || words->front() != "render" || (*words)[1] != "--map-size=64" ||
        words->back() != "--size=32x18")
        std::abort();
    app::Cell cell;
    for (size_t i = 2; i + 1 < words->size(); ++i) {
        const std::string& word = (*words)[i];
        const size_t equals = word.find('=');
        if (word.rfind("--", 0) != 0 || equals == std::string::npos) std::abort();
        const std::string name = word.substr(2, equals - 2);
        if (name == "map-size" || name == "size" || name == "state" || name == "help" || name == "version" ||
            name.empty() || !std::ranges::all_of(name, [](char c) {
                return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
            }))
            std::abort(); // a given flag the file repeated, or a word that is not an option of a frame
        cell.emplace_back(name, word.substr(equals + 1));
    }
    // Through the parser the command uses, the first few options (each parse builds the whole
    // option table: fuzz_configs says why a long input is not worth more).
    if (cell.size() > 16) cell.resize(16);
    const auto parsed = app::parseCell(cell, "paper", "32x18");
    if (!parsed) hasMessage(parsed.errorInfo());
    return 0;
}
