#include "local_shadows.h"

#include "gl_shaders.h"
#include "shadowkit/core/output_conventions.h"
#include "shadowkit/gl/read_backs.h"
#include "uniforms.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

namespace shadowkit::gl {
namespace {

// Depth textures sampled with a comparison (GL_LEQUAL: lit when the receiver's distance is at
// most the stored one), cleared to 1: nothing nearer than the range. A driver out of memory for
// them (eight lamps' cubes of 4096² are 3 GiB) fails in one line: unchecked, the maps read 0
// and every lamp shadows everything.
core::Result<Texture> createDepthArray(GLenum target, int size, int layers) {
    while (glGetError() != GL_NO_ERROR) {
    } // earlier errors are not this allocation's
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    Texture texture(id);
    glTextureStorage3D(id, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        const double gib = double(size) * size * layers * 4.0 / double(1u << 30);
        char amount[32];
        std::snprintf(amount, sizeof amount, "%.2f GiB", gib);
        return core::environmentError("local_map_size: the GL driver is out of memory for " + std::to_string(layers) +
                                          (target == GL_TEXTURE_CUBE_MAP_ARRAY ? " cube faces of " : " spot maps of ") +
                                          std::to_string(size) + "² (" + amount + ")",
                                      "local_map_size");
    }
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    const float far = 1.0f;
    glClearTexImage(id, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
    return texture;
}

// How a local light looks in the camera passes: warm lamps, bright enough within a quarter
// of their range (the windowed inverse square of local_lights.glsl). A look, not photometry.
glm::vec3 radianceOf(double range) { return glm::vec3(1.0f, 0.78f, 0.5f) * static_cast<float>(range * range / 40.0); }

glm::vec4 positionRange(const core::Vec3& p, double range) { return {glm::vec3(p), static_cast<float>(range)}; }

} // namespace

core::Result<std::unique_ptr<LocalShadowMaps>> LocalShadowMaps::create() {
    auto maps = std::unique_ptr<LocalShadowMaps>(new LocalShadowMaps);
    using namespace shaders;
    for (const bool material : {false, true}) {
        const std::string_view with = kMaterialVariant[material];
        auto geometry = buildProgram(material ? "local lights' depth pass (geometry shader, materials)"
                                              : "local lights' depth pass (geometry shader)",
                                     {with, kLocalDepthGlsl, "#define SK_CROSSING_OUT vsCrossing\n", kVisibleGlsl,
                                      kImpostorGlsl, kLocalDepthWorldVert},
                                     {with, kLocalDepthGlsl, kLocalDepthGeom},
                                     {with, kLocalDepthGlsl, kMaterialGlsl, kLocalDepthFrag});
        if (!geometry) return geometry.errorInfo();
        (material ? maps->m_geometryPrograms.material : maps->m_geometryPrograms.plain) = std::move(geometry).value();
    }
    const char* extension = epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array")
                                ? "GL_ARB_shader_viewport_layer_array"
                            : epoxy_has_gl_extension("GL_AMD_vertex_shader_layer") ? "GL_AMD_vertex_shader_layer"
                                                                                   : nullptr;
    if (extension) {
        const std::string enable = std::string("#extension ") + extension + " : require\n";
        for (const bool material : {false, true}) {
            const std::string_view with = kMaterialVariant[material];
            auto layered =
                buildProgram(material ? "local lights' depth pass (vertex layer, materials)"
                                      : "local lights' depth pass (vertex layer)",
                             {enable, with, kLocalDepthGlsl, kVisibleGlsl, kImpostorGlsl, kLocalDepthLayerVert},
                             {with, kLocalDepthGlsl, kMaterialGlsl, kLocalDepthFrag});
            if (!layered) return layered.errorInfo();
            (material ? maps->m_vertexLayerPrograms.material : maps->m_vertexLayerPrograms.plain) =
                std::move(layered).value();
        }
    }
    for (const Program* p : {&maps->m_geometryPrograms.plain, &maps->m_geometryPrograms.material,
                             &maps->m_vertexLayerPrograms.plain, &maps->m_vertexLayerPrograms.material})
        if (*p)
            if (auto s = checkUniformBlock(*p, "local lights' depth pass", "LocalDepth", sizeof(LocalDepthUniforms),
                                           localDepthFields());
                !s)
                return s.errorInfo();
    maps->m_depthUniforms = createBuffer(nullptr, sizeof(LocalDepthUniforms));
    maps->m_lightUniforms = createBuffer(nullptr, sizeof(LocalLightsUniforms));
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    maps->m_framebuffer = Framebuffer(fbo);
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    // Complete 1-texel maps from the start: the camera passes sample both samplers in every frame.
    if (auto s = maps->allocate(1, 1, 1); !s) return s.errorInfo();
    maps->m_size = 1;
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS); // 2x2 PCF across a face's edge reads the next face
    return maps;
}

LocalPass LocalShadowMaps::resolve(LocalPass pass) const {
    if (pass == LocalPass::Layered) return hasVertexLayer() ? LocalPass::VertexLayer : LocalPass::Geometry;
    if (pass == LocalPass::VertexLayer && !hasVertexLayer()) return LocalPass::Geometry;
    return pass;
}

size_t LocalShadowMaps::listCount(const core::LocalLighting& lights, LocalPass pass) {
    if (pass != LocalPass::PerFace) return lights.size();
    size_t faces = 0;
    for (const core::ShadowSetup& setup : lights.pointSetups) faces += setup.views.size();
    return faces + lights.spots.size();
}

core::Status LocalShadowMaps::allocate(int size, int spots, int points) {
    // The old maps go first: a driver short of memory may fit the new ones alone.
    m_spotMaps = Texture(), m_pointMaps = Texture();
    auto spotMaps = createDepthArray(GL_TEXTURE_2D_ARRAY, size, spots);
    auto pointMaps = spotMaps ? createDepthArray(GL_TEXTURE_CUBE_MAP_ARRAY, size, 6 * points)
                              : core::Result<Texture>(spotMaps.errorInfo());
    if (!pointMaps) {
        spotMaps = Texture();                  // its memory back before the 1-texel maps
        if (size > 1) (void)allocate(1, 1, 1); // a later frame tries the size again
        return pointMaps.errorInfo();
    }
    m_spotMaps = std::move(spotMaps).value(), m_pointMaps = std::move(pointMaps).value();
    m_size = size, m_spots = spots, m_points = points;
    return core::Ok{};
}

core::Result<PassStats> LocalShadowMaps::draw(const GpuScene& scene, const core::LocalLighting& lights,
                                              const CasterLists& casters,
                                              std::span<const std::vector<visibility::HalfSpace>> volumes,
                                              LocalPass requested, bool hardwarePcf) {
    const LocalPass pass = resolve(requested);
    const size_t count = listCount(lights, pass);
    if (casters.lists.size() != count || volumes.size() != count ||
        (!casters.culled.empty() && casters.culled.size() != count))
        return core::makeError("local lights: wrong number of culled lists");
    const int spots = static_cast<int>(lights.spots.size()), points = static_cast<int>(lights.points.size());
    if (lights.mapSize != m_size || spots > m_spots || points > m_points) {
        if (auto s = allocate(lights.mapSize, std::max(spots, 1), std::max(points, 1)); !s) return s.errorInfo();
    }
    const float far = 1.0f;
    glClearTexImage(m_spotMaps.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
    glClearTexImage(m_pointMaps.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
    // 2x2 PCF in the sampler (GL_LINEAR), else the hard test.
    for (const Texture* t : {&m_spotMaps, &m_pointMaps}) {
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, hardwarePcf ? GL_LINEAR : GL_NEAREST);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, hardwarePcf ? GL_LINEAR : GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    glViewport(0, 0, m_size, m_size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);  // both sides stored; the lookup's bias keeps surfaces off themselves
    glEnable(GL_DEPTH_CLAMP); // nothing clipped at near or far: depth is written per fragment
    const bool vertexLayer = pass == LocalPass::VertexLayer || (pass == LocalPass::PerFace && hasVertexLayer());
    const PassPrograms programs = (vertexLayer ? m_vertexLayerPrograms : m_geometryPrograms).passPrograms();
    glBindBufferBase(GL_UNIFORM_BUFFER, kLocalDepthBinding, m_depthUniforms.id());

    PassStats stats;
    size_t next = 0;
    // One pass writing `faces` (indices into `views`) of a light at layerBase, from lists `at`.
    auto drawFaces = [&](const core::ShadowSetup& setup, double range, std::span<const int> faces, int layerBase,
                         size_t at) {
        LocalDepthUniforms u{};
        for (const core::ShadowView& view : setup.views)
            u.faceClipFromWorld[view.face.value_or(0)] = glm::mat4(view.clipFromWorld);
        u.wsLightInvRange = glm::vec4(glm::vec3(setup.wsLightPosition), static_cast<float>(1.0 / range));
        for (size_t r = 0; r < faces.size(); ++r) u.faceOfReplica[r / 4][static_cast<int>(r % 4)] = faces[r];
        u.layerBase = layerBase;
        u.replicas = static_cast<int32_t>(faces.size());
        uploadToBuffer(m_depthUniforms.id(), 0, sizeof u, &u);
        const int copies = static_cast<int>(faces.size());
        // What the GPU culled, then the CPU's list: a large mesh (a kilometre of terrain) by its
        // clusters meeting the list's volume — a lamp sees a few.
        const DrawStats d = casters.draw(scene, at, programs, &volumes[at], vertexLayer ? copies : 1);
        // Counted as faces written: the geometry shader amplifies what the vertex path instances.
        const size_t amplify = vertexLayer ? 1 : faces.size();
        stats.instances += d.instances * amplify;
        stats.triangles += d.triangles * amplify;
        stats.drawCalls += d.drawCalls;
    };
    glNamedFramebufferTexture(m_framebuffer.id(), GL_DEPTH_ATTACHMENT, m_pointMaps.id(), 0);
    for (int p = 0; p < points; ++p) {
        const core::ShadowSetup& setup = lights.pointSetups[static_cast<size_t>(p)];
        const double range = lights.points[static_cast<size_t>(p)].range;
        std::array<int, 6> faces{};
        for (size_t v = 0; v < setup.views.size(); ++v) faces[v] = setup.views[v].face.value_or(0);
        const std::span<const int> kept(faces.data(), setup.views.size());
        if (pass == LocalPass::PerFace) {
            for (const int& face : kept) drawFaces(setup, range, std::span<const int>(&face, 1), 6 * p, next++);
        } else {
            const size_t at = next++;
            if (!kept.empty()) drawFaces(setup, range, kept, 6 * p, at);
        }
    }
    glNamedFramebufferTexture(m_framebuffer.id(), GL_DEPTH_ATTACHMENT, m_spotMaps.id(), 0);
    for (int s = 0; s < spots; ++s) {
        const size_t at = next++;
        const int only = 0;
        if (!lights.spotSetups[static_cast<size_t>(s)].views.empty())
            drawFaces(lights.spotSetups[static_cast<size_t>(s)], lights.spots[static_cast<size_t>(s)].range,
                      std::span<const int>(&only, 1), s, at);
    }
    glDisable(GL_DEPTH_CLAMP);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return stats;
}

void LocalShadowMaps::bind(const core::LocalLighting& lights, const LocalBiasSettings& bias, int evalLight,
                           bool sunLights) const {
    LocalLightsUniforms u{};
    u.pointCount = static_cast<int32_t>(lights.points.size());
    u.spotCount = static_cast<int32_t>(lights.spots.size());
    auto texelOf = [&](const core::ShadowSetup& setup) {
        return setup.views.empty() ? 0.0f : static_cast<float>(core::texelSizePerMetre(setup.views[0], lights.mapSize));
    };
    for (size_t i = 0; i < lights.points.size(); ++i) {
        const core::PointLight& l = lights.points[i];
        u.pointPositionRange[i] = positionRange(l.wsPosition, l.range);
        u.pointRadianceTexel[i] = glm::vec4(radianceOf(l.range), texelOf(lights.pointSetups[i]));
        u.lightRadius[i].x = static_cast<float>(l.radius);
    }
    for (size_t i = 0; i < lights.spots.size(); ++i) {
        const core::SpotLight& l = lights.spots[i];
        u.spotPositionRange[i] = positionRange(l.wsPosition, l.range);
        u.spotAxisCosHalf[i] = glm::vec4(glm::vec3(glm::normalize(l.wsDirection)),
                                         static_cast<float>(std::cos(0.5 * glm::radians(l.coneDegrees))));
        u.spotRadianceTexel[i] = glm::vec4(radianceOf(l.range), texelOf(lights.spotSetups[i]));
        u.lightRadius[i].y = static_cast<float>(l.radius);
        const core::ShadowSetup& setup = lights.spotSetups[i];
        if (!setup.views.empty())
            u.spotTextureFromWorld[i] = glm::mat4(core::toEngineView(setup.views[0], setup, {}).textureFromWorld);
    }
    u.evalLight = evalLight;
    u.sunLights = sunLights ? 1 : 0;
    u.localSlopeBiasTexels = static_cast<float>(bias.slopeTexels);
    u.localNormalOffsetTexels = static_cast<float>(bias.normalOffsetTexels);
    u.localConstantBiasMetres = static_cast<float>(bias.constantMetres);
    u.localMapTexels = static_cast<float>(lights.mapSize);
    uploadToBuffer(m_lightUniforms.id(), 0, sizeof u, &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, kLocalLightsBinding, m_lightUniforms.id());
    glBindTextureUnit(kSpotMapUnit, m_spotMaps.id());
    glBindTextureUnit(kPointMapUnit, m_pointMaps.id());
    // The same maps' stored distances for PCSS's blocker search (the renderer binds the sampler).
    glBindTextureUnit(kSpotDepthUnit, m_spotMaps.id());
    glBindTextureUnit(kPointDepthUnit, m_pointMaps.id());
}

scene::Image LocalShadowMaps::readAsGreys(const core::LocalLighting& lights) const {
    const int n = m_size;
    const int spots = static_cast<int>(lights.spots.size()), points = static_cast<int>(lights.points.size());
    if (spots + points == 0 || n != lights.mapSize) return {};
    detail::countReadBack(); // both arrays after one wait
    const size_t layerTexels = static_cast<size_t>(n) * static_cast<size_t>(n);
    auto readAll = [&](const Texture& t, int layers) {
        std::vector<float> d(layerTexels * static_cast<size_t>(layers));
        readTexture(t.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(d.size() * sizeof(float)), d.data());
        return d;
    };
    const std::vector<float> spotTexels = spots ? readAll(m_spotMaps, m_spots) : std::vector<float>{};
    const std::vector<float> pointTexels = points ? readAll(m_pointMaps, 6 * m_points) : std::vector<float>{};
    scene::Image image(spots * n + points * 4 * n, points ? 3 * n : n);
    // One light's layers with their used distance range stretched: near bright, empty black.
    // `place(layer, s, t)` gives the image pixel of texel (s, t), t the row from the top.
    auto paint = [&](const float* first, int layers, auto place) {
        float lo = 1.0f, hi = 0.0f;
        for (size_t i = 0; i < layerTexels * static_cast<size_t>(layers); ++i)
            if (first[i] < 1.0f) lo = std::min(lo, first[i]), hi = std::max(hi, first[i]);
        const float span = hi > lo ? hi - lo : 1.0f;
        for (int layer = 0; layer < layers; ++layer)
            for (int t = 0; t < n; ++t)
                for (int s = 0; s < n; ++s) {
                    const float v = first[static_cast<size_t>(layer) * layerTexels +
                                          static_cast<size_t>(t) * static_cast<size_t>(n) + static_cast<size_t>(s)];
                    const auto grey = static_cast<uint8_t>(v < 1.0f ? 40.0f + 215.0f * (1.0f - (v - lo) / span) : 0.0f);
                    uint8_t* p = place(layer, s, t);
                    p[0] = p[1] = p[2] = grey;
                }
    };
    for (int s = 0; s < spots; ++s)
        // A spot map's t runs up (NDC y): the top image row is its last texel row.
        paint(spotTexels.data() + static_cast<size_t>(s) * layerTexels, 1,
              [&](int, int x, int t) { return image.pixel(s * n + x, n - 1 - t); });
    // The cross: a cube face's t runs down its tile (OpenGL's face orientation), tiles
    // continuous across their edges.
    static constexpr int kTile[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}}; // +X −X +Y −Y +Z −Z
    for (int p = 0; p < points; ++p)
        paint(pointTexels.data() + static_cast<size_t>(6 * p) * layerTexels, 6, [&](int face, int x, int t) {
            return image.pixel(spots * n + p * 4 * n + kTile[face][0] * n + x, kTile[face][1] * n + t);
        });
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

} // namespace shadowkit::gl
