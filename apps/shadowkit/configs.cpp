// compare --configs (configs.h).
#include "configs.h"

#include "shadowkit/scene/file_read.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <sstream>

namespace shadowkit::app {

// "a=1,b=2;c=3" or a JSON file holding [{"a": 1, "b": 2}, {"c": 3}].
core::Result<std::vector<Cell>> parseConfigs(const std::string& text) {
    std::vector<Cell> cells;
    if (text.size() > 5 && text.substr(text.size() - 5) == ".json") {
        const auto file = scene::readFile(text);
        if (!file) return core::makeError("--configs: " + file.error());
        try {
            const nlohmann::json list = nlohmann::json::parse(*file);
            if (!list.is_array()) return core::makeError("--configs: " + text + ": expected a list of objects");
            for (const auto& object : list) {
                if (!object.is_object()) return core::makeError("--configs: " + text + ": expected a list of objects");
                Cell cell;
                for (const auto& [key, value] : object.items())
                    cell.emplace_back(key, value.is_string() ? value.get<std::string>() : value.dump());
                cells.push_back(cell);
            }
        } catch (const nlohmann::json::exception& e) {
            return core::makeError("--configs: " + text + ": not valid JSON (" + e.what() + ")");
        }
    } else {
        std::stringstream cellsText(text);
        for (std::string cellText; std::getline(cellsText, cellText, ';');) {
            Cell cell;
            std::stringstream pairs(cellText);
            for (std::string pair; std::getline(pairs, pair, ',');) {
                const size_t eq = pair.find('=');
                if (eq == std::string::npos || eq == 0)
                    return core::makeError(fmt::format("--configs: expected key=value, got '{}'", pair));
                cell.emplace_back(pair.substr(0, eq), pair.substr(eq + 1));
            }
            cells.push_back(cell);
        }
    }
    if (cells.empty()) return core::makeError("--configs: no configuration given");
    if (cells.size() > 64) return core::makeError("--configs: at most 64 cells");
    return cells;
}

core::Result<CellOptions> parseCell(const Cell& cell, const std::string& view, const std::string& size) {
    CellOptions o;
    CLI::App app{"cell"};
    o.view.addTo(app);
    o.technique.addTo(app);
    o.render.addTo(app);
    o.lights.addTo(app);
    std::vector<std::string> argv = {"--view=" + view};
    if (!size.empty()) argv.push_back("--size=" + size);
    for (const auto& [key, value] : cell) argv.push_back("--" + key + "=" + value);
    std::reverse(argv.begin(), argv.end()); // CLI11 takes the vector last argument first
    try {
        app.parse(argv);
    } catch (const CLI::ParseError& e) {
        return core::makeError(fmt::format("--configs: {}", e.what()));
    }
    if (auto t = o.technique.check(); !t) return core::makeError("--configs: " + t.error());
    if (auto s = o.render.check(); !s) return core::makeError("--configs: " + s.error());
    return o;
}

} // namespace shadowkit::app
