// The one table of a frame's options: every field of FrameConfig, gl::RenderSettings and the
// technique's core::ShadowSetupInputs, each once, with the flag that sets it (or where its value
// comes from when no flag does: the view, the scene), the error field its check reports, its
// range and the layer whose validate() checks it. Front ends read it instead of keeping tables of
// their own: the CLI names a library error's flag through optionForField, and tests hold the CLI's
// flags, the docs' option list and the structs' fields to it (a field added without a row, or a
// row whose flag no command takes, fails a test).
#pragma once

#include <span>
#include <string_view>

namespace shadowkit::frame {

// Where an option's range is checked: exactly one validate() of that library.
enum class CheckedIn {
    Core,  // core::validateOptions, core::validate(...) and friends
    Gl,    // gl::validate(...), gl::validateVirtualSettings, the renderer's frame check
    Frame, // frame::FrameConfig::check and what it calls of its own
    None,  // any value is valid (a switch, a choice parsed by name)
};

struct OptionRow {
    // The struct member, from its root: "RenderSettings.blur.radiusPixels",
    // "ShadowSetupInputs.lispsm.weight", "FrameConfig.fogDensity".
    std::string_view member;
    // The command-line flag (render, eval, compare, bench and the viewer share them); empty when
    // no flag sets it, and then `source` says what does.
    std::string_view flag;
    // The field a failed check names (core::Error::field); empty for CheckedIn::None.
    std::string_view field;
    std::string_view range; // as the check has it: "(0, 16]", "a power of two in [1024, 65536]"
    CheckedIn checkedIn = CheckedIn::None;
    std::string_view source = {}; // with no flag: "each frame's view", "the scene"
};

// Every row, grouped by struct.
std::span<const OptionRow> optionTable();
// The first row whose error field is `field`, or nullptr.
const OptionRow* optionForField(std::string_view field);

} // namespace shadowkit::frame
