// shadowkit: render, measure and export shadow set-ups from the command line.
#include "commands.h"
#include "html_reports.h"
#include "state.h"

#include "shadowkit/core/version.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

int main(int argc, char** argv) {
    CLI::App app{"shadowkit: robust real-time shadows for large outdoor worlds", "shadowkit"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "shadowkit " SHADOWKIT_VERSION_STRING);
    const std::vector<shadowkit::app::Command> commands = {
        shadowkit::app::addRenderCommand(app),  shadowkit::app::addEvalCommand(app),
        shadowkit::app::addAnalyzeCommand(app), shadowkit::app::addCompareCommand(app),
        shadowkit::app::addBenchCommand(app),   shadowkit::app::addSetupCommand(app),
        shadowkit::app::addExportCommand(app),  shadowkit::app::addSweepCommand(app),
        shadowkit::app::addScoreCommand(app),
    };

    shadowkit::app::setInvocation(std::vector<std::string>(argv + 1, argv + argc)); // reports print it
    // --state FILE: the saved options of a viewer session, as if typed before the others.
    auto args = shadowkit::app::expandState(std::vector<std::string>(argv + 1, argv + argc));
    if (!args) return shadowkit::app::fail(args.errorInfo());
    for (const shadowkit::app::Command& command : commands)
        if (command.subcommand->get_name() == "render" || command.subcommand->get_name() == "eval")
            command.subcommand->add_option("--state", "options saved by shadowkit-viewer (JSON): given flags win");
    std::reverse(args->begin(), args->end()); // CLI11 takes the vector last argument first

    try {
        app.parse(*args);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, not CLI11's two: what is wrong and where to look.
        return shadowkit::app::parseErrorExit(e);
    }
    for (const shadowkit::app::Command& command : commands)
        if (command.subcommand->parsed()) return command.run();
    return 2;
}
