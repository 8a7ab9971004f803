// How a frame is drawn (RenderSettings and what it holds: blur, culling, local lights' pass and
// bias) and what is drawn over it (LineSegment): the renderer's inputs besides the scene, the
// camera, the light and the set-up, in a header of their own so that code describing a frame
// (libs/frame, the apps' options, the passes inside libs/gl) need not include the renderer.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/core/shadow_setup.h"

#include <glm/vec3.hpp>

#include <optional>
#include <string_view>

namespace shadowkit::gl {

// Eye-space, depth-dependent blur of the shadow mask (Scherzer 2005 §4.3).
struct BlurSettings {
    int iterations = 0;        // passes of a 3x3 kernel: 0 (off), 1, 2, 4, 8, 16 ... [0, 64]
    float radiusPixels = 1.5f; // tap distance at view depth 0; (0, 16]
    // Radius at view depth z: radiusPixels / (1 + falloff · z): strong near the viewer,
    // weak far away (Scherzer 2005: "near the viewer, the shadow map is blurred more").
    float depthFalloff = 0.05f; // 1/m, [0, 10]
    // Taps whose view depth differs from the centre's by more than this fraction are
    // ignored: the blur does not bleed across depth discontinuities.
    float depthThreshold = 0.02f; // (0, 1]
};
// Checks the ranges above; error fields "blur.iterations", "blur.radius",
// "blur.depth_falloff", "blur.depth_threshold".
core::Status validate(const BlurSettings& blur);

// Which instances the camera pass draws (shadow passes cull by their volume unless Off).
enum class Culling {
    Off,       // every instance, every pass
    Frustum,   // those whose box meets the view frustum
    Occlusion, // of those, the ones CHC++ occlusion queries find visible (a depth pre-pass)
    // Frustum and occlusion culling on the GPU (compute passes writing indirect draws, a
    // two-phase depth pyramid for the camera; docs/scale-and-visibility.md): the camera
    // pass as Occlusion, the sun's maps, local lights and virtual pages as Frustum (and
    // receiverMask), the lists never on the CPU — but a virtual page's large clustered meshes,
    // and the pages of a view's first frame.
    Gpu,
    // Gpu where the rasteriser is a GPU, Occlusion where it is software (Mesa's llvmpipe: the
    // compute passes would run on the CPU's cores beside the rasteriser's threads, and cost
    // more than CHC++'s queries there). The renderer resolves it for its driver
    // (Renderer::culling); front ends say which it chose.
    Auto,
};
const char* cullingName(Culling culling); // "off", "frustum", "chc", "gpu", "auto"

// Whether OpenGL's GL_RENDERER string names a software rasteriser: Mesa's llvmpipe and softpipe,
// SwiftShader, Microsoft's GDI and Basic Render drivers. Anything else is taken for a GPU.
bool isSoftwareRasteriser(std::string_view glRenderer);
// `requested`, with Auto resolved for the driver whose GL_RENDERER is `glRenderer`.
Culling resolveCulling(Culling requested, std::string_view glRenderer);

inline constexpr int kMaxLocalLightsPerKind = 16; // spot and point lights a frame can shadow, each

// How a point light's cube faces are written (local_shadows.h; seed 003: all faces in one pass).
enum class LocalPass {
    Layered,     // one pass per light: VertexLayer where the driver has it, else Geometry
    VertexLayer, // gl_Layer from the vertex shader, each instance drawn once per face
    Geometry,    // gl_Layer from a geometry shader, one invocation per face
    PerFace,     // six passes, one per kept face, each culled to its face
};
const char* localPassName(LocalPass pass); // "layered", "vertex-layer", "geometry", "per-face"

// Bias of the local lights' lookups, in distance units: the core's, which engines get too.
using LocalBiasSettings = core::LocalBias;

// How a frame is drawn. The shadow maps' size comes with the set-up (ShadowSetup::mapSize).
struct RenderSettings {
    int width = 1280, height = 720; // output pixels, [1, GL_MAX_TEXTURE_SIZE]
    // Depth bias of the shadow pass and lookup; unset: core::recommendedBias for the
    // set-up's technique and depth layout and this filter (biasFor).
    std::optional<core::BiasSettings> bias;
    core::FilterSettings filter;
    // The sun's angular diameter in degrees, [0, 20] (the real sun: 0.53): the width of the
    // penumbrae the Pcss filter draws. 0: a point, hard shadows whatever the filter.
    double sunAngleDegrees = 0.0;
    BlurSettings blur;
    float fogDensity = 0.002f; // 1/m of exponential fog (Scherzer 2005 used fog); 0 = none
    // Draw only the instances each pass can see: the camera pass those meeting the view
    // frustum (and, with Occlusion, not hidden behind others), each shadow map those meeting
    // its clip volume extended towards the light. Invisible by contract (the same pixels
    // either way); Off draws everything.
    Culling culling = Culling::Frustum;
    // Shadow caster culling by visible receivers (Bittner et al. 2011): each shadow map
    // draws only casters that can shadow a pixel the camera sees, found from the camera's
    // depth (a pre-pass; CHC++'s own with Occlusion, the two-phase one with Gpu, whose masks
    // stay on the GPU). Same pixels; ignored when culling is Off.
    bool receiverMask = false;
    // Levels of detail (scene::buildLods): every instance is drawn at the coarsest level
    // whose geometric error, projected at its centre, stays within lodPixelError pixels of
    // the camera, and in a shadow pass also within lodTexelError texels of that map (a
    // caster's shadow lies near it). Simplified receivers look themselves up moved towards
    // the light by their error, so they do not self-shadow. false: full meshes everywhere.
    bool lod = true;
    float lodPixelError = 0.25f; // (0, 16]
    float lodTexelError = 0.25f; // (0, 16]
    // Levels that keep coverage rather than a surface (leaf cards, the leafy trees' billboard
    // clouds: scene::LodLevel::keepsCoverage) are taken this many times further out: they may
    // move their coverage lodFoliageScale × the pixel and texel bounds. 1: as every other mesh.
    // 6: the scale at which no standard view of the leafy forest errs more than 0.2 points more
    // than the full trees with TSM (docs/materials.md); 8 draws a quarter fewer triangles for up
    // to 0.9 more. Virtual pages, whose texels are as fine as the pixels near the camera, see the
    // clouds more: 0.5 points more on `aerial` at 6, 0.12 at 4.
    float lodFoliageScale = 6.0f; // [1, 64]
    // Into a level that keeps coverage a tree crosses over this fraction of the level's bound,
    // centred on it, instead of switching at it: from (1 − lodFade / 2) × the bound to
    // (1 + lodFade / 2) × it, it is drawn at both levels, each keeping its share of the pixels and
    // texels in an ordered dither (material.glsl), so a moving camera sees the canopy dissolve into
    // its cloud rather than pop, and on the mean a tree is as fine as when switching. 0: a switch.
    float lodFade = 0.0f; // [0, 0.9]
    // Levels of detail chosen as this camera would choose them (its eye and projection), in every
    // pass, while the frame is drawn from its own: a measurement's hook. `eval --path --level-pops`
    // draws each frame again with the previous frame's camera here, so what differs between the two
    // pictures is what the switches between levels changed on screen. Unset: the frame's camera.
    std::optional<core::PerspectiveCamera> lodCamera;
    bool cascadeColors = false; // tint each cascade's range (Dimitrov 2007, Figure 3-2)
    // Partial occlusion by alpha-tested casters (leaves): they cast through opacity layers beside
    // the sun's maps (deep opacity maps, Yuksel & Keyser 2008; gl/src/opacity_layers.h) as a
    // fraction of the light, the maps' depth holding the opaque casters alone. Fixed maps and
    // cascades; refused with virtual maps. 12 bytes a texel more.
    bool foliageOpacity = false;
    // Show, instead of the shaded colour, each pixel's pixels per texel of the sun's map that
    // serves it — eval's `pixels_per_texel` (largest singular value of d(pixel)/d(texel)) with
    // eval::aliasingMapImage's colours (log2 from 1/64 to 64) — computed in the shader, live.
    bool aliasingOverlay = false;
    // false: night. The sun neither lights the frame nor has its maps drawn; the local lights
    // (Renderer::setLocalLights) and a dim ambient remain.
    bool sun = true;
    LocalPass localPass = LocalPass::Layered;
    LocalBiasSettings localBias;
    // Technique virtual: pages in the physical pool; 0 as many as fit 2^24 texels (64 MiB of
    // depth, guard bands included). When a frame requests more, the least recently requested
    // pages are evicted, and what still does not fit is served by coarser levels.
    int virtualPoolPages = 0;
    // Technique virtual: the last fraction of each level's range of pixel footprints, [0, 1),
    // over which the lookup fades into the next coarser level (two lookups there); 0: none.
    float virtualBlendBand = 0.0f;
    // Technique virtual: at most this many pages drawn a frame; 0: every page requested. Over
    // it, pages missing are served by coarser levels for a frame or more, and a change of what
    // pages depend on (a moving sun) keeps the pages of the earlier sun on screen while the new
    // sun's are drawn, each level shown in the frame its last page is (virtual_pages.h): the cost
    // of a frame is capped, and the shadows lag the sun by the frames a clipmap takes to draw.
    int virtualPageBudget = 0;
    // Technique virtual: how a frame learns which pages its receivers need. false: it waits for
    // its own requests (exact at once; a stall of the pipeline on a GPU, one a frame). true: it
    // reads an earlier frame's, one or two frames late as the GPU returns them, and never waits
    // while the sun holds — pages first needed meanwhile are served by coarser levels. What an
    // application loop wants (bench's default); eval and render wait.
    bool virtualRequestsLate = false;
};

// RenderSettings' virtual-map fields in range; errors name virtual.pool_pages,
// virtual.blend_band, virtual.page_budget. The renderer checks them for every virtual frame;
// front ends call it to fail before anything is loaded.
core::Status validateVirtualSettings(const RenderSettings& settings);
// The levels of detail's error bounds in (0, 16] pixels and texels, the foliage scale in
// [1, 64] and the cross-fade band in [0, 0.9]; errors name lod.pixel_error, lod.texel_error,
// lod.foliage_scale and lod.fade.
core::Status validateLevelsOfDetail(float pixelError, float texelError, float foliageScale, float fade);
// A fog density >= 0 per metre, finite; the error names "fog".
core::Status validateFogDensity(double density);
// A filter virtual maps can draw with: not msm (the pages hold depth only); the error names "filter".
core::Status validateVirtualFilter(const core::FilterSettings& filter);
// At most kMaxLocalLightsPerKind point and as many spot lights (Renderer::setLocalLights; front
// ends call it before computing the lights' set-ups); the error names "lights".
core::Status validateLocalLightCounts(size_t points, size_t spots);

// The bias a frame with these settings is drawn with: settings.bias, or the recommended one.
core::BiasSettings biasFor(const core::ShadowSetup& setup, const RenderSettings& settings);

// A coloured world-space segment drawn over a frame (Renderer::drawLines): wireframes for insight.
struct LineSegment {
    core::Vec3 wsFrom{0.0}, wsTo{0.0};
    glm::vec3 color{1.0f};
};

} // namespace shadowkit::gl
