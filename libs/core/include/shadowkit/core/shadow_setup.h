// ShadowSetup: what every technique computes from camera, light and scene bounds —
// one shadow view per map, each with its matrices — plus diagnostics.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/convex_body.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/small_vector.h"
#include "shadowkit/core/virtual_clipmap.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace shadowkit::core {

enum class Technique {
    Standard, ///< orthographic fit of the whole scene box; independent of the view
    Focused,  ///< uniform (orthographic) fit of the focus body B
    Lispsm,   ///< light space perspective shadow map (Wimmer et al. 2004) with Scherzer 2005's improvements
    Psm,      ///< perspective shadow map (Stamminger & Drettakis 2002): the map taken in post-perspective space
    Tsm,      ///< trapezoidal shadow map (Martin & Tan 2004): a trapezoid around the view mapped to the square
    Csm,      ///< cascaded / parallel-split shadow maps (Dimitrov 2007): one map per depth range of the view
    Virtual,  ///< virtual shadow maps: a clipmap of paged maps, pages where receivers are (virtual_clipmap.h)
};

/// What the shadow map stores as depth.
enum class DepthLayout {
    Hyperbolic,    ///< clip z / w of clipFromWorld: what the projection gives (warped maps: hyperbolic)
    Linear,        ///< linearDepthFromWorld: distance along the light, computed and written per
                   /// fragment (Martin & Tan 2004; Scherzer 2005 §4.2) so depth resolution is even
                   /// over B whatever the warp
    LightDistance, ///< local lights: distance to ShadowSetup::wsLightPosition, mapped from the
                   // view's lightDistance [near, far] to [0, 1], written per fragment (seed 003)
};

/// The light a set-up is for: the sun (ShadowSetupInputs) or a local light (local_lights.h).
enum class LightType { Directional, Spot, Point };

/// A technique and its name in JSON, the CLI and reports.
struct TechniqueInfo {
    Technique technique;   ///< the technique
    std::string_view name; ///< the name in JSON, the CLI and reports
};
std::span<const TechniqueInfo> allTechniques();
std::string_view techniqueName(Technique technique);
std::optional<Technique> parseTechnique(std::string_view name);
/// The best technique implemented, by measurement: what `shadowkit render` uses unless told
/// otherwise. TSM (with its linear depth) has the lowest or equal-lowest wrong_pct of the single
/// maps on every standard view and the lowest mean (0.44 %, LiSPSM 0.60 %; docs/techniques.md).
constexpr Technique defaultTechnique() { return Technique::Tsm; }
/// "standard, focused": for error messages and help.
std::string techniqueNameList();

/// LiSPSM's choice of the free parameter n (Wimmer et al. 2004 §3.5, §4.4; Scherzer 2005 §4.4).
enum class LispsmFormula {
    /// Wimmer et al. 2004 §4.4: n = (z0 + √(z0 z1)) / sin γ with z0 = z_n, z1 = z_n + d sin γ,
    /// d the extent of B along the warp axis (the Δz = (f − n) sin γ refinement).
    Paper,
    /// Scherzer 2005 eq. 1: n = (z_n + √(z_n (z_n + Δz))) / sin γ with Δz the depth extent of B
    /// along the warp axis, measured from visible depth bounds when the caller has them.
    Scherzer,
};
enum class LispsmDirection {
    CrossProduct, ///< V_P = (l ⊗ v) ⊗ l: the view direction made perpendicular to the light (Scherzer 2005 eq. 3)
    MiddleVector, ///< V_P = Σ (B_i − eye), made perpendicular to the light (Scherzer 2005 §4.4)
};

/// LiSPSM's free parameter n: formula, weight, warp axis, visible near distance.
struct LispsmOptions {
    LispsmFormula formula = LispsmFormula::Scherzer;           ///< how n is chosen
    LispsmDirection direction = LispsmDirection::CrossProduct; ///< the warp axis
    double weight = 1.0;                                       ///< multiplies the chosen n; (0, inf)
    std::optional<double> nOverride; ///< a fixed n in metres (> 0); the formula is then skipped
    /// With ShadowSetupInputs::visibleDepth: also take z_n in n's formula from the nearest
    /// visible depth, not the camera's near plane. Scherzer 2005 §4.4 narrows only Δz (from
    /// the visible far distance); n_opt balances the error between z_n and z_n + Δz (Wimmer
    /// et al. 2004 §4.3), so when nothing is visible before z_n' > z_n the balance belongs to
    /// [z_n', far]: a weaker warp, a lower worst case and a coarser median (docs/techniques.md, visible depth).
    bool visibleNear = false;
};
/// Checks the ranges above; error fields "lispsm.weight", "lispsm.n".
Status validate(const LispsmOptions& options);

/// TSM's parameters: the focus fraction of the 80 % rule.
struct TsmOptions {
    /// View depth of the focus point, as a fraction of [z_n, z_f] from the near plane: the
    /// region up to it is mapped to the "80 % line" of the map (Martin & Tan). (0, 1).
    /// 0.2: lowest mean wrong_pct over the six standard views of the default forest at
    /// 2048² with the recommended bias (0.44, against 0.56 at 0.1 and 0.53 at 0.3;
    /// shadowkit eval --views all --technique tsm --tsm-focus F).
    double focusFraction = 0.2;
};
/// Error field "tsm.focus".
Status validate(const TsmOptions& options);

enum class CascadeWarp {
    None,   ///< each split a focused uniform map (Dimitrov 2007's crop matrix)
    Lispsm, ///< each split warped with LiSPSM, its near plane as z_n
};

/// Cascaded shadow maps (Dimitrov 2007): split count and scheme, per-split warp, stabilisation, blend band.
struct CascadeOptions {
    int count = 4; ///< splits, [1, 8]
    /// Practical split scheme weight (Zhang et al. 2006; Dimitrov 2007): 0 uniform, 1 logarithmic; [0, 1].
    /// 0.9: lowest mean wrong_pct over the six standard views with 4 × 1024² on the default
    /// forest with the recommended bias (0.53; 0.79 at 0.5, 0.58 at 0.75, 0.60 at 0.95, 0.65 at 1;
    /// shadowkit eval --views all --technique csm --map-size 1024 --lambda L).
    double lambda = 0.9;
    /// Explicit split distances instead: count + 1 increasing values from the camera's near
    /// to its far plane (metres). Empty: use lambda.
    std::vector<double> splits;
    CascadeWarp warp = CascadeWarp::None; ///< each split uniform, or warped with LiSPSM
    /// Rotation-invariant extent (the split's bounding sphere) in a view-independent light
    /// frame, snapped to whole texels, so shadow edges do not swim as the camera moves.
    /// Not combinable with a warp, which moves texels with the view by design.
    bool stabilize = false;
    /// Each split reaches back over this fraction of the previous split's depth range, so
    /// the shader can blend the two across that band; [0, 0.5].
    double blendBand = 0.0;
};
/// Checks what does not depend on the camera (count, lambda, blend band, combinations);
/// error fields "cascades.count", "cascades.lambda", "cascades.blend_band",
/// "cascades.stabilize". The explicit splits are checked against the camera by
/// computeShadowSetup ("cascades.splits").
Status validate(const CascadeOptions& options);

inline constexpr int kMinMapSize = 16, kMaxMapSize = 16384; ///< texels per side
inline constexpr int kMaxCascadeCount = 8;                  ///< cascades.count <= 8
/// Maps in one set-up: cascades, or the levels of a virtual clipmap.
inline constexpr size_t kMaxShadowViews = kMaxClipmapLevels;
/// Error field "map_size".
Status validateMapSize(int texelsPerSide);
/// Error field "scene_bounds": finite, min <= max on every axis (the sun's and the local lights' set-ups).
Status validateSceneBounds(const Aabb& wsSceneBounds);

/// Everything a set-up is computed from: camera, light, scene box, technique and its options, map size.
struct ShadowSetupInputs {
    PerspectiveCamera camera;                 ///< the view the shadows are for
    DirectionalLight light;                   ///< the sun
    Aabb wsSceneBounds;                       ///< every caster and receiver lies inside
    Technique technique = defaultTechnique(); ///< the recommended one (the CLI's default too)
    /// Texels per side of each shadow map (every cascade), [kMinMapSize, kMaxMapSize]: the
    /// stabilised cascades snap to it, and the renderer allocates it (ShadowSetup::mapSize).
    int mapSize = 2048;
    LispsmOptions lispsm;                   ///< technique Lispsm, and cascades warped per split
    TsmOptions tsm;                         ///< technique Tsm
    CascadeOptions cascades;                ///< technique Csm
    VirtualOptions virtualMaps;             ///< technique Virtual
    std::optional<DepthLayout> depthLayout; ///< unset: the technique's own (linear for TSM)
    /// View-depth range [near, far] of what the camera actually sees, 0 <= near < far: a
    /// min/max reduction of its depth buffer (visible_depth.h). It never narrows a focus
    /// body — hidden casters may shadow visible receivers (Scherzer 2005 §4.4) — only the
    /// parameters: LiSPSM's Δz for n (and z_n with LispsmOptions::visibleNear), and the
    /// cascades' split distances, placed over the visible range as sample-distribution
    /// shadow maps do (Lauritzen et al. 2011). Error field "visible_depth".
    std::optional<Vec2> visibleDepth;
    /// The world point the stabilised cascades' texel lattice passes through
    /// (CascadeOptions::stabilize): fixed in the world, so the lattice does not move with the
    /// camera. computeShadowSetup works relative to the eye and moves it there with the rest.
    Vec3 wsGridOrigin{0.0};
};

/// The layout a set-up with these inputs stores: the explicit one, else the technique's own
/// (`virtual` always stores clip depth, linear in its orthographic pages).
DepthLayout depthLayoutFor(const ShadowSetupInputs& inputs);

/// Warp parameters of the warped techniques, as `shadowkit setup` prints them under "warp"
/// (the JSON names are given per field).
struct LispsmWarp {
    double n = 0.0;            ///< "n": near distance of P along the warp axis (metres)
    double f = 0.0;            ///< "f": its far distance
    double d = 0.0;            ///< "d": extent of B along the warp axis (metres)
    double gammaDegrees = 0.0; ///< "gamma_degrees": angle between view and light
    bool uniform = false;      ///< "uniform": fell back to the uniform limit (n > kLispsmUniformRatio d)
    /// No warp axis at all (view exactly parallel to the light): n, f, d were not computed
    /// and are left out of the JSON.
    bool viewParallel = false;
};
/// PSM's parameters as the set-up chose them: slide-back, the virtual camera's planes, the light's w, the inverted
/// case.
struct PsmWarp {
    double slideBack = 0.0; ///< "slide_back": how far the virtual camera moved back (metres)
    double ppNear = 0.0;    ///< "near": the virtual camera's near plane
    double ppFar = 0.0;     ///< "far": its far plane
    double lightW = 0.0;    ///< "light_w": the light's post-perspective w, scaled (< 0: behind the viewer)
    bool inverted = false;  ///< "inverted": the inverted projection for a light behind
};
/// TSM's parameters as the set-up chose them: the trapezoid's height, focus distance and top line.
struct TsmWarp {
    /// "lambda", "delta", "eta": trapezoid height, focus distance and top line offset (L units);
    /// left out of the JSON when uniform.
    double lambda = 0.0; ///< "lambda": trapezoid height
    double delta = 0.0;  ///< "delta": focus distance
    double eta = 0.0;    ///< "eta": top line offset
    /// "ends_ratio": z_b / z_t, the nearest receiver's view depth in the last quarter of the
    /// receivers' extent along the centre line over that in the first (NaN: no extent).
    double endsRatio = 0.0;
    /// "width_ratio": the receivers' width across the centre line in those two bands, last over
    /// first (1 for a model inside the frustum, 2.5–4 for a terrain; NaN: no extent; JSON null).
    double widthRatio = 0.0;
    bool uniform = false; ///< "uniform": view parallel to the light, no trapezoid
};
using WarpParameters = std::variant<std::monostate, LispsmWarp, PsmWarp, TsmWarp, ClipmapLevel>;

/// One shadow map: lightFromWorld, clipFromLight and their product, its split, its warp parameters.
struct ShadowView {
    Mat4 lightFromWorld{1.0};  ///< rigid: world to light space (the light looks down −Z)
    Mat4 clipFromLight{1.0};   ///< the map's projection (and warp), clip depth [0, 1]
    Mat4 clipFromWorld{1.0};   ///< clipFromLight * lightFromWorld
    std::optional<Vec2> split; ///< [near, far] view depth range, for cascades
    WarpParameters warp;       ///< monostate for the uniform techniques
    /// Row r with depth = dot(r, (p, 1)): distance along the light mapped to [0, 1] over
    /// what the map must hold (0 nearest the light). Used when the layout is Linear.
    Vec4 linearDepthFromWorld{0.0};
    /// Local lights: [near, far] distance from the light that the stored depth spans
    /// (LightDistance layout), and for a point light the cube face, 0-5 (local_lights.h).
    Vec2 lightDistance{0.0};
    std::optional<int> face; ///< point lights: the cube face, 0–5 in OpenGL's order

    /// Large worlds: the same maps for eye-relative coordinates p − ShadowSetup::wsEye. An
    /// engine that renders camera-relative (positions minus the eye in double, then float)
    /// uploads these: their entries are of the size of the scene around the eye, where the
    /// world matrices' translations carry the eye's distance from the origin, which float
    /// cannot (a 6 cm step at 1,000 km). computeShadowSetup builds the set-up here and derives
    /// the world matrices from these, not the other way round.
    Mat4 lightFromEyeRelative{1.0};
    Mat4 clipFromEyeRelative{1.0};        ///< clipFromLight * lightFromEyeRelative
    Vec4 linearDepthFromEyeRelative{0.0}; ///< linearDepthFromWorld for p − ShadowSetup::wsEye
    /// After clipFromLight changed: clipFromWorld and clipFromEyeRelative again.
    void recomposeClip() {
        clipFromWorld = clipFromLight * lightFromWorld;
        clipFromEyeRelative = clipFromLight * lightFromEyeRelative;
    }
};

/// The result of a set-up: one ShadowView per map, depth layout, diagnostics and fallbacks.
struct ShadowSetup {
    Technique technique = Technique::Focused; ///< the technique that computed it
    /// One per shadow map, held inline (up to kMaxShadowViews: eight cascades or sixteen
    /// clipmap levels) so that computing a set-up does not allocate.
    SmallVector<ShadowView, kMaxShadowViews> views;
    ConvexBody body;                    ///< B (empty for `standard`, or when the view misses the scene)
    std::vector<std::string> fallbacks; ///< degenerate cases met and what was done instead
    int mapSize = 2048;                 ///< texels per side of every map: what the renderer allocates
    /// Clip depth is always [0, 1] (conventions.h: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)).
    DepthLayout depthLayout = DepthLayout::Hyperbolic;
    /// True: casters in front of the near plane are clamped to depth 0 rather than clipped,
    /// so the depth pass must enable depth clamping (GL_DEPTH_CLAMP).
    bool depthClamp = true;
    LightType lightType = LightType::Directional; ///< the sun, a spot or a point light
    Vec3 wsLightPosition{0.0};                    ///< local lights
    int skippedFaces = 0;                         ///< point lights: cube faces left out, seeing nothing the camera sees
    /// A point light in one aimed map (computePointAimedMapSetup): the map holds only part of what
    /// the camera sees within reach; receivers outside its cone get no shadow from this light.
    bool holdsPartOfView = false;
    /// The world point the views' eye-relative members are relative to: the camera's eye for
    /// a set-up computeShadowSetup made (or, held by SetupHysteresis, the eye of its refit);
    /// a local light's position for its set-up.
    Vec3 wsEye{0.0};
    /// Technique::Virtual: what its levels share (the views are the levels, finest first).
    std::optional<VirtualClipmap> clipmap;
};

/// For a set-up computed in world coordinates (local lights): the eye-relative members from
/// the world ones, relative to `wsEye`.
void setEyeRelativeFromWorld(ShadowSetup& setup, const Vec3& wsEye);

/// A floating origin: the same set-up for coordinates measured from `wsOrigin` (q = p −
/// wsOrigin): its world members take q, its points and wsEye are moved by −wsOrigin, its
/// eye-relative members are unchanged. Composed in double from the eye-relative matrices, so
/// an origin near the eye (a renderer's scene origin, a tile's centre) loses nothing however
/// far both are from the world's origin.
ShadowSetup rebased(const ShadowSetup& setup, const Vec3& wsOrigin);
/// The same in place.
void rebase(ShadowSetup& setup, const Vec3& wsOrigin);

/// Checks the options that do not depend on the camera, light or scene (map size, LiSPSM,
/// TSM and cascade options): what a front end can check before it has loaded a scene.
Status validateOptions(const ShadowSetupInputs& inputs);
/// Checks every input (camera, light, finite non-empty scene bounds, then validateOptions and
/// the cascades against the camera) without computing anything; errors carry their field.
Status validate(const ShadowSetupInputs& inputs);

/// Validates the inputs and runs the technique.
Result<ShadowSetup> computeShadowSetup(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
