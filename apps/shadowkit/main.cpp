// shadowkit: render, measure and export shadow set-ups from the command line.
#include "commands.h"

#include <fmt/format.h>

#include <vector>

int main(int argc, char** argv) {
    CLI::App app{"shadowkit: robust real-time shadows for large outdoor worlds"};
    app.require_subcommand(1);
    const std::vector<shadowkit::app::Command> commands = {
        shadowkit::app::addRenderCommand(app),
        shadowkit::app::addEvalCommand(app),
        shadowkit::app::addAnalyzeCommand(app),
        shadowkit::app::addCompareCommand(app),
        shadowkit::app::addBenchCommand(app),
        shadowkit::app::addSetupCommand(app),
        shadowkit::app::addExportCommand(app),
    };

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, not CLI11's two: what is wrong and where to look. A value that does not
        // convert or is not one of the choices is bad input (exit 1, like every other bad
        // value); an unknown flag or a missing argument is a usage error (exit 2).
        fmt::print(stderr, "shadowkit: error: {} (see shadowkit --help)\n", e.what());
        const bool badValue = dynamic_cast<const CLI::ValidationError*>(&e) || dynamic_cast<const CLI::ConversionError*>(&e);
        return badValue ? 1 : 2;
    }
    for (const shadowkit::app::Command& command : commands)
        if (command.subcommand->parsed()) return command.run();
    return 2;
}
