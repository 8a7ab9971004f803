// The viewer's options are `render`'s, held as text (StateOptions, the `--state` file's
// form) so that what the viewer shows is what `shadowkit render --state FILE` draws: the
// panel edits the text, and every change is parsed again by the same option groups.
#pragma once

#include "local_light_options.h"
#include "options.h"
#include "state.h"
#include "timeline.h"

#include <memory>

namespace shadowkit::viewer {

struct FrameOptions {
    FrameOptions() { technique.virtualRequestsLate = true; } // an application loop: no frame waits for them
    app::SceneOptions scene;                                 // read once: the viewer keeps the scene it started with
    app::ViewOptions view;
    app::TechniqueOptions technique;
    app::RenderOptions render;
    app::LocalLightOptions lights;
    app::TimelineOptions timeline; // --path, --time, --sun-path (--frames is the viewer's own)

    // Registers every group on `cmd`.
    void addTo(CLI::App& cmd);
};

// The options a state holds, parsed and checked; errors name the option.
core::Result<std::unique_ptr<FrameOptions>> parseFrameOptions(const app::StateOptions& state);

// The long options of `cmd` that a command line gives, as typed (before CLI11 turns a choice
// into its number): each with its values, "true" for a bare flag. Skips those in `skip`;
// the command line must already parse.
app::StateOptions givenOptions(const CLI::App& cmd, const std::vector<std::string>& args,
                               std::initializer_list<const char*> skip);

} // namespace shadowkit::viewer
