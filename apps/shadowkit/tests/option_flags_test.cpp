// The command line against the one table of options (frame/option_table.h): every flag the table
// names is taken by `render` (and its shared option groups: eval, compare, bench and the viewer
// use the same ones) and listed in docs/commands.md; every option the render command takes for
// a frame field is in the table.
#include "local_light_options.h"
#include "options.h"
#include "timeline.h"

#include "shadowkit/frame/option_table.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

using namespace shadowkit;

namespace {

// A command with every option group `render` has, and `setup`'s scene box.
struct RenderLikeCommand {
    CLI::App app{"options"};
    app::BoundsOptions bounds;
    app::SceneOptions scene;
    app::ViewOptions view;
    app::TechniqueOptions technique;
    app::RenderOptions render;
    app::TimelineOptions timeline;
    app::LocalLightOptions lights;
    RenderLikeCommand() {
        bounds.addTo(app);
        scene.addTo(app);
        view.addTo(app);
        technique.addTo(app);
        render.addTo(app);
        timeline.addTo(app);
        lights.addTo(app);
    }
};

} // namespace

TEST(OptionFlagsTest, EveryFlagOfTheTableIsTakenByTheCommandLine) {
    RenderLikeCommand command;
    for (const frame::OptionRow& row : frame::optionTable()) {
        if (row.flag.empty()) continue;
        EXPECT_NE(command.app.get_option_no_throw(std::string(row.flag)), nullptr)
            << row.member << ": " << row.flag << " is in the table but no command takes it";
    }
}

TEST(OptionFlagsTest, EveryFrameFlagOfTheCommandLineIsInTheTable) {
    // The technique, render and local-light groups set frame fields only; each of their flags
    // has a row (the scene, view and timeline groups choose what is drawn, not how).
    CLI::App app{"options"};
    app::TechniqueOptions technique;
    app::RenderOptions render;
    app::LocalLightOptions lights;
    technique.addTo(app);
    render.addTo(app);
    lights.addTo(app);
    std::set<std::string> tabled;
    for (const frame::OptionRow& row : frame::optionTable()) tabled.insert(std::string(row.flag));
    // Flags that are switches over several rows' values rather than fields of their own.
    const std::set<std::string> aliases = {"--no-cull", "--stabilize", "--cascade-colors"};
    for (const CLI::Option* option : app.get_options()) {
        const std::string flag = option->get_name();
        if (flag.rfind("--", 0) != 0 || flag == "--help") continue;
        EXPECT_TRUE(tabled.count(flag) || aliases.count(flag)) << flag << " sets a frame field but has no row";
    }
}

TEST(OptionFlagsTest, TheCommandsPageListsEveryFlagOfTheTable) {
    std::ifstream page(SHADOWKIT_SOURCE_DIR "/docs/commands.md");
    ASSERT_TRUE(page) << "docs/commands.md";
    std::stringstream text;
    text << page.rdbuf();
    for (const frame::OptionRow& row : frame::optionTable()) {
        if (row.flag.empty()) continue;
        EXPECT_NE(text.str().find("`" + std::string(row.flag)), std::string::npos)
            << row.flag << " is not in docs/commands.md";
    }
}
