// ShadowSetup: what every technique computes from camera, light and scene bounds —
// one shadow view per map, each with its matrices — plus diagnostics.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/result.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadowkit::core {

enum class Technique {
    Standard, // orthographic fit of the whole scene box; independent of the view
    Focused,  // uniform (orthographic) fit of the focus body B
};

struct TechniqueInfo {
    Technique technique;
    std::string_view name;    // CLI / JSON name
    std::string_view summary; // one line for --help
};
std::span<const TechniqueInfo> allTechniques();
std::string_view techniqueName(Technique technique);
std::optional<Technique> parseTechnique(std::string_view name);
// The best technique implemented: what `shadowkit render` uses unless told otherwise.
constexpr Technique defaultTechnique() { return Technique::Focused; }
// "standard, focused": for error messages and help.
std::string techniqueNameList();

enum class ClipDepth { ZeroToOne, MinusOneToOne };

struct ShadowSetupInputs {
    PerspectiveCamera camera;
    DirectionalLight light;
    Aabb wsSceneBounds; // every caster and receiver lies inside
    Technique technique = Technique::Focused;
};

struct ShadowView {
    Mat4 lightFromWorld{1.0};
    Mat4 clipFromLight{1.0};
    Mat4 clipFromWorld{1.0}; // clipFromLight * lightFromWorld
    std::optional<Vec2> split; // [near, far] view depth range, for cascades
};

struct ShadowSetup {
    Technique technique = Technique::Focused;
    std::vector<ShadowView> views;   // one per shadow map
    ConvexBody body;                 // B (empty for `standard`, or when the view misses the scene)
    std::vector<std::string> fallbacks; // degenerate cases met and what was done instead
    ClipDepth clipDepth = ClipDepth::ZeroToOne;
    // True: casters in front of the near plane are clamped to depth 0 rather than clipped,
    // so the depth pass must enable depth clamping (GL_DEPTH_CLAMP).
    bool depthClamp = true;
};

// Validates the inputs (camera fields, finite non-empty scene bounds) and runs the technique.
Result<ShadowSetup> computeShadowSetup(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
