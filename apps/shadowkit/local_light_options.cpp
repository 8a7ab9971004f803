#include "local_light_options.h"

#include "options.h" // parseNumbers

#include <fmt/format.h>

namespace shadowkit::app {
namespace {

constexpr const char* kForms = "point:x,y,z[,range] or spot:x,y,z,dx,dy,dz,angle[,range]";

core::Result<LocalLight> parseLight(const std::string& spec) {
    const size_t colon = spec.find(':');
    const std::string kind = spec.substr(0, colon), rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
    std::vector<double> v;
    const bool numbers = parseNumbers(rest, ',', v);
    auto bad = [&] { return core::makeError(fmt::format("--light: expected {}, got '{}'", kForms, spec)); };
    if (!numbers) return bad();
    core::Status valid = core::Ok{};
    LocalLight light;
    if (kind == "point" && (v.size() == 3 || v.size() == 4)) {
        core::PointLight p{.wsPosition = {v[0], v[1], v[2]}};
        if (v.size() == 4) p.range = v[3];
        valid = p.validate();
        light = p;
    } else if (kind == "spot" && (v.size() == 7 || v.size() == 8)) {
        core::SpotLight s{.wsPosition = {v[0], v[1], v[2]}, .wsDirection = {v[3], v[4], v[5]}, .coneDegrees = v[6]};
        if (v.size() == 8) s.range = v[7];
        valid = s.validate();
        light = s;
    } else {
        return bad();
    }
    if (!valid) return core::makeError(fmt::format("--light: {} (in '{}')", valid.error(), spec));
    return light;
}

} // namespace

void LocalLightOptions::addTo(CLI::App& cmd) {
    cmd.add_option("--light", specs, fmt::format("a local light with shadows, repeatable: {} (degrees, metres; range 30 m "
                                                 "unless given)",
                                                 kForms));
}

core::Result<std::vector<LocalLight>> LocalLightOptions::lights() const {
    std::vector<LocalLight> out;
    for (const std::string& spec : specs) {
        auto light = parseLight(spec);
        if (!light) return light.errorInfo();
        out.push_back(*light);
    }
    return out;
}

} // namespace shadowkit::app
