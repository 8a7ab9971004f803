// Evaluation as a regression suite: every technique, with its defaults, on every standard
// view of a small forest — the blob forest and the leafy one, each in its own file — measured
// against ray-traced truth and compared with the figures recorded in data/golden/ within the
// tolerances below. A change that
// moves a figure past its tolerance fails here, before it reaches the tables of README and docs/.
//
// After a change that is meant to move figures, re-record them (and say why in the commit):
//   SHADOWKIT_UPDATE_GOLDEN=1 build/tests/shadowkit_golden_tests
// CTest label `gl`: runs headless on Mesa llvmpipe.
#include "headless_gl_test.h"

#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace shadowkit;
using nlohmann::json;

namespace {

const std::filesystem::path kGoldenFolder = std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "golden";

// The figures compared, with how far each may move: absolute for percentages of pixels,
// relative for pixel counts and pixels-per-texel quantiles.
struct Tolerance {
    const char* name;
    double absolute, relative;
};
constexpr Tolerance kTolerances[] = {
    {"valid_px", 0.0, 0.01},
    {"wrong_pct", 0.05, 0.0},
    {"false_shadow_pct", 0.05, 0.0},
    {"false_lit_pct", 0.05, 0.0},
    {"undersampled_pct", 0.5, 0.0},
    {"pixels_per_texel_p50", 0.0, 0.02},
    {"pixels_per_texel_p99", 0.0, 0.05},
};

json figuresJson(const eval::Figures& f) {
    return {{"valid_px", f.validPx},
            {"wrong_pct", f.wrongPct},
            {"false_shadow_pct", f.falseShadowPct},
            {"false_lit_pct", f.falseLitPct},
            {"undersampled_pct", f.undersampledPct},
            {"pixels_per_texel_p50", f.pixelsPerTexelP50},
            {"pixels_per_texel_p99", f.pixelsPerTexelP99}};
}

class GoldenFiguresTest : public gl::testing::HeadlessGlTest {
protected:
    static void checkGolden(const std::filesystem::path& goldenFile);
};

} // namespace

void GoldenFiguresTest::checkGolden(const std::filesystem::path& goldenFile) {
    std::ifstream in(goldenFile);
    ASSERT_TRUE(in) << goldenFile << ": missing";
    json golden = json::parse(in);
    const json& config = golden.at("config");

    scene::ForestOptions forestOptions;
    forestOptions.kind =
        config.value("forest", "simple") == "leafy" ? scene::ForestKind::Leafy : scene::ForestKind::Simple;
    forestOptions.trees = config.at("trees");
    forestOptions.terrainSize = config.at("terrain_size");
    forestOptions.terrainResolution = config.at("terrain_resolution");
    const scene::Scene forest = scene::makeForest(forestOptions);
    auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    ASSERT_TRUE(views) << views.error();
    auto measurer = measure::Measurer::create(forest);
    ASSERT_TRUE(measurer) << measurer.error();
    const int divisor = config.at("image_divisor");

    const bool update = std::getenv("SHADOWKIT_UPDATE_GOLDEN") != nullptr;
    json recorded = json::object();
    for (const core::TechniqueInfo& technique : core::allTechniques()) {
        for (const scene::ViewSpec& spec : *views) {
            if (!spec.lights.empty()) continue; // the sun's techniques on the sunlit views
            const scene::ResolvedView view = scene::resolveView(spec, forest);
            gl::RenderSettings settings; // every default: the recommended bias, hard test
            settings.width = view.width / divisor;
            settings.height = view.height / divisor;
            const core::ShadowSetupInputs inputs{.camera = view.camera,
                                                 .light = view.light,
                                                 .wsSceneBounds = forest.wsBounds(),
                                                 .technique = technique.technique,
                                                 .mapSize = config.at("map_size")};
            auto m = (*measurer)->measure(inputs, settings);
            ASSERT_TRUE(m) << technique.name << " " << spec.name << ": " << m.error();
            const json actual = figuresJson(m->figures());
            recorded[std::string(technique.name)][spec.name] = actual;
            if (update) continue;
            const json& expected = golden.at("figures").at(std::string(technique.name)).at(spec.name);
            for (const Tolerance& t : kTolerances) {
                const double want = expected.at(t.name), got = actual.at(t.name);
                EXPECT_LE(std::abs(got - want), t.absolute + t.relative * std::abs(want))
                    << technique.name << " on " << spec.name << ": " << t.name << " " << got << ", recorded " << want;
            }
        }
    }
    if (update) {
        golden["figures"] = recorded;
        std::ofstream(goldenFile) << golden.dump(2) << "\n";
        std::printf("re-recorded %s\n", goldenFile.string().c_str());
    }
}

TEST_F(GoldenFiguresTest, EveryTechniqueMatchesItsRecordedFiguresOnEveryStandardView) {
    checkGolden(kGoldenFolder / "small-forest.json");
}

// The leafy forest's cards and thin wood, alpha-tested in every map and in the truth.
TEST_F(GoldenFiguresTest, EveryTechniqueMatchesItsRecordedFiguresOnTheLeafyForest) {
    checkGolden(kGoldenFolder / "small-leafy-forest.json");
}
