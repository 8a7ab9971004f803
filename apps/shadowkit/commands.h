// The shadowkit subcommands. Each registers its subcommand and options on the app and
// returns it with the function that runs it (exit code: 0 success, 1 bad input or failure).
#pragma once

#include "common.h"

#include <CLI/CLI.hpp>

#include <functional>

namespace shadowkit::app {

struct Command {
    CLI::App* subcommand = nullptr;
    std::function<int()> run;
};

Command addRenderCommand(CLI::App& app);
Command addSetupCommand(CLI::App& app);
Command addExportCommand(CLI::App& app);
class EvalSession;
// With a session (eval --serve), the scene and measurer are taken from it and left in it.
Command addEvalCommand(CLI::App& app, EvalSession* session = nullptr);
Command addAnalyzeCommand(CLI::App& app);
Command addCompareCommand(CLI::App& app);
Command addBenchCommand(CLI::App& app);
Command addSweepCommand(CLI::App& app);
Command addScoreCommand(CLI::App& app);

} // namespace shadowkit::app
