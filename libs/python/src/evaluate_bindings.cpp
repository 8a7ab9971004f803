// shadowkit.Evaluator / shadowkit.evaluate: the measure pipeline (libs/measure) from Python —
// render with a technique, ray-trace the truth, compare per pixel — returning the figures of
// `shadowkit eval` and the per-pixel buffers as NumPy arrays (top row first).
#include "bindings.h"

#include "shadowkit/core/light_size.h"
#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <pybind11/stl.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <system_error>

namespace shadowkit::python {

namespace {

// The project's data (views.json): $SHADOWKIT_DATA_DIR, else the source tree's data/ (a module
// run from the build tree), else the configured install prefix's. Not the running program's
// place, which is Python's.
std::filesystem::path dataDirectory() {
    if (const char* env = std::getenv("SHADOWKIT_DATA_DIR")) return env;
    std::error_code ec;
    const std::filesystem::path source = SHADOWKIT_SOURCE_DATA_DIR;
    if (std::filesystem::exists(source / "views.json", ec)) return source;
    return SHADOWKIT_INSTALL_DATA_DIR;
}

template <class T, class Source>
py::array_t<T> image(const std::vector<Source>& values, int width, int height) {
    py::array_t<T> out({py::ssize_t(height), py::ssize_t(width)});
    T* data = out.mutable_data();
    for (size_t i = 0; i < values.size(); ++i) data[i] = static_cast<T>(values[i]);
    return out;
}

py::dict figuresDict(const eval::Figures& f) {
    return py::dict(
        py::arg("valid_px") = f.validPx, py::arg("excluded_px") = f.excludedPx, py::arg("wrong_pct") = f.wrongPct,
        py::arg("false_shadow_pct") = f.falseShadowPct, py::arg("false_lit_pct") = f.falseLitPct,
        py::arg("undersampled_pct") = f.undersampledPct, py::arg("pixels_per_texel_p50") = f.pixelsPerTexelP50,
        py::arg("pixels_per_texel_p95") = f.pixelsPerTexelP95, py::arg("pixels_per_texel_p99") = f.pixelsPerTexelP99);
}

// One forest and one headless GL context, kept across evaluations (building the forest and
// the ray tracer's BVH is the slow part; truths are cached per camera, sun and size).
class Evaluator {
public:
    Evaluator(uint64_t seed, int trees, double terrainSize, int terrainResolution, int movers,
              const std::string& forest) {
        scene::ForestOptions o;
        if (forest != "simple" && forest != "leafy")
            throw py::value_error("forest: must be 'simple' or 'leafy', got '" + forest + "'");
        o.kind = forest == "leafy" ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
        o.seed = seed, o.trees = trees, o.terrainSize = terrainSize, o.terrainResolution = terrainResolution,
        o.movers = movers;
        if (core::Status s = scene::validate(o); !s) throw py::value_error(s.error());
        m_scene = scene::makeForest(o);
        m_measurer = check(measure::Measurer::createHeadless(m_scene));
    }

    py::dict evaluate(const std::string& viewName, const std::string& technique, int mapSize,
                      std::optional<std::pair<int, int>> size, const std::string& filter, int cascades,
                      const std::string& cascadeWarp, double sunAngle) {
        const auto views = check(scene::loadViews(dataDirectory() / "views.json"));
        scene::ResolvedView view = scene::resolveView(check(scene::findView(views, viewName)), m_scene);
        if (size) {
            if (size->first < 1 || size->second < 1 || size->first > 16384 || size->second > 16384)
                throw py::value_error("size: width and height must be in [1, 16384] pixels");
            view.setSize(size->first, size->second);
        }
        // The frame as `shadowkit eval` draws it: through the frame driver (the view's lamps too).
        frame::FrameConfig config;
        core::ShadowSetupInputs& in = config.technique;
        const auto parsed = core::parseTechnique(technique);
        if (!parsed) throw py::value_error("technique: '" + technique + "' is not one of " + core::techniqueNameList());
        in.technique = *parsed;
        in.mapSize = mapSize;
        in.cascades.count = cascades;
        if (cascadeWarp == "lispsm")
            in.cascades.warp = core::CascadeWarp::Lispsm;
        else if (cascadeWarp != "none")
            throw py::value_error("cascade_warp: must be none or lispsm");
        config.render.filter = check(core::parseFilter(filter));
        check(core::validateSunAngle(sunAngle));
        config.render.sunAngleDegrees = sunAngle;
        auto driver = check(frame::FrameDriver::create(config));
        const frame::PreparedFrame prepared = check(driver.prepare(m_measurer->renderer(), view));
        const measure::Measurement m = check(m_measurer->measure(prepared));
        const int w = view.width, h = view.height;
        py::dict out;
        out["figures"] = figuresDict(m.figures());
        out["technique"] = std::string(core::techniqueName(m.setup.technique));
        out["maps"] = m.setup.views.size();
        if (m.soft)
            out["soft"] = py::dict(
                py::arg("sun_angle_deg") = m.soft->sunAngleDegrees, py::arg("soft_compared_px") = m.soft->comparedPx,
                py::arg("penumbra_px") = m.soft->penumbraPx, py::arg("soft_mae") = m.soft->softMae,
                py::arg("penumbra_mae") = m.soft->penumbraMae, py::arg("soft_wrong_pct") = m.soft->softWrongPct,
                py::arg("penumbra_width_ratio") = m.soft->penumbraWidthRatio);
        if (m.softTruth) out["soft_visibility"] = image<float>(m.softTruth->visibility, w, h); // NaN: no surface
        out["shadow_term"] = image<float>(m.raster.shadowTerm, w, h);  // 1 lit .. 0 shadowed, the map's test
        out["view_depth"] = image<float>(m.raster.viewDepth, w, h);    // metres; 0 where nothing was drawn
        out["surface_id"] = image<uint32_t>(m.raster.surfaceId, w, h); // instance + 1; 0 sky
        out["truth_lit"] = image<uint8_t>(m.truth->lit, w, h);         // the shadow ray reached the sun
        out["truth_faces_light"] = image<uint8_t>(m.truth->facesLight, w, h);
        std::vector<uint8_t> classes(m.comparison.classes.size());
        for (size_t i = 0; i < classes.size(); ++i) classes[i] = static_cast<uint8_t>(m.comparison.classes[i]);
        out["pixel_class"] = image<uint8_t>(classes, w, h); // eval::PixelClass: 0 not evaluated .. 5 excluded
        out["pixels_per_texel"] = image<float>(m.comparison.pixelsPerTexel, w, h); // NaN where not valid
        return out;
    }

private:
    scene::Scene m_scene;
    std::unique_ptr<measure::Measurer> m_measurer;
};

constexpr const char* kEvaluateDoc =
    R"(Render `view` (a standard view of data/views.json) with a technique, ray-trace the truth
and compare per pixel, as `shadowkit eval` does. size=(width, height) overrides the view's;
filter: hard, pcf2, pcf:N, poisson:N, pcss[:N]. sun_angle: the sun's angular diameter in degrees
(0.53 the real sun; 0 a point): the penumbrae pcss draws, and the soft truth the frame is also
compared with (then a dict soft: sun_angle_deg, soft_compared_px, penumbra_px, soft_mae,
penumbra_mae, soft_wrong_pct, penumbra_width_ratio, and the array soft_visibility: the visible fraction of the
disk per pixel). Returns a dict: figures (valid_px, excluded_px,
wrong_pct, false_shadow_pct, false_lit_pct, undersampled_pct, pixels_per_texel_p50,
pixels_per_texel_p95, pixels_per_texel_p99), technique, maps, and per-pixel arrays (height x width, top row first):
shadow_term, view_depth, surface_id, truth_lit, truth_faces_light, pixel_class (0 not
evaluated, 1 lit correct, 2 shadow correct, 3 false shadow, 4 false lit, 5 excluded),
pixels_per_texel.)";

} // namespace

void bindEvaluation(py::module_& m) {
    m.def(
        "data_directory", [] { return dataDirectory().string(); },
        "Where the module finds views.json and the camera paths: $SHADOWKIT_DATA_DIR, else the source tree's "
        "data/ (a build), else the installed share/shadowkit.");
    // Defaults from the libraries' own option structs, as the command line's.
    const scene::ForestOptions d;
    const core::ShadowSetupInputs kDefaults;
    const std::string kDefaultTechnique(core::techniqueName(core::defaultTechnique()));
    py::class_<Evaluator>(m, "Evaluator", "A forest and a headless GL context (EGL) for repeated evaluations.")
        .def(py::init<uint64_t, int, double, int, int, const std::string&>(), py::kw_only(), py::arg("seed") = d.seed,
             py::arg("trees") = d.trees, py::arg("terrain_size") = d.terrainSize,
             py::arg("terrain_resolution") = d.terrainResolution, py::arg("movers") = d.movers,
             py::arg("forest") = "simple")
        .def("evaluate", &Evaluator::evaluate, kEvaluateDoc, py::kw_only(), py::arg("view") = "perpendicular",
             py::arg("technique") = kDefaultTechnique, py::arg("map_size") = kDefaults.mapSize,
             py::arg("size") = py::none(), py::arg("filter") = "hard", py::arg("cascades") = kDefaults.cascades.count,
             py::arg("cascade_warp") = "none", py::arg("sun_angle") = 0.0);
    m.def(
        "evaluate",
        [](const std::string& view, const std::string& technique, int mapSize, std::optional<std::pair<int, int>> size,
           const std::string& filter, int cascades, const std::string& cascadeWarp, double sunAngle, uint64_t seed,
           int trees, double terrainSize, int terrainResolution, const std::string& forest) {
            Evaluator evaluator(seed, trees, terrainSize, terrainResolution, scene::ForestOptions{}.movers, forest);
            return evaluator.evaluate(view, technique, mapSize, size, filter, cascades, cascadeWarp, sunAngle);
        },
        "One evaluation with a forest of its own (see Evaluator.evaluate; seed, trees, terrain_size, "
        "terrain_resolution and forest ('simple' or 'leafy': branches and alpha-tested leaf cards) make the forest).",
        py::kw_only(), py::arg("view") = "perpendicular", py::arg("technique") = kDefaultTechnique,
        py::arg("map_size") = kDefaults.mapSize, py::arg("size") = py::none(), py::arg("filter") = "hard",
        py::arg("cascades") = kDefaults.cascades.count, py::arg("cascade_warp") = "none", py::arg("sun_angle") = 0.0,
        py::arg("seed") = d.seed, py::arg("trees") = d.trees, py::arg("terrain_size") = d.terrainSize,
        py::arg("terrain_resolution") = d.terrainResolution, py::arg("forest") = "simple");
}

} // namespace shadowkit::python
