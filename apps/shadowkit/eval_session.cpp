#include "eval_session.h"

#include "commands.h"

#include "shadowkit/scene/animation.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace shadowkit::app {

namespace {

// Everything the scene is built from, and the moment its movers stand at; a scene file's
// modification time too, so a file rewritten between requests is loaded again.
std::string keyOf(const SceneOptions& o, double time) {
    std::string file;
    if (o.scene != "forest") {
        std::error_code ec;
        file = std::to_string(std::filesystem::last_write_time(o.scene, ec).time_since_epoch().count());
    }
    return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}", o.scene, file, o.seed, o.trees, o.terrainSize, o.terrainResolution,
                       o.movers, o.worldOffset, time);
}

} // namespace

core::Status EvalSession::prepare(const SceneOptions& options, double time) {
    const std::string key = keyOf(options, time);
    if (m_measurer && key == m_key) return core::Ok{};
    reset();
    auto loaded = options.load(/*verbose=*/true, time);
    if (!loaded) return loaded.errorInfo();
    m_scene = std::make_unique<scene::Scene>(std::move(loaded).value());
    scene::animate(*m_scene, time); // movers where they are at --time (t = 0: where they stand)
    auto measurer = measure::Measurer::createHeadless(*m_scene);
    if (!measurer) {
        reset();
        return measurer.errorInfo();
    }
    m_measurer = std::move(measurer).value();
    fmt::print(stderr, "ray tracer: built in {:.2f} s\n", m_measurer->rayTracerBuildSeconds());
    m_key = key;
    return core::Ok{};
}

void EvalSession::reset() {
    m_measurer.reset(); // before the scene it points into
    m_scene.reset();
    m_key.clear();
}

namespace {

int serveOne(const std::string& line, EvalSession& session) {
    const nlohmann::json request = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (request.is_discarded() || !request.is_array())
        return fail("--serve: a request is one line holding a JSON array of eval arguments");
    std::vector<std::string> arguments;
    for (const nlohmann::json& a : request) {
        if (!a.is_string()) return fail("--serve: a request's arguments are strings");
        arguments.push_back(a.get<std::string>());
    }
    if (std::find(arguments.begin(), arguments.end(), "--serve") != arguments.end())
        return fail("--serve: a request cannot serve in turn");
    CLI::App app;
    const Command eval = addEvalCommand(app, &session);
    arguments.insert(arguments.begin(), "eval");
    std::reverse(arguments.begin(), arguments.end()); // CLI11 takes the vector last argument first
    try {
        app.parse(arguments); // consumes `arguments`
    } catch (const CLI::CallForHelp&) {
        return fail("--serve: --help is not an evaluation");
    } catch (const CLI::ParseError& e) {
        return parseErrorExit(e);
    }
    const int code = eval.run();
    if (code != 0) session.reset(); // a failure part-way may leave GL state behind: start afresh
    return code;
}

} // namespace

int serveEvaluations() {
    EvalSession session;
    for (std::string line; std::getline(std::cin, line);) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const int code = serveOne(line, session);
        std::fflush(stderr);
        fmt::print("\nshadowkit-serve: exit {}\n", code);
        std::fflush(stdout);
    }
    return 0;
}

} // namespace shadowkit::app
