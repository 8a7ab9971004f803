// The default set-up on models we did not make: never far worse than the focused map.
//
// Tuned on our forest, the default (TSM 2048², frame::FrameConfig's technique) once failed a
// public 25 m model with no ground under it at `noon`: 27.5 % wrong where the focused map was
// 2.07 % (TSM's 80 % rule warps hard whatever the view's depth ratio; tsm.cpp now caps the warp
// at the view's own perspective). Here public models — a compact engine seen from afar with
// no ground (the failing shape), a spider of thin legs, a grooved figure, spheres in walled
// cells, a hip roof — our pillar on a plate and the shapes authored for the corpus are measured
// on every standard view against ray-traced truth, default against focused: the default may be
// at most 1.5 times as wrong, plus 0.1 points for views where both are nearly right (a handful
// of pixels). The grooved figure, the spheres and the roof have views not held yet (below;
// tools/measure-corpus.sh measures every file of the corpus, docs/reliability.md). The public
// models come from Debian's assimp-testmodels (tools/install-deps.sh); a model that is missing
// fails the test, naming the package.
// CTest label `gl`: runs headless on Mesa llvmpipe.
#include "headless_gl_test.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/frame/frame_config.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

// Each model with the views it is not held on yet.
const struct {
    fs::path file;
    std::set<std::string> notYet;
} kModels[] = {
    {"/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", {}},
    {"/usr/share/assimp/models/OBJ/spider.obj", {}},
    // A figure with fine grooves: on `into-sun` TSM's normal offset, half a texel, carries the
    // lookup past ridges narrower than that (1.14 % against the focused map's 0.57), most of it
    // on facets within a degree of grazing.
    {"/usr/share/assimp/models/OBJ/WusonOBJ.obj", {"into-sun"}},
    // Spheres in walled cells: on `paper` the offset carries receivers at the spheres' rims out
    // of the walls' shadows (4.94 % against 1.39).
    {"/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf", {"paper"}},
    // A hip roof: the offset carries receivers at its valleys and eaves under the neighbouring
    // face, false shadow in lines along the creases (sun-behind 0.57 % against 0.01).
    {"/usr/share/assimp/models/OBJ/regr01.obj", {"paper", "perpendicular", "sun-behind", "noon"}},
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "pillar_on_plate.gltf", {}},
    // Authored here (tools/authored_shapes.py): 3 cm ropes and 40 cm masts seen from afar; a wide
    // flat town; a single tree of alpha-cut leaves. Their `into-sun` holds since TSM's warp
    // stopped outgrowing a compact footprint's pixels (docs/reliability.md, "Models we did not
    // make").
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "ship.obj", {}},
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "town.obj", {}},
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "tree.gltf", {}},
    // A pavilion under the sky sphere it ships with, left out as it loads (scene/sky_enclosure.h).
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "sky.gltf", {}},
    // A glasshouse whose glass lets the sun in (KHR_materials_transmission, gltf_transmission.cpp).
    // On `sun-behind` (the sun 25° up) the offset lifts the ground's lookups by half a texel, and
    // the 16 m of shadow its two low walls cast on the lawn and the floor end a line of pixels
    // short, cot 25° = 2.1 times that lift further on: 0.49 % false light against 0.03.
    {fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "glasshouse.gltf", {"sun-behind"}},
};
constexpr double kRatio = 1.5, kSlackPoints = 0.1;
// 640 × 360: a small model covers a few thousand pixels (Wuson about 8,600 against 2,100 at
// 320 × 180), so a view's figure is not a handful of pixels' (at 320 × 180 the tree's
// `into-sun` read 0.24 % against a bound of 0.235, at 640 × 360 0.30 against 0.37).
constexpr int kWidth = 640, kHeight = 360;

class CorpusDefaultsTest : public gl::testing::HeadlessGlTest {};

// A model of kModels and a measurer of it; nullptr, the test failed naming why, when it cannot
// be had (a missing file names the Debian package).
struct LoadedModel {
    scene::Scene scene;
    std::unique_ptr<measure::Measurer> measurer; // of `scene`, which it may hold on to
};
std::unique_ptr<LoadedModel> loadModel(const fs::path& file) {
    if (!fs::exists(file)) {
        ADD_FAILURE() << file << " is missing: install assimp-testmodels (tools/install-deps.sh)";
        return nullptr;
    }
    auto model = scene::loadScene(file);
    if (!model) {
        ADD_FAILURE() << model.error();
        return nullptr;
    }
    auto loaded = std::make_unique<LoadedModel>(LoadedModel{std::move(*model), nullptr});
    auto measurer = measure::Measurer::create(loaded->scene);
    if (!measurer) {
        ADD_FAILURE() << file << ": " << measurer.error();
        return nullptr;
    }
    loaded->measurer = std::move(*measurer);
    return loaded;
}

// `wrong_pct` of a model's view under the sun with the default set-up's technique, or with
// `focused`, at kWidth × kHeight; `bias` replaces the recommended one where given.
double wrongPct(measure::Measurer& measurer, const scene::Scene& model, const scene::ViewSpec& spec, bool focused,
                std::optional<core::BiasSettings> bias = std::nullopt) {
    const scene::ResolvedView view = scene::resolveView(spec, model);
    gl::RenderSettings settings; // the recommended bias unless given, hard test
    settings.width = kWidth, settings.height = kHeight;
    settings.bias = bias;
    core::ShadowSetupInputs inputs = frame::FrameConfig{}.technique;
    inputs.camera = view.camera, inputs.light = view.light, inputs.wsSceneBounds = model.wsBounds();
    if (focused) inputs.technique = core::Technique::Focused;
    auto m = measurer.measure(inputs, settings);
    EXPECT_TRUE(m) << spec.name << ": " << m.error();
    return m ? m->figures().wrongPct : 0.0;
}

} // namespace

TEST_F(CorpusDefaultsTest, TheDefaultIsNeverMuchWorseThanTheFocusedMapOnAnyViewOfAnyModel) {
    auto views = scene::loadViews(fs::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    ASSERT_TRUE(views) << views.error();
    int measured = 0;
    for (const auto& [file, notYet] : kModels) {
        const std::unique_ptr<LoadedModel> loaded = loadModel(file);
        if (!loaded) continue;
        const scene::Scene& model = loaded->scene;
        measure::Measurer& measurer = *loaded->measurer;
        for (const scene::ViewSpec& spec : *views) {
            if (!spec.lights.empty() || notYet.contains(spec.name)) continue; // the sun's set-ups on the sunlit views
            const double byDefault = wrongPct(measurer, model, spec, false);
            const double byFocused = wrongPct(measurer, model, spec, true);
            ++measured;
            EXPECT_LE(byDefault, kRatio * byFocused + kSlackPoints)
                << file.filename() << " on " << spec.name << ": the default is " << byDefault << " % wrong, focused "
                << byFocused << " %";
        }
    }
    EXPECT_GT(measured, 0);
}

TEST_F(CorpusDefaultsTest, TheFootprintOffsetHoldsTheViewsTheTexelOffsetMissesButTheClearCoatCards) {
    // The normal offset by a texel's footprint on the triangle's normal under a twentieth of
    // today's half texel (--normal-offset 0.05 --normal-offset-footprint 0.25;
    // docs/bias-and-filtering.md): not the default yet, as it moves every table. Of the seven views
    // above that the default misses it holds the bound on all but the clear-coat card's `paper`
    // (on llvmpipe Wuson's `into-sun` 0.52 % against 0.955, the glasshouse's `sun-behind` 0.13
    // against 0.145). With the triangle's normal turned to the shading normal's side the roof's
    // `noon` fell outside (0.19 against 0.145); without the twentieth, the glasshouse (0.24).
    auto views = scene::loadViews(fs::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    ASSERT_TRUE(views) << views.error();
    const core::ShadowSetupInputs defaults = frame::FrameConfig{}.technique;
    core::BiasSettings footprint = core::recommendedBias(defaults.technique, core::depthLayoutFor(defaults));
    footprint.normalOffset = 0.05;
    footprint.normalOffsetFootprint = 0.25;
    int measured = 0;
    for (const auto& [file, notYet] : kModels) {
        const std::string name = file.filename().string();
        if (notYet.empty() || name == "ClearCoatTest.gltf") continue; // the card: 3.15 % against 2.19
        const std::unique_ptr<LoadedModel> loaded = loadModel(file);
        if (!loaded) continue;
        const scene::Scene& model = loaded->scene;
        measure::Measurer& measurer = *loaded->measurer;
        for (const scene::ViewSpec& spec : *views) {
            if (!notYet.contains(spec.name)) continue;
            const double byFootprint = wrongPct(measurer, model, spec, false, footprint);
            const double byFocused = wrongPct(measurer, model, spec, true);
            ++measured;
            EXPECT_LE(byFootprint, kRatio * byFocused + kSlackPoints)
                << name << " on " << spec.name << ": the footprint offset is " << byFootprint << " % wrong, focused "
                << byFocused << " %";
        }
    }
    EXPECT_EQ(measured, 6);
}
