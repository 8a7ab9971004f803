#include "frame_options.h"

#include <fmt/format.h>

#include <algorithm>

namespace shadowkit::viewer {

void FrameOptions::addTo(CLI::App& cmd) {
    scene.addTo(cmd);
    view.addTo(cmd);
    technique.addTo(cmd);
    render.addTo(cmd);
    lights.addTo(cmd);
    timeline.addTo(cmd, false);
}

core::Result<std::unique_ptr<FrameOptions>> parseFrameOptions(const app::StateOptions& state) {
    auto options = std::make_unique<FrameOptions>();
    CLI::App app{"frame"};
    options->addTo(app);
    std::vector<std::string> argv;
    for (const auto& [name, values] : state)
        for (const std::string& v : values) argv.push_back("--" + name + "=" + v);
    std::reverse(argv.begin(), argv.end()); // CLI11 takes the vector last argument first
    try {
        app.parse(argv);
    } catch (const CLI::ParseError& e) {
        return core::makeError(e.what());
    }
    if (auto s = options->technique.check(/*measuresFrames=*/true, /*takesAuto=*/true); !s) return s.errorInfo();
    if (auto s = options->render.check(); !s) return s.errorInfo();
    return options;
}

app::StateOptions givenOptions(const CLI::App& cmd, const std::vector<std::string>& args,
                               std::initializer_list<const char*> skip) {
    app::StateOptions out;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& word = args[i];
        if (word.rfind("--", 0) != 0) continue;
        const size_t eq = word.find('=');
        const std::string name = word.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
        const CLI::Option* option = cmd.get_option_no_throw("--" + name);
        if (!option) continue;
        std::string value = "true"; // a bare flag
        if (eq != std::string::npos)
            value = word.substr(eq + 1);
        else if (option->get_expected_min() > 0 && i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0)
            value = args[++i];
        if (std::find_if(skip.begin(), skip.end(), [&](const char* s) { return name == s; }) != skip.end()) continue;
        out[name].push_back(value);
    }
    return out;
}

} // namespace shadowkit::viewer
