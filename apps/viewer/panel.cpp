#include "panel.h"

#include "frame_options.h"

#include "shadowkit/core/shadow_setup.h"

#include <imgui.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace shadowkit::viewer {
namespace {

using app::StateOptions;

std::string valueOf(const StateOptions& s, const std::string& name, const std::string& fallback) {
    const auto it = s.find(name);
    return it == s.end() || it->second.empty() ? fallback : it->second.back();
}

void set(StateOptions& s, const std::string& name, const std::string& value) { s[name] = {value}; }

template <class Choices>
bool combo(StateOptions& s, const char* label, const char* name, const Choices& choices, const std::string& fallback) {
    const std::string current = valueOf(s, name, fallback);
    bool changed = false;
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (const auto& entry : choices) {
            const std::string choice(entry); // the lists hold strings or string_views
            if (ImGui::Selectable(choice.c_str(), current == choice)) {
                set(s, name, choice);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

bool sliderFloat(StateOptions& s, const char* label, const char* name, float lo, float hi, float fallback,
                 bool logarithmic = false) {
    float v = static_cast<float>(std::atof(valueOf(s, name, fmt::format("{}", fallback)).c_str()));
    if (!ImGui::SliderFloat(label, &v, lo, hi, "%.3g", logarithmic ? ImGuiSliderFlags_Logarithmic : 0)) return false;
    set(s, name, fmt::format("{}", v));
    return true;
}

bool sliderInt(StateOptions& s, const char* label, const char* name, int lo, int hi, int fallback) {
    int v = std::atoi(valueOf(s, name, std::to_string(fallback)).c_str());
    if (!ImGui::SliderInt(label, &v, lo, hi)) return false;
    set(s, name, std::to_string(v));
    return true;
}

// A bare flag (--stabilize): present or absent.
bool checkbox(StateOptions& s, const char* label, const char* name) {
    bool on = s.count(name) > 0 && valueOf(s, name, "true") != "false";
    if (!ImGui::Checkbox(label, &on)) return false;
    if (on)
        set(s, name, "true");
    else
        s.erase(name);
    return true;
}

// The options' own registration — FrameOptions::addTo, the groups `render` parses — from which
// every enumerated option's list and default come (app::choicesOf, app::defaultOf): a technique
// core adds, or a choice a flag gains, appears here without an edit.
CLI::App& registry() {
    static FrameOptions options;
    static const std::unique_ptr<CLI::App> app = [] {
        auto cmd = std::make_unique<CLI::App>("viewer panel");
        options.addTo(*cmd);
        return cmd;
    }();
    return *app;
}

// A combo box for an enumerated option, its list and default as the command line has them.
bool choiceCombo(StateOptions& s, const char* label, const char* name) {
    const std::string flag = std::string("--") + name;
    return combo(s, label, name, app::choicesOf(registry(), flag), app::defaultOf(registry(), flag));
}
std::string defaultOf(const char* name) { return app::defaultOf(registry(), std::string("--") + name); }
// The default of a numeric option, as the slider's value while the state does not set it.
float numberOf(const char* name) { return std::stof(defaultOf(name)); }

constexpr std::array kTexelBudgets = {"1M", "4M", "16M", "32M"};
constexpr std::array kMapSizes = {"256", "512", "1024", "2048", "4096", "8192"};
constexpr std::array kFilters = {"hard",       "pcf2", "pcf:3",   "pcf:5", "poisson:16",
                                 "poisson:32", "pcss", "pcss:32", "msm"};

// The sun: night, or its elevation and azimuth.
bool sunSection(StateOptions& s, const PanelDefaults& d) {
    const auto f = [](double v) { return static_cast<float>(v); };
    bool changed = false;
    bool night = valueOf(s, "sun", "") == "off";
    if (ImGui::Checkbox("night (--sun off)", &night)) {
        if (night)
            set(s, "sun", "off");
        else
            s.erase("sun");
        changed = true;
    }
    if (!night) {
        // Angles replace a direction given as a vector.
        // Both sliders are drawn every frame, so neither call may be short-circuited away.
        const bool elevationMoved = sliderFloat(s, "elevation", "sun-elevation", 1.0f, 89.0f, f(d.sunElevationDegrees));
        const bool azimuthMoved = sliderFloat(s, "azimuth", "sun-azimuth", 0.0f, 360.0f, f(d.sunAzimuthDegrees));
        if (elevationMoved || azimuthMoved) {
            s.erase("sun");
            changed = true;
        }
    }
    return changed;
}

// The technique and its parameters, as the chosen family has them.
bool techniqueSection(StateOptions& s) {
    bool changed = false;
    changed |= choiceCombo(s, "technique", "technique");
    changed |= combo(s, "map size", "map-size", kMapSizes, defaultOf("map-size"));
    const std::string t = valueOf(s, "technique", defaultOf("technique"));
    if (t == "auto") changed |= combo(s, "texel budget", "texel-budget", kTexelBudgets, "4M");
    if (t == "lispsm") {
        changed |= choiceCombo(s, "n formula", "lispsm-formula");
        changed |= choiceCombo(s, "warp axis", "lispsm-direction");
        changed |= sliderFloat(s, "n weight", "lispsm-weight", 0.1f, 10.0f, numberOf("lispsm-weight"), true);
        // A fixed n replaces the formula while it is set.
        bool fixedN = s.count("lispsm-n") > 0;
        if (ImGui::Checkbox("fixed n", &fixedN)) {
            if (fixedN)
                set(s, "lispsm-n", "10");
            else
                s.erase("lispsm-n");
            changed = true;
        }
        if (fixedN) changed |= sliderFloat(s, "n (m)", "lispsm-n", 0.1f, 1000.0f, 10.0f, true);
        changed |= checkbox(s, "z_n from the visible near", "lispsm-visible-near");
    }
    if (t == "lispsm" || t == "csm") {
        bool measured = valueOf(s, "visible-depth", "") == "auto";
        if (ImGui::Checkbox("visible depth from the frame", &measured)) {
            if (measured)
                set(s, "visible-depth", "auto");
            else
                s.erase("visible-depth");
            changed = true;
        }
    }
    if (t == "tsm") changed |= sliderFloat(s, "focus", "tsm-focus", 0.0f, 0.9f, numberOf("tsm-focus"));
    if (t == "csm") {
        changed |= sliderInt(s, "cascades", "cascades", 1, 8, static_cast<int>(numberOf("cascades")));
        changed |= sliderFloat(s, "lambda", "lambda", 0.0f, 1.0f, numberOf("lambda"));
        // Explicit split distances replace λ while given (Enter applies, empty clears).
        std::array<char, 256> splits{};
        const std::string current = valueOf(s, "splits", "");
        current.copy(splits.data(), splits.size() - 1);
        if (ImGui::InputText("splits near,...,far", splits.data(), splits.size(),
                             ImGuiInputTextFlags_EnterReturnsTrue)) {
            if (splits[0] == '\0')
                s.erase("splits");
            else
                set(s, "splits", splits.data());
            changed = true;
        }
        changed |= choiceCombo(s, "warp", "cascade-warp");
        changed |= sliderFloat(s, "blend band", "blend-band", 0.0f, 0.5f, numberOf("blend-band"));
    }
    changed |= checkbox(s, "stabilize", "stabilize");
    if (s.count("stabilize") && !(t == "csm" && valueOf(s, "cascade-warp", "none") == "none")) {
        changed |= sliderFloat(s, "refit margin", "stabilize-margin", 0.0f, 1.0f, numberOf("stabilize-margin"));
        changed |= sliderFloat(s, "texel growth", "stabilize-growth", 1.01f, 4.0f, numberOf("stabilize-growth"));
        changed |= sliderInt(s, "look-ahead frames", "stabilize-lookahead", 0, 120,
                             static_cast<int>(numberOf("stabilize-lookahead")));
    }
    return changed;
}

// The bias (defaults: the recommendation), the filter, the sun's size and the blur.
bool biasAndFilterSection(StateOptions& s, const PanelDefaults& d) {
    const auto f = [](double v) { return static_cast<float>(v); };
    bool changed = false;
    changed |= sliderFloat(s, "slope", "bias-slope", 0.0f, 8.0f, f(d.biasSlope));
    changed |= sliderFloat(s, "constant", "bias-constant", 0.0f, 100000.0f, f(d.biasConstant), true);
    changed |= sliderFloat(s, "normal offset", "normal-offset", 0.0f, 4.0f, f(d.normalOffset));
    changed |= sliderFloat(s, "footprint offset", "normal-offset-footprint", 0.0f, 2.0f, f(d.normalOffsetFootprint));
    changed |= choiceCombo(s, "receiver plane", "receiver-plane-bias");
    changed |= choiceCombo(s, "offset guard", "offset-guard");
    changed |= choiceCombo(s, "cull", "cull");
    changed |= choiceCombo(s, "depth layout", "depth-layout");
    if (ImGui::Button("reset to recommended")) {
        for (const char* name : {"bias-slope", "bias-constant", "normal-offset", "normal-offset-footprint",
                                 "receiver-plane-bias", "offset-guard", "cull", "depth-layout"})
            s.erase(name);
        changed = true;
    }
    changed |= combo(s, "filter", "filter", kFilters, defaultOf("filter"));
    // The sun's size: the width of the penumbrae pcss draws (0.53: the real sun).
    changed |= sliderFloat(s, "sun angle (deg)", "sun-angle", 0.0f, 5.0f, numberOf("sun-angle"));
    // Leaves cast a fraction of the light (opacity layers, beside fixed maps or virtual pages).
    changed |= checkbox(s, "leaves: opacity layers", "foliage-opacity");
    changed |= sliderInt(s, "blur iterations", "blur-iterations", 0, 16, static_cast<int>(numberOf("blur-iterations")));
    if (valueOf(s, "blur-iterations", "0") != "0") {
        changed |= sliderFloat(s, "blur radius (px)", "blur-radius", 0.1f, 16.0f, numberOf("blur-radius"));
        changed |=
            sliderFloat(s, "blur depth falloff", "blur-depth-falloff", 0.0f, 1.0f, numberOf("blur-depth-falloff"));
    }
    return changed;
}

} // namespace

bool drawOptionsPanel(StateOptions& s, const PanelDefaults& d) {
    bool changed = false;
    if (ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen)) changed |= sunSection(s, d);
    if (ImGui::CollapsingHeader("Technique", ImGuiTreeNodeFlags_DefaultOpen)) changed |= techniqueSection(s);
    if (ImGui::CollapsingHeader("Bias and filter")) changed |= biasAndFilterSection(s, d);
    if (ImGui::CollapsingHeader("Insight", ImGuiTreeNodeFlags_DefaultOpen)) {
        changed |= checkbox(s, "aliasing heat map (pixels per texel)", "aliasing-overlay");
        changed |= checkbox(s, "split colours", "cascade-colors");
    }
    if (ImGui::CollapsingHeader("Visibility")) {
        changed |= choiceCombo(s, "visibility", "visibility");
        changed |= choiceCombo(s, "caster culling", "caster-culling");
        // Levels of detail of the leaves: how far out their clouds are taken, and the band over
        // which a tree crosses into one (0: it switches in one frame).
        changed |=
            sliderFloat(s, "foliage level scale", "lod-foliage-scale", 1.0f, 64.0f, numberOf("lod-foliage-scale"));
        changed |= sliderFloat(s, "level cross-fade band", "lod-fade", 0.0f, 0.9f, numberOf("lod-fade"));
    }
    if (ImGui::CollapsingHeader("Spot and point lights")) {
        changed |= combo(s, "local map size", "local-map-size", kMapSizes, defaultOf("local-map-size"));
        changed |= choiceCombo(s, "cube pass", "local-pass");
        changed |= sliderFloat(s, "slope (texels)", "local-bias-slope", 0.0f, 8.0f, numberOf("local-bias-slope"));
        changed |= sliderFloat(s, "normal offset (texels)", "local-normal-offset", 0.0f, 8.0f,
                               numberOf("local-normal-offset"));
    }
    return changed;
}

} // namespace shadowkit::viewer
