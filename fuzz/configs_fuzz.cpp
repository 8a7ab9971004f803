// `compare --configs`: the text form ("a=1,b=2;c=3", first byte even) or a JSON file (odd), each
// cell through the option groups of `render` exactly as the command parses them, then resolved
// over a small forest into a set-up and local lights: every option parser (vectors, sizes,
// splits, lights, techniques, filters) and the core behind it, with no GL.
#include "configs.h"
#include "frame_config_options.h"
#include "fuzz_support.h"

#include <algorithm>
#include <cstdlib>

namespace {
// Errors echo the user's text as typed (a newline in --configs included); the command line's
// fail() prints them on one line. What must hold here: an error has a message.
void oneLine(const shadowkit::core::Error& e) {
    if (e.message.empty()) std::abort();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace shadowkit;
    if (size == 0 || size > 4096) return 0;
    const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
    const auto cells = app::parseConfigs(data[0] % 2 ? fuzz::writeInput(data + 1, size - 1, ".json").string() : text);
    if (!cells) return oneLine(cells.errorInfo()), 0;
    // Every cell takes the same path, and each builds the command line's whole option table
    // (CLI11's add_option checks each new name against all before it): a 4 KiB input of a hundred
    // cells ran a hundred times the work of one for no new coverage, and as the corpus grew long
    // inputs the target slowed from 320 to 50 runs a second. The parser above still reads them all.
    constexpr std::size_t kCellsTried = 4;
    for (std::size_t i = 0; i < std::min(cells->size(), kCellsTried); ++i) {
        const app::Cell& cell = (*cells)[i];
        const auto o = app::parseCell(cell, "paper", "64x36");
        if (!o) {
            oneLine(o.errorInfo());
            continue;
        }
        const auto view = o->view.resolve(fuzz::smallForest());
        if (!view) {
            oneLine(view.errorInfo());
            continue;
        }
        const auto inputs = o->technique.inputsFor(*view, fuzz::smallForest().wsBounds());
        if (!inputs) {
            oneLine(inputs.errorInfo());
            continue;
        }
        const auto setup = core::computeShadowSetup(*inputs);
        if (setup)
            for (const core::ShadowView& v : setup->views)
                if (!core::isFinite(v.clipFromWorld)) std::abort(); // never a NaN matrix
        const auto config = app::frameConfigOf(o->technique, o->render, o->lights);
        if (!config) {
            oneLine(config.errorInfo());
            continue;
        }
        const auto lighting = frame::localLightingFor(*config, *view, fuzz::smallForest().wsBounds());
        if (!lighting) oneLine(app::withFlagName(lighting.errorInfo()));
    }
    return 0;
}
