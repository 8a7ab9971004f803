// Options shared by the shadowkit subcommands: scene, camera / view, sun, technique.
// Each group registers its flags on a CLI11 subcommand and resolves them into library
// types, turning bad values into one-line errors that name the flag.
#pragma once

#include "shadowkit/core/error_driven.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/setup_hysteresis.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/scene/views.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace shadowkit::app {

struct SceneOptions {
    std::string scene = "forest";
    std::string forest =
        "simple"; // the built-in forest's trees: simple (opaque blobs) or leafy (branches and leaf cards)
    uint64_t seed = 1;
    int trees = 10000;
    double terrainSize = 1024.0;
    int terrainResolution = 256;
    int movers = scene::ForestOptions{}.movers;
    bool impostors = false;    // --impostors (scene::ForestOptions::impostors)
    std::string worldOffset;   // "x,y,z": where the scene stands in the world (Scene::wsOrigin)
    std::string sceneUp = "y"; // a scene file's up axis, y or z (scene::LoadOptions::up)
    // A town of meshes placed once loaded as tiles (scene::LoadOptions::mergeSmallMeshes): what a
    // frame draws. Not a flag: `export` turns it off, to write the file's meshes as they were.
    bool mergeSmallMeshes = true;
    // A sky sphere or box round a file's model kept, casting its shadow over everything
    // (scene::LoadOptions::keepSky): left out otherwise.
    bool keepSky = false;
    // The first of the built-in forest's flags given on the command line (--forest, --seed,
    // --trees, --terrain-size, --terrain-resolution, --movers, --impostors): with a scene file it would be
    // ignored, so check() and load() refuse it.
    std::string forestFlag;

    void addTo(CLI::App& cmd);
    // --world-offset parsed (0 when not given).
    core::Result<core::Vec3> offset() const;
    // Without building anything: the forest's options in range, a scene file present, the offset parsed.
    core::Status check() const;
    // Builds the forest or loads the file, printing what it made and how long it took; a file's
    // animations standing as at `poseSeconds` (the first frame's time: scene::LoadOptions::poseSeconds).
    core::Result<scene::Scene> load(bool verbose = true, double poseSeconds = 0.0) const;
};

struct ViewOptions {
    std::string view = "perpendicular";
    std::string eye, dir, up, size, sun; // raw "x,y,z" / "WxH" text, validated in check()
    std::optional<double> fov, zNear, zFar, sunElevation, sunAzimuth;

    void addTo(CLI::App& cmd);
    // What needs no scene: the view's name (spec()) and the flags (checkFlags()); each command
    // checks it before loading one, and resolve() again.
    core::Status check() const;
    // The named view of views.json; an error names --view.
    core::Result<scene::ViewSpec> spec() const;
    // The flags' syntax (--size, --eye, --dir, --up, --sun) and --sun against the sun's angles.
    core::Status checkFlags() const;
    // The named view placed over `scene`, with any explicit flag overriding its field.
    // `sayFraming`: say on stderr where the camera stands when it frames a loaded scene (not
    // when a camera path takes the view's place: the path says so, Timeline::prepareViews).
    core::Result<scene::ResolvedView> resolve(const scene::Scene& scene, bool sayFraming = true) const;
};

struct TechniqueOptions {
    core::Technique technique = core::defaultTechnique();
    // --technique auto: the family and its parameters chosen per frame by the sampling model
    // (auto_technique.h); `technique` then stays the default until a frame is resolved.
    bool automatic = false;
    std::string texelBudget;    // --texel-budget text ("4M", "16777216"); empty: one --map-size map
    bool cascadesGiven = false; // --cascades was given: auto keeps to that count
    core::LispsmFormula lispsmFormula = core::LispsmOptions{}.formula;
    core::LispsmDirection lispsmDirection = core::LispsmOptions{}.direction;
    std::string visibleDepth, splits; // raw "near,far" (or "auto") / "a,b,c" text, parsed by inputsFor()
    // --visible-depth auto: measure the visible range from the frame (frame::FrameDriver).
    bool visibleDepthFromFrame() const { return visibleDepth == "auto"; }
    enum class LayoutChoice { Auto, Hyperbolic, Linear }; // Auto: the technique's own
    LayoutChoice depthLayout = LayoutChoice::Auto;
    double lispsmWeight = core::LispsmOptions{}.weight;
    std::optional<double> lispsmN;
    bool lispsmVisibleNear = core::LispsmOptions{}.visibleNear;
    double tsmFocus = core::TsmOptions{}.focusFraction;
    int mapSize = core::ShadowSetupInputs{}.mapSize;
    core::CascadeOptions cascades;      // count, lambda, warp, stabilize, blend band; splits from `splits`
    core::HysteresisOptions hysteresis; // --stabilize-margin, --stabilize-growth
    core::VirtualOptions virtualMaps;   // --virtual-*: the clipmap (its image height is each frame's)
    int virtualPoolPages = 0;           // --virtual-pool-pages (gl::RenderSettings::virtualPoolPages)
    float virtualBlendBand = 0.0f;      // --virtual-blend-band (gl::RenderSettings::virtualBlendBand)
    int virtualPageBudget = 0;          // --virtual-page-budget (gl::RenderSettings::virtualPageBudget)
    bool virtualRequestsLate = false;   // --virtual-requests (gl::RenderSettings::virtualRequestsLate)

    // --stabilize holds texel lattices (core::SetupHysteresis) for every technique but
    // unwarped cascades, which snap their own texels (CascadeOptions::stabilize).
    bool holdsLattices() const {
        return cascades.stabilize && (technique != core::Technique::Csm || cascades.warp != core::CascadeWarp::None);
    }
    void addTo(CLI::App& cmd);
    // Checks the technique's flags (cheap: call before loading a scene); errors name the flag.
    // Commands that do not render and measure a frame refuse --visible-depth auto.
    // Only commands that resolve it per frame (render, eval) take --technique auto.
    core::Status check(bool measuresFrames = true, bool takesAuto = false) const;
    // --technique auto's options: the budget (K and M are 2^10 and 2^20 texels) and, with
    // --cascades given, that count. Errors name the flag.
    core::Result<core::AutoOptions> autoOptions() const;
    // Everything computeShadowSetup needs for this view and scene box.
    core::Result<core::ShadowSetupInputs> inputsFor(const scene::ResolvedView& view, const core::Aabb& wsBounds) const;
};

// A view over a scene, or over bare bounds given by --scene-bounds (setup, analyze).
struct BoundedView {
    core::Aabb wsBounds;
    scene::ResolvedView view;
};
struct BoundsOptions {
    std::string sceneBounds; // "minx,miny,minz,maxx,maxy,maxz"
    void addTo(CLI::App& cmd);
    // With bare bounds, the ground is their bottom: the view's eye height is above it.
    core::Result<BoundedView> resolve(const SceneOptions& scene, const ViewOptions& view) const;
};

// Bias, filter, blur and debug views of the GL passes, shared by render, eval and compare.
// Bias values not given come from core::recommendedBias for the technique and filter.
struct RenderOptions {
    enum class Choice { Auto, On, Off };
    enum class CullChoice { Auto, Closed, Back, Front, None }; // Auto: the recommended culling
    std::optional<double> biasSlope, biasConstant, normalOffset, normalOffsetFootprint;
    CullChoice cull = CullChoice::Auto;
    Choice receiverPlaneBias = Choice::Auto;
    Choice offsetGuard = Choice::Auto; // --offset-guard: core::BiasSettings::offsetGuard
    std::string filter = "hard";
    double sunAngle = 0.0; // --sun-angle: the sun's angular diameter in degrees; 0 a point
    gl::BlurSettings blur;
    bool foliageOpacity = false; // --foliage-opacity: leaves cast through opacity layers (partial occlusion)
    bool cascadeColors = false;
    bool aliasingOverlay = false;               // --aliasing-overlay: pixels per texel instead of shading (live)
    gl::Culling visibility = gl::Culling::Auto; // --visibility: gpu on a GPU, chc on a software rasteriser
    bool receiverMask = true;                   // --caster-culling receivers (docs/scale-and-visibility.md)
    bool noCull = false;                        // --no-cull: --visibility off (what culling saves, measured)
    bool noLod = false;                         // full meshes everywhere (what levels of detail save, measured)
    float lodPixelError = gl::RenderSettings{}.lodPixelError;     // --lod-pixel-error: the camera's level bound
    float lodTexelError = gl::RenderSettings{}.lodTexelError;     // --lod-texel-error: the shadow maps' level bound
    float lodFoliageScale = gl::RenderSettings{}.lodFoliageScale; // --lod-foliage-scale: coverage levels' multiple
    float lodFade = gl::RenderSettings{}.lodFade;                 // --lod-fade: the cross-fade band, a fraction
    std::optional<double> fog; // --fog: density in 1/m; unset: the scene's (scene::ResolvedView::fogDensity)

    void addTo(CLI::App& cmd);
    // Checks the flags (cheap: call before loading a scene); errors name the flag.
    core::Status check() const;
    // The culling asked for: --visibility, or off with --no-cull.
    gl::Culling culling() const { return noCull ? gl::Culling::Off : visibility; }
};

// The culling a frame asking for `requested` is drawn with on the driver whose GL_RENDERER is
// `glRenderer`, as front ends print it: "chc", or for auto "chc (auto: llvmpipe ... is a
// software rasteriser)" / "gpu (auto: NVIDIA ... is a GPU rasteriser)".
std::string cullingSaid(gl::Culling requested, std::string_view glRenderer);

// A CLI11 transform from a name to an enum value: the names appear in --help as the
// option's type ("standard|focused|..."), and anything else is a one-line error naming the
// flag and the choices.
template <class T>
using Choices = std::vector<std::pair<std::string, T>>;

inline constexpr const char* kChoicesValidator = "choices"; // the name choicesOf() finds them by

template <class T>
CLI::Validator choice(Choices<T> choices) {
    std::string names;
    for (const auto& [name, value] : choices) names += (names.empty() ? "" : "|") + name;
    return CLI::Validator(
        [choices, names](std::string& text) -> std::string {
            for (const auto& [name, value] : choices)
                if (text == name) {
                    text = std::to_string(static_cast<int>(value)); // what CLI11 converts to the enum
                    return {};
                }
            return "expected " + names + ", got '" + text + "'";
        },
        names, kChoicesValidator);
}

// The names an enumerated option registered on `cmd` takes ("--cull" -> auto, back, front, none),
// as its registration lists them for parsing and --help; empty for other options. With
// defaultOf (the default --help shows), the one table the viewer's panel builds its lists from.
std::vector<std::string> choicesOf(CLI::App& cmd, const std::string& flag);
std::string defaultOf(CLI::App& cmd, const std::string& flag);

// A library error, with its field spelt as the flag that sets it ("lispsm.weight: must be
// > 0" -> "--lispsm-weight: must be > 0"); errors without a known field are kept as they are.
core::Error withFlagName(const core::Error& error);

// "a<sep>b<sep>c" -> numbers, appended to `out`; false on an empty, non-numeric or
// non-finite item.
bool parseNumbers(const std::string& text, char separator, std::vector<double>& out);

// --views: "a,b" (standard views of data/views.json, each checked), "all" (the six sunlit ones,
// docs/techniques.md) or "local" (those with spot and point lights, docs/local-lights.md);
// errors name --views.
core::Result<std::vector<std::string>> viewNamesOf(const std::string& list);
// The camera a view name asks of the loaded file — "file" (its first: empty) or "file:NAME"
// (an index or a name, scene::fileView) — or nothing for a views.json view.
std::optional<std::string> fileCameraOf(const std::string& view);

// "x,y,z" -> vector; the error names the flag and shows the text.
core::Result<core::Vec3> parseVec3(const std::string& flag, const std::string& text);

} // namespace shadowkit::app
