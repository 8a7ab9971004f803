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
// of pixels). Every view holds (tools/measure-corpus.sh measures every file of the corpus,
// docs/reliability.md). The public
// models come from Debian's assimp-testmodels (tools/install-deps.sh); a model that is missing
// fails the test, naming the package.
// CTest label `gl`: runs headless on Mesa llvmpipe.
#include "headless_gl_test.h"

#include "shadowkit/frame/frame_config.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/scene_io.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

using namespace shadowkit;
namespace fs = std::filesystem;

namespace {

const fs::path kModels[] = {
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
    "/usr/share/assimp/models/OBJ/spider.obj",
    // A figure with fine grooves, spheres in walled cells, a hip roof: the receiver's offset once
    // ran half a texel along its normal whatever its slope, which carried lookups past ridges
    // narrower than that (Wuson's `into-sun` 1.14 % against the focused map's 0.57), the
    // spheres' rims out of the walls' shadows and the roof's valleys under the neighbouring face.
    // Moved by a quarter of the texel's footprint on its triangle instead (core::recommendedBias),
    // every view holds but the spheres' `paper` (3.15 % against 1.39: the offset carried their
    // rims, which the sun grazes, out of the walls' shadows). The offset guard keeps them there
    // (core::BiasSettings::offsetGuard): 1.67 %, and without it the spheres' view fails here.
    "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
    "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf",
    "/usr/share/assimp/models/OBJ/regr01.obj",
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "pillar_on_plate.gltf",
    // Authored here (tools/authored_shapes.py): 3 cm ropes and 40 cm masts seen from afar; a wide
    // flat town; a single tree of alpha-cut leaves. Their `into-sun` holds since TSM's warp
    // stopped outgrowing a compact footprint's pixels (docs/reliability.md, "Models we did not
    // make").
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "ship.obj",
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "town.obj",
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "tree.gltf",
    // A pavilion under the sky sphere it ships with, left out as it loads (scene/sky_enclosure.h).
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "sky.gltf",
    // A glasshouse whose glass lets the sun in (KHR_materials_transmission, gltf_transmission.cpp).
    // On `sun-behind` (the sun 25° up) its two low walls cast 16 m of shadow on the lawn and the
    // floor, which end cot 25° = 2.1 times the receivers' lift short: half a texel along the
    // normal lost a line of pixels there (0.49 % false light against 0.03). The footprint offset
    // with a twentieth of a texel keeps it to 0.13 against a bound of 0.145 (the footprint
    // alone 0.24: a line of false shadow along the far wall's foot).
    fs::path(SHADOWKIT_SOURCE_DATA_DIR) / ".." / "tests" / "data" / "shapes" / "glasshouse.gltf",
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
// `focused`, at kWidth × kHeight, with the recommended bias.
double wrongPct(measure::Measurer& measurer, const scene::Scene& model, const scene::ViewSpec& spec, bool focused) {
    // As `shadowkit eval --size 640x360` draws it: `paper`, a square view, widened around its framing.
    scene::ResolvedView view = scene::resolveView(spec, model);
    view.setSize(kWidth, kHeight);
    gl::RenderSettings settings; // the recommended bias, hard test
    settings.width = view.width, settings.height = view.height;
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
    for (const fs::path& file : kModels) {
        const std::unique_ptr<LoadedModel> loaded = loadModel(file);
        if (!loaded) continue;
        const scene::Scene& model = loaded->scene;
        measure::Measurer& measurer = *loaded->measurer;
        for (const scene::ViewSpec& spec : *views) {
            if (!spec.lights.empty()) continue; // the sun's set-ups on the sunlit views
            const double byDefault = wrongPct(measurer, model, spec, false);
            const double byFocused = wrongPct(measurer, model, spec, true);
            ++measured;
            EXPECT_LE(byDefault, kRatio * byFocused + kSlackPoints)
                << file.filename() << " on " << spec.name << ": the default is " << byDefault << " % wrong, focused "
                << byFocused << " %";
        }
    }
    EXPECT_EQ(measured, 66); // 11 models × 6 sunlit views: none skipped
}
