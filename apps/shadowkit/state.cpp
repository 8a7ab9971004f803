#include "state.h"

#include "shadowkit/scene/file_read.h"
#include "shadowkit/scene/file_write.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>

namespace shadowkit::app {
namespace {

constexpr int kStateVersion = 1;

// The long option a command-line word names ("--map-size=64" and "--map-size" → "map-size").
std::string optionName(const std::string& word) {
    if (word.size() < 3 || word.compare(0, 2, "--") != 0) return {};
    return word.substr(2, word.find('=') - 2);
}

// A name a state may give: spelled as the commands' long options are (a lower-case letter, then
// lower-case letters, digits and '-'), and none that does anything but set an option of a frame
// (--help and --version print and exit 0 having drawn nothing; --state would read another file).
bool isStateOptionName(const std::string& name) {
    const auto lower = [](char c) { return c >= 'a' && c <= 'z'; };
    if (name.empty() || name.size() > 64 || !lower(name.front())) return false;
    if (!std::ranges::all_of(name, [&](char c) { return lower(c) || (c >= '0' && c <= '9') || c == '-'; }))
        return false;
    return name != "help" && name != "version" && name != "state";
}

} // namespace

core::Result<StateOptions> loadState(const std::string& file) {
    const auto bytes = scene::readFile(file);
    if (!bytes) return core::makeError("--state: " + bytes.error());
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(*bytes);
    } catch (const nlohmann::json::exception&) { // parse errors, and numbers out of range
        return core::makeError("--state: " + file + ": not valid JSON");
    }
    const bool versioned = root.is_object() && root.contains("shadowkit_state") &&
                           root["shadowkit_state"].is_number_integer() &&
                           root["shadowkit_state"].get<int64_t>() == kStateVersion; // value() would throw on a string
    if (!versioned || !root.contains("options") || !root["options"].is_object())
        return core::makeError("--state: " + file + ": expected {\"shadowkit_state\": 1, \"options\": {...}}");
    StateOptions options;
    for (const auto& item : root["options"].items()) {
        const std::string name = item.key(); // a plain variable: clang 14 lambdas cannot capture structured bindings
        const nlohmann::json& value = item.value();
        if (!isStateOptionName(name))
            return core::makeError("--state: " + file + ": bad option name '" + name +
                                   "' (an option of render without its dashes, e.g. map-size, other than help, "
                                   "version or state)");
        auto text = [&](const nlohmann::json& v) -> core::Result<std::string> {
            if (v.is_string()) return v.get<std::string>();
            if (v.is_number() || v.is_boolean()) return v.dump();
            return core::makeError("--state: " + file + ": option '" + name +
                                   "' must be a string, number or list of them");
        };
        std::vector<std::string>& values = options[name];
        for (const nlohmann::json& v : value.is_array() ? value : nlohmann::json::array({value})) {
            auto t = text(v);
            if (!t) return t.errorInfo();
            values.push_back(*t);
        }
    }
    return options;
}

core::Status saveState(const StateOptions& options, const std::string& file) {
    nlohmann::json list = nlohmann::json::object();
    for (const auto& [name, values] : options)
        list[name] = values.size() == 1 ? nlohmann::json(values.front()) : nlohmann::json(values);
    return scene::writeFile(file, nlohmann::json{{"shadowkit_state", kStateVersion}, {"options", list}}.dump(2) + "\n");
}

core::Result<std::vector<std::string>> expandState(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    std::string file;
    size_t at = 0;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--state") {
            if (i + 1 >= args.size()) return core::makeError("--state: needs a file");
            file = args[++i];
            at = out.size();
        } else if (args[i].rfind("--state=", 0) == 0) {
            file = args[i].substr(8);
            at = out.size();
        } else {
            out.push_back(args[i]);
        }
    }
    if (file.empty()) return out;
    auto options = loadState(file);
    if (!options) return options.errorInfo();
    std::set<std::string> given;
    for (const std::string& word : out) given.insert(optionName(word));
    std::vector<std::string> expanded;
    for (const auto& [name, values] : *options)
        if (!given.count(name))
            for (const std::string& v : values) expanded.push_back("--" + name + "=" + v);
    out.insert(out.begin() + static_cast<std::ptrdiff_t>(at), expanded.begin(), expanded.end());
    return out;
}

} // namespace shadowkit::app
