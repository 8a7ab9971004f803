// Shadow maps of spot and point lights (seed 003, "Shadow mapping for point lights": a cube
// map of six 90° views holding the distance to the light, all faces written "in the same
// pass: see gl_Layer"). Spot lights are layers of one depth texture array, point lights cubes
// of one cube-map array; the camera passes sample both (local_lights.glsl).
//
// The layered pass: each light is one pass whose draws write every face it keeps
// (core::computePointShadowSetup skips faces that see nothing of the view), either
//   - from the vertex shader (GL_ARB_shader_viewport_layer_array, or AMD's older
//     GL_AMD_vertex_shader_layer): every instance is drawn once per face with a face index
//     from gl_InstanceID, so no extra stage runs; or
//   - from a geometry shader with one invocation per face (the seed's way, core GL 4.0);
// or, to compare, six passes, one per face, each with its own culled list.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "program.h"

#include "shadowkit/core/local_lights.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/gl/render_settings.h"
#include "shadowkit/scene/image.h"

#include <memory>
#include <span>

namespace shadowkit::gl {

class LocalShadowMaps {
public:
    static core::Result<std::unique_ptr<LocalShadowMaps>> create();

    // The driver lets the vertex shader choose the layer.
    bool hasVertexLayer() const { return static_cast<bool>(m_vertexLayerPrograms.plain); }
    // What `pass` runs as here: Layered is VertexLayer where the driver has it, else Geometry.
    LocalPass resolve(LocalPass pass) const;

    // How many lists draw() takes for these lights: one per light (points first, then
    // spots), or with PerFace one per kept cube face (in each point set-up's view order),
    // then one per spot light.
    static size_t listCount(const core::LocalLighting& lights, LocalPass pass);

    // Allocates the maps for these lights (kept while counts and size stay), then writes
    // every light's map; casters from the renderer's culling, listCount() lists of them (and as
    // many GPU-culled beside them, GPU-driven), and each list's volume (PassLists::localVolumes: a
    // large mesh draws its clusters meeting it). What lists culled on the GPU drew is not counted.
    core::Result<PassStats> draw(const GpuScene& scene, const core::LocalLighting& lights, const CasterLists& casters,
                                 std::span<const std::vector<visibility::HalfSpace>> volumes, LocalPass pass,
                                 bool hardwarePcf);

    // The camera passes' uniforms (LocalLights) and textures; evalLight: −1 for the sun, else
    // the local light the eval pass writes the shadow term of.
    void bind(const core::LocalLighting& lights, const LocalBiasSettings& bias, int evalLight, bool sunLights) const;

    // The maps as greys, near the light bright: every spot map, then every point light's cube
    // unfolded as a cross (+Y above, −X +Z +X −Z across, −Y below), lights side by side.
    scene::Image readAsGreys(const core::LocalLighting& lights) const;

private:
    // Both maps' textures for `spots` spot maps and `points` cubes of size² texels, the old ones
    // released first; a driver out of memory leaves 1-texel maps (the camera passes sample both
    // in every frame) and fails in one line.
    core::Status allocate(int size, int spots, int points);
    LocalShadowMaps() = default;
    ProgramPair m_vertexLayerPrograms, m_geometryPrograms; // plain and with materials
    Buffer m_depthUniforms, m_lightUniforms;
    Texture m_spotMaps, m_pointMaps;
    Framebuffer m_framebuffer;
    int m_size = 0, m_spots = 0, m_points = 0;
};

} // namespace shadowkit::gl
