// Options shared by the shadowkit subcommands: scene, camera / view, sun, technique.
// Each group registers its flags on a CLI11 subcommand and resolves them into library
// types, turning bad values into one-line errors that name the flag.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/gl/renderer.h"
#include "shadowkit/scene/scene.h"
#include "shadowkit/scene/views.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace shadowkit::app {

struct SceneOptions {
    std::string scene = "forest";
    uint64_t seed = 1;
    int trees = 10000;
    double terrainSize = 1024.0;
    int terrainResolution = 256;

    void addTo(CLI::App& cmd);
    // Builds the forest or loads the file, printing what it made and how long it took.
    core::Result<scene::Scene> load(bool verbose = true) const;
};

struct ViewOptions {
    std::string view = "perpendicular";
    std::string eye, dir, up, size, sun; // raw "x,y,z" / "WxH" text, validated in resolve()
    std::optional<double> fov, zNear, zFar, sunElevation, sunAzimuth;

    void addTo(CLI::App& cmd);
    // The named view placed over `scene`, with any explicit flag overriding its field.
    core::Result<scene::ResolvedView> resolve(const scene::Scene& scene) const;
};

struct TechniqueOptions {
    std::string technique;
    std::string lispsmFormula = "scherzer", lispsmDirection = "cross", visibleDepth, depthLayout = "auto";
    double lispsmWeight = 1.0;
    double tsmFocus = core::TsmOptions{}.focusFraction;
    int mapSize = 2048; // texels per side of each map (cascades snap to it)
    int cascades = core::CascadeOptions{}.count;
    double lambda = core::CascadeOptions{}.lambda;
    double blendBand = 0.0;
    std::string cascadeWarp = "none", splits;
    bool stabilize = false;
    std::optional<double> lispsmN;

    void addTo(CLI::App& cmd);
    // Checks the technique's flags (cheap: call before loading a scene).
    core::Result<core::Technique> resolve() const;
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
// Bias values not given fall back to core::recommendedBias for the technique.
struct RenderOptions {
    std::optional<double> biasSlope, biasConstant, normalOffset;
    std::string cull = "auto", receiverPlaneBias = "auto", filter = "hard";
    int blurIterations = 0;
    float blurRadius = gl::BlurSettings{}.radiusPixels, blurDepthFalloff = gl::BlurSettings{}.depthFalloff;
    bool cascadeColors = false;

    void addTo(CLI::App& cmd);
    // Checks the flags (cheap: call before loading a scene).
    core::Status check() const;
    // Settings for a view's image size, the map size and the set-up's technique and
    // layout (for the recommended bias); errors name the flag.
    core::Result<gl::RenderSettings> settingsFor(const scene::ResolvedView& view, int mapSize,
                                                 const core::ShadowSetup& setup) const;
};

// "x,y,z" -> vector; the error names the flag and shows the text.
core::Result<core::Vec3> parseVec3(const std::string& flag, const std::string& text);

} // namespace shadowkit::app
