// Renders a scene with a shadow set-up: the shadow-map depth pass, then the shaded
// camera view, into off-screen targets that can be read back as images.
#pragma once

#include "shadowkit/core/bias.h"
#include "shadowkit/core/camera.h"
#include "shadowkit/core/coherent_culling.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/local_lights.h"
#include "shadowkit/core/raster_buffers.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_filter.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene.h"

#include <memory>
#include <optional>
#include <span>

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
};
const char* cullingName(Culling culling); // "off", "frustum", "chc"

inline constexpr int kMaxLocalLightsPerKind = 16; // spot and point lights a frame can shadow, each

// How a point light's cube faces are written (local_shadows.h; seed 003: all faces in one pass).
enum class LocalPass {
    Layered,     // one pass per light: VertexLayer where the driver has it, else Geometry
    VertexLayer, // gl_Layer from the vertex shader, each instance drawn once per face
    Geometry,    // gl_Layer from a geometry shader, one invocation per face
    PerFace,     // six passes, one per kept face, each culled to its face
};
const char* localPassName(LocalPass pass); // "layered", "vertex-layer", "geometry", "per-face"

// Bias of the local lights' lookups, in distance units (their maps store the distance to the
// light): sizes in texels become metres through the texel's world size at the receiver's
// distance (core::texelSizePerMetre), so one setting holds near and far from the light.
struct LocalBiasSettings {
    double slopeTexels = 1.5;        // distance reduced by this × texel size × tan(angle to the light), [0, 16]
    double normalOffsetTexels = 1.0; // receiver moved along its normal by this × texel size, [0, 16]
    double constantMetres = 0.005;   // and its distance reduced by this, [0, 1]
};
// Fields "local_bias.slope", "local_bias.normal_offset", "local_bias.constant".
core::Status validate(const LocalBiasSettings& bias);

// How a frame is drawn. The shadow maps' size comes with the set-up (ShadowSetup::mapSize).
struct RenderSettings {
    int width = 1280, height = 720; // output pixels, [1, GL_MAX_TEXTURE_SIZE]
    // Depth bias of the shadow pass and lookup; unset: core::recommendedBias for the
    // set-up's technique and depth layout and this filter (biasFor).
    std::optional<core::BiasSettings> bias;
    core::FilterSettings filter;
    BlurSettings blur;
    float fogDensity = 0.002f; // 1/m of exponential fog (Scherzer 2005 used fog); 0 = none
    // Draw only the instances each pass can see: the camera pass those meeting the view
    // frustum (and, with Occlusion, not hidden behind others), each shadow map those meeting
    // its clip volume extended towards the light. Invisible by contract (the same pixels
    // either way); Off draws everything.
    Culling culling = Culling::Frustum;
    // Shadow caster culling by visible receivers (Bittner et al. 2011): each shadow map
    // draws only casters that can shadow a pixel the camera sees, found from the camera's
    // depth (a pre-pass; CHC++'s own with Occlusion). Same pixels; ignored when culling is Off.
    bool receiverMask = false;
    // Levels of detail (scene::buildLods): every instance is drawn at the coarsest level
    // whose geometric error, projected at its centre, stays within lodPixelError pixels of
    // the camera, and in a shadow pass also within lodTexelError texels of that map (a
    // caster's shadow lies near it). Simplified receivers look themselves up moved towards
    // the light by their error, so they do not self-shadow. false: full meshes everywhere.
    bool lod = true;
    float lodPixelError = 0.25f; // (0, 16]
    float lodTexelError = 0.25f; // (0, 16]
    bool cascadeColors = false;  // tint each cascade's range (Dimitrov 2007, Figure 3-2)
    // Show, instead of the shaded colour, each pixel's pixels per texel of the sun's map that
    // serves it — eval's `pixels_per_texel` (largest singular value of d(pixel)/d(texel)) with
    // eval::aliasingMapImage's colours (log2 from 1/64 to 64) — computed in the shader, live.
    bool aliasingOverlay = false;
    // false: night. The sun neither lights the frame nor has its maps drawn; the local lights
    // (Renderer::setLocalLights) and a dim ambient remain.
    bool sun = true;
    LocalPass localPass = LocalPass::Layered;
    LocalBiasSettings localBias;
};

// The bias a frame with these settings is drawn with: settings.bias, or the recommended one.
core::BiasSettings biasFor(const core::ShadowSetup& setup, const RenderSettings& settings);

// A coloured world-space segment drawn over a frame (Renderer::drawLines): wireframes for insight.
struct LineSegment {
    core::Vec3 wsFrom{0.0}, wsTo{0.0};
    glm::vec3 color{1.0f};
};

struct PassStats {
    double gpuMilliseconds = 0.0; // between two GL timestamp queries
    size_t instances = 0;         // submitted (over every map, for the shadow pass)
    size_t triangles = 0;         // submitted
    size_t drawCalls = 0;
};

struct FrameStats {
    PassStats shadow, main;
    PassStats local;               // every local light's maps (Renderer::setLocalLights), faces written counted
    int localMaps = 0;             // spot maps and cube faces drawn
    int skippedFaces = 0;          // cube faces left out: they see nothing of the view
    double cullMilliseconds = 0.0; // CPU: choosing every pass's instances and uploading the lists
    // Of cullMilliseconds, the time inside GL calls that do or await the GPU's work: the
    // camera depth pre-pass's draws, the occlusion queries and their results (blocking when
    // not back), the settle loop after a camera cut, the receiver masks' compute pass and
    // read-back. On llvmpipe that is the rasteriser itself.
    double cullGlMilliseconds = 0.0;
    // Culling's own CPU cost: the CPU time of the calling thread in culling outside those GL
    // calls and outside list building — the hierarchy queries, the CHC++ traversal and its
    // polls, the masks' decoding, dilation and caster tests. Thread time, not wall-clock: on
    // llvmpipe the rasteriser's threads share the cores.
    double cullOwnCpuMilliseconds = 0.0;
    // Of cullMilliseconds, thread CPU time choosing every drawn instance's level of detail and
    // building the passes' lists: per instance drawn, culled or not (so not culling's cost).
    double listCpuMilliseconds = 0.0;
    // Culling::Occlusion: the CHC++ pre-pass (counted in cullMilliseconds, with its waits).
    core::CoherentCullingStats occlusion;
    double occlusionMilliseconds = 0.0;
    double receiverMaskMilliseconds = 0.0; // CPU, incl. the read-back (counted in cullMilliseconds)
};

// Cameras, lights, set-ups and lines come in world coordinates; the renderer draws in the
// scene's (scene::Scene::wsOrigin at 0), rebasing every frame's set-up in double from its
// eye-relative matrices, so a scene 1,000 km from the origin is drawn as precisely as at it.
// Inside libs/gl, `ws` names that space.
class Renderer {
public:
    // Uploads the scene and builds the programs; needs a current Context.
    static core::Result<std::unique_ptr<Renderer>> create(const scene::Scene& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Validates the settings and the set-up's map size against the driver's limits, then draws.
    core::Result<FrameStats> render(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                    const core::ShadowSetup& setup, const RenderSettings& settings);

    // The shadow pass, then instead of shading, the per-pixel buffers the evaluation
    // compares with ray-traced truth (shadow term — filtered and blurred as the settings
    // say —, surface identity, depth, normal, shadow texel coordinates and their screen
    // derivatives).
    // With `localLight` ≥ 0 the shadow term, texel coordinates and their derivatives are those
    // of that local light's map (points first, then spots), without its range and cone.
    core::Result<core::RasterBuffers> renderEvalBuffers(const core::PerspectiveCamera& camera,
                                                        const core::DirectionalLight& light,
                                                        const core::ShadowSetup& setup, const RenderSettings& settings,
                                                        int localLight = -1);

    // The spot and point lights of the frames to come, with their set-ups (core::computeLocalLighting
    // for the frame's camera), drawn beside the sun until set again. At most
    // kMaxLocalLightsPerKind of each kind.
    core::Status setLocalLights(core::LocalLighting lights);
    const core::LocalLighting& localLights() const;

    // The view-depth range of what this camera sees ([nearest, farthest] drawn; nullopt for
    // an empty frame), for ShadowSetupInputs::visibleDepth: a camera depth pre-pass (the
    // culling's own, CHC++ included) reduced to min / max on the GPU, 8 bytes read back.
    // For a single frame; it waits for the GPU.
    core::Result<std::optional<core::Vec2>> visibleDepth(const core::PerspectiveCamera& camera,
                                                         const core::DirectionalLight& light,
                                                         const core::ShadowSetup& setup,
                                                         const RenderSettings& settings);
    // The same range from the last frame render() drew, when it made a camera pre-pass
    // (Culling::Occlusion or receiverMask): what a running application feeds to its next
    // frame's set-up, by then long computed, so nothing waits (Scherzer 2005 took Δz "from
    // the visibility algorithm" the same way). nullopt without a pre-pass or visible pixels.
    std::optional<core::Vec2> lastVisibleDepth();

    // Instances that moved since the last frame (scene::animate's list of global indices),
    // all of dynamic batches of the scene the renderer was created with: their transforms
    // go to the GPU, their boxes into the instance hierarchy (refitted to the root). Fails,
    // changing nothing, for an index out of range or of a static batch.
    core::Status moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved);

    // World bounds of every instance, from the instance hierarchy: O(1).
    core::Aabb wsSceneBounds() const;

    // The last rendered frame (top row first).
    scene::Image readColor() const;
    // Draws segments over the last rendered frame as `camera` sees them (always on top: no
    // depth test); readColor() and present() then include them.
    void drawLines(const core::PerspectiveCamera& camera, std::span<const LineSegment> lines);
    // Copies the last rendered frame into the current context's default framebuffer (a
    // window's), scaled to width × height pixels; nothing before the first frame.
    void present(int width, int height) const;
    // The last shadow maps as greys, side by side: near the light is bright, empty texels black.
    scene::Image readShadowMap() const;
    // The local lights' last maps likewise: spot maps, then each cube unfolded as a cross.
    scene::Image readLocalShadowMaps() const;

private:
    Renderer();
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace shadowkit::gl
