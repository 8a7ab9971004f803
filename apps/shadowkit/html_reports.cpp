#include "html_reports.h"

#include "shadowkit/eval/level_map.h"
#include "shadowkit/eval/maps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <ctime>

namespace shadowkit::app {
namespace {

std::vector<std::string>& startArguments() {
    static std::vector<std::string> args;
    return args;
}

std::string quoted(const std::string& arg) {
    const bool plain = !arg.empty() && std::all_of(arg.begin(), arg.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string_view("-_./=:,+@%").find(c) != std::string_view::npos;
    });
    if (plain) return arg;
    std::string out = "'";
    for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// The level map's caption: what its colours mean, and the truth's shadowed pixels split by the
// level their caster was drawn at, with the share of each that came out lit.
std::string levelCaption(const eval::LevelMap& levels, const eval::Comparison& comparison) {
    const std::vector<eval::CasterLevelFigures> split = eval::casterLevelFigures(levels, comparison);
    int64_t shadowed = 0;
    for (const eval::CasterLevelFigures& f : split) shadowed += f.shadowedPx;
    std::string caption = "levels of detail: where the truth is in shadow, the level the sun pass drew its caster at; "
                          "elsewhere, faded, the camera pass's level of the surface";
    const char* separator = ". Of the shadowed pixels: ";
    for (const eval::CasterLevelFigures& f : split) {
        const std::string level = f.level == eval::kLevelNotDrawn ? "casters not drawn"
                                  : f.level == 0                  ? "full casters"
                                                                  : fmt::format("level {} casters", f.level);
        caption += fmt::format("{}{} {:.1f} % ({:.1f} % of them lit)", separator, level,
                               100.0 * double(f.shadowedPx) / double(std::max<int64_t>(shadowed, 1)),
                               100.0 * double(f.falseLitPx) / double(std::max<int64_t>(f.shadowedPx, 1)));
        separator = "; ";
    }
    return caption;
}

} // namespace

void setInvocation(std::vector<std::string> args) { startArguments() = std::move(args); }

std::string commandLine(const std::vector<std::string>& args) {
    std::string text = "shadowkit";
    for (const std::string& a : args) {
        text += ' ';
        text += quoted(a);
    }
    return text;
}

std::string invocation() { return commandLine(startArguments()); }

std::string invocationWithout(std::initializer_list<std::string_view> drop, const std::vector<std::string>& add,
                              std::string_view subcommand) {
    const std::vector<std::string>& args = startArguments();
    std::vector<std::string> kept;
    for (size_t i = 0; i < args.size(); ++i) {
        if (i == 0 && !subcommand.empty()) { // the subcommand comes first (main's argv[1])
            kept.emplace_back(subcommand);
            continue;
        }
        const std::string& a = args[i];
        const std::string_view name = std::string_view(a).substr(0, a.find('='));
        if (std::find(drop.begin(), drop.end(), name) == drop.end()) {
            kept.push_back(a);
            continue;
        }
        if (a.find('=') == std::string::npos) ++i; // "--x v": the value goes too
    }
    kept.insert(kept.end(), add.begin(), add.end());
    return commandLine(kept);
}

core::Result<eval::HtmlEntry> reportEntry(const measure::Measurement& measured, const eval::ViewReport& report,
                                          const core::DirectionalLight& sun, bool sunShines,
                                          const std::filesystem::path& page, const std::string& slug,
                                          const std::string& label, const std::string& command) {
    eval::HtmlEntry entry{label, report, {}, command};
    const std::filesystem::path dir = page.parent_path();
    const std::string stem = page.stem().string() + "-" + slug;
    auto add = [&](const scene::Image& image, const std::string& suffix, const std::string& caption) -> core::Status {
        const std::string file = stem + "-" + suffix + ".png";
        if (auto s = scene::writePng(image, dir / file); !s) return core::makeError("--report: " + s.error());
        entry.pictures.push_back({file, caption});
        return core::Ok{};
    };
    const int w = measured.raster.width, h = measured.raster.height;
    if (measured.image.width > 0)
        if (auto s = add(measured.image, "frame", "the rendered frame"); !s) return s.errorInfo();
    if (sunShines) {
        if (auto s = add(eval::renderedShadowImage(*measured.truth, measured.raster, sun), "rendered",
                         "rendered shadows (the sun's)");
            !s)
            return s.errorInfo();
        if (auto s = add(eval::truthShadowImage(*measured.truth, sun), "truth", "ray-traced truth"); !s)
            return s.errorInfo();
        // Under the sun's disk (--sun-angle): the soft truth and the signed error against it.
        if (const auto& soft = measured.softTruth) {
            if (auto s = add(eval::softTruthShadowImage(*measured.truth, *soft, sun), "soft-truth",
                             "ray-traced truth under the sun's disk (the visible fraction of it)");
                !s)
                return s.errorInfo();
            if (auto s = add(eval::softErrorMapImage(measured.raster.shadowTerm, *soft, measured.comparison),
                             "soft-error", "error against the sun's disk: red too dark, blue too light");
                !s)
                return s.errorInfo();
        }
    }
    if (auto s = add(eval::errorMapImage(measured.comparison, w, h), "error", "error map"); !s) return s.errorInfo();
    if (auto s = add(eval::aliasingMapImage(measured.comparison, w, h), "aliasing", "aliasing map (pixels per texel)");
        !s)
        return s.errorInfo();
    if (measured.levels)
        if (auto s = add(eval::levelMapImage(*measured.levels), "levels",
                         levelCaption(*measured.levels, measured.comparison));
            !s)
            return s.errorInfo();
    return entry;
}

std::string machineDescription(const measure::Measurer& measurer) {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    const std::string gl = measurer.contextDescription();
    return fmt::format("{}{}", gl.empty() ? "" : "OpenGL " + gl + ", ", date);
}

} // namespace shadowkit::app
