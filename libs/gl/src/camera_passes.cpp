#include "camera_passes.h"

#include "gl_shaders.h"
#include "look.h"
#include "lookup_reach.h"
#include "program.h"
#include "uniforms.h"

#include "shadowkit/core/light_size.h"
#include "shadowkit/core/output_conventions.h"

namespace shadowkit::gl {
namespace {

// The camera's casters drawn with the main or eval programs: the CPU's list, where a large mesh
// (a kilometre of terrain) draws only its clusters meeting the camera's view, as a shadow map's
// CPU list does in its map (culling on; off, every cluster), then what the GPU culled. The
// terrain first, as a list in batch order draws it: over the pre-pass, where two surfaces tie
// in depth the last drawn shows (a box standing on the ground), as on the CPU path.
DrawStats drawInView(const GpuScene& scene, const CasterLists& casters, const PassPrograms& programs,
                     const CameraView& view) {
    const std::vector<visibility::HalfSpace> volume = view.settings.culling == Culling::Off
                                                          ? std::vector<visibility::HalfSpace>{}
                                                          : visibility::clipVolume(view.camera.clipFromWorld());
    DrawStats draws = scene.draw(casters.lists.front(), programs, volume, /*setInstanceBase=*/true);
    if (!casters.culled.empty()) draws += scene.draw(casters.culled.front(), programs, /*setInstanceBase=*/true);
    return draws;
}

FrameUniforms frameUniformsOf(const CameraView& view, bool readBlurredMask) {
    const core::PerspectiveCamera& camera = view.camera;
    const core::ShadowSetup& setup = view.setup;
    const RenderSettings& settings = view.settings;
    FrameUniforms frame{};
    frame.clipFromWorld = glm::mat4(camera.clipFromWorld());
    frame.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    frame.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    frame.wsTowardsLight = glm::vec4(glm::vec3(view.light.wsTowardsLight()), 0.0f);
    const Radiance radiance = radianceOf(daylight(view.light, settings));
    frame.sunRadiance = radiance.sun;
    frame.ambientRadiance = radiance.ambient;
    frame.fogColorDensity = glm::vec4(glm::vec3(radiance.fogColor), settings.fogDensity);
    frame.mapTexels = static_cast<float>(setup.mapSize);
    frame.mapCount = static_cast<int32_t>(setup.views.size());
    frame.linearLayout = setup.depthLayout == core::DepthLayout::Linear ? 1 : 0;
    frame.cascadeColors = settings.cascadeColors ? 1 : 0;
    const core::FilterSettings f = lookupFilterFor(setup, settings.filter);
    frame.filterKind = static_cast<int32_t>(f.kind); // SK_FILTER_* in the shaders
    frame.filterTaps = f.taps;
    frame.poissonRadiusTexels = f.radiusTexels;
    frame.lightTanHalfAngle = static_cast<float>(core::tanAngularRadius(settings.sunAngleDegrees));
    frame.receiverPlane = view.bias.receiverPlane ? 1 : 0;
    frame.offsetGuard = view.bias.offsetGuard ? 1 : 0;
    frame.normalOffsetTexels = static_cast<float>(view.bias.normalOffset);
    frame.normalOffsetFootprint = static_cast<float>(view.bias.normalOffsetFootprint);
    frame.readBlurredMask = readBlurredMask ? 1 : 0;
    frame.aliasingOverlay = settings.aliasingOverlay ? 1 : 0;
    frame.foliageOpacity = settings.foliageOpacity ? 1 : 0;
    for (size_t i = 0; i < setup.views.size(); ++i) {
        const core::ShadowView& map = setup.views[i];
        frame.shadowTextureFromWorld[i] = glm::mat4(core::toEngineView(map, setup, {}).textureFromWorld);
        frame.shadowLinearDepthFromWorld[i] = glm::vec4(map.linearDepthFromWorld);
        const core::Vec2 range = map.split.value_or(core::Vec2(camera.zNear, camera.zFar));
        frame.cascadeRange[i] = glm::vec4(static_cast<float>(range.x), static_cast<float>(range.y), 0.0f, 0.0f);
    }
    return frame;
}

// The depth a camera pass starts from: the pre-pass's, tested GL_LEQUAL with writes off (the
// pre-pass already holds every covered pixel's nearest depth, to the bit: main.vert's
// gl_Position is invariant), or cleared to the far plane for bindFrame's GL_LESS with writes. A
// pre-pass of another size (none this frame) is not used.
void startDepth(const Texture& depth, int width, int height, const CameraDepthTarget* prepass, GLuint framebuffer) {
    if (prepass && prepass->width == width && prepass->height == height) {
        glCopyImageSubData(prepass->depth.id(), GL_TEXTURE_2D, 0, 0, 0, 0, depth.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width,
                           height, 1);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        return;
    }
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &clearDepth);
}

// Back to bindFrame's depth state after a camera pass.
void endDepth() {
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}

} // namespace

core::Result<std::unique_ptr<CameraPasses>> CameraPasses::create() {
    auto passes = std::unique_ptr<CameraPasses>(new CameraPasses);
    auto programs = CameraPrograms::create();
    if (!programs) return programs.errorInfo();
    passes->m_programs = std::move(programs).value();
    auto blur = buildProgram("blur pass", {shaders::kFullscreenVert}, {shaders::kBlurFrag});
    if (!blur) return blur.errorInfo();
    if (auto s = checkUniformBlock(*blur, "blur pass", "Blur", sizeof(BlurUniforms), blurFields()); !s)
        return s.errorInfo();
    passes->m_blurProgram = std::move(blur).value();
    passes->m_frameUniforms = createBuffer(nullptr, sizeof(FrameUniforms));
    passes->m_blurUniforms = createBuffer(nullptr, sizeof(BlurUniforms));
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    passes->m_emptyVertexArray = VertexArray(vao);
    passes->m_rawDepth = createRawDepthSampler();
    return passes;
}

void CameraPasses::bindFrame(const CameraView& view, bool readBlurredMask) const {
    const FrameUniforms frame = frameUniformsOf(view, readBlurredMask);
    uploadToBuffer(m_frameUniforms.id(), 0, sizeof frame, &frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, m_frameUniforms.id());
    for (const unsigned unit : {kShadowDepthUnit, kSpotDepthUnit, kPointDepthUnit})
        glBindSampler(unit, m_rawDepth.id()); // the maps once more, their stored depths
    // The camera passes' own raster state, whatever ran before (the culling's box queries leave
    // depth writes off; a frame without shadow passes has nothing between them and these).
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
}

core::Status CameraPasses::evalTarget(int width, int height) {
    if (m_eval && m_eval->width == width && m_eval->height == height) return core::Ok{};
    m_eval.emplace(width, height);
    m_evalAndColor.reset();
    return checkComplete(m_eval->framebuffer, "eval pass");
}

core::Status CameraPasses::colorTarget(int width, int height) {
    if (m_color && m_color->width == width && m_color->height == height) return core::Ok{};
    m_color.emplace(width, height);
    m_evalAndColor.reset();
    return checkComplete(m_color->framebuffer, "main pass");
}

void CameraPasses::clearToSky(const CameraView& view) const {
    const glm::vec3 sky = skyColor(daylight(view.light, view.settings));
    const float clearColor[4] = {sky.r, sky.g, sky.b, 1.0f};
    glClearNamedFramebufferfv(m_color->framebuffer.id(), GL_COLOR, 0, clearColor);
}

core::Status CameraPasses::evalPass(const GpuScene& scene, const CasterLists& casters, const CameraView& view,
                                    const CameraDepthTarget* prepass) {
    if (auto s = evalTarget(view.settings.width, view.settings.height); !s) return s;
    glBindFramebuffer(GL_FRAMEBUFFER, m_eval->framebuffer.id());
    glViewport(0, 0, m_eval->width, m_eval->height);
    m_eval->clearColors();
    startDepth(m_eval->depth, m_eval->width, m_eval->height, prepass, m_eval->framebuffer.id());
    ++m_viewsDrawn;
    drawInView(scene, casters, m_programs.eval(view.setup.clipmap.has_value()), view);
    endDepth();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return core::Ok{};
}

core::Result<DrawStats> CameraPasses::evalAndMainPass(const GpuScene& scene, const CasterLists& casters,
                                                      const CameraView& view, const CameraDepthTarget* prepass) {
    const RenderSettings& settings = view.settings;
    if (auto s = evalTarget(settings.width, settings.height); !s) return s.errorInfo();
    if (auto s = colorTarget(settings.width, settings.height); !s) return s.errorInfo();
    const bool virtualMaps = view.setup.clipmap.has_value();
    if (auto s = m_programs.prepareShadedEval(virtualMaps); !s) return s.errorInfo();
    if (!m_evalAndColor) {
        m_evalAndColor = evalAndColorFramebuffer(*m_eval, *m_color);
        if (auto s = checkComplete(*m_evalAndColor, "shaded eval pass"); !s) return s.errorInfo();
    }
    glBindFramebuffer(GL_FRAMEBUFFER, m_evalAndColor->id());
    glViewport(0, 0, settings.width, settings.height);
    m_eval->clearColors();
    clearToSky(view);
    startDepth(m_color->depth, settings.width, settings.height, prepass, m_evalAndColor->id());
    return drawPicture(scene, casters, m_programs.shadedEval(virtualMaps), view);
}

int CameraPasses::blurPass(const BlurSettings& blur) {
    const int width = m_eval->width, height = m_eval->height;
    if (!m_mask || m_mask->width != width || m_mask->height != height) m_mask.emplace(width, height);
    const BlurUniforms uniforms{
        .radiusPixels = blur.radiusPixels, .depthFalloff = blur.depthFalloff, .depthThreshold = blur.depthThreshold};
    uploadToBuffer(m_blurUniforms.id(), 0, sizeof uniforms, &uniforms);
    glBindBufferBase(GL_UNIFORM_BUFFER, kBlurBinding, m_blurUniforms.id());
    glUseProgram(m_blurProgram.id());
    glBindVertexArray(m_emptyVertexArray.id());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, width, height);
    glBindTextureUnit(kBlurDepthUnit, m_eval->viewDepth.id());
    int target = 0;
    for (int i = 0; i < blur.iterations; ++i) {
        glBindTextureUnit(kBlurMaskUnit, i == 0 ? m_eval->shadowTerm.id() : m_mask->images[1 - target].id());
        glBindFramebuffer(GL_FRAMEBUFFER, m_mask->framebuffers[target].id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        target = 1 - target;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    return 1 - target; // the last one written
}

core::Result<DrawStats> CameraPasses::mainPass(const GpuScene& scene, const CasterLists& casters,
                                               const CameraView& view, int blurredMask,
                                               const CameraDepthTarget* prepass) {
    if (auto s = colorTarget(view.settings.width, view.settings.height); !s) return s.errorInfo();
    if (blurredMask >= 0) glBindTextureUnit(kShadowMaskUnit, m_mask->images[blurredMask].id());
    glBindFramebuffer(GL_FRAMEBUFFER, m_color->framebuffer.id());
    glViewport(0, 0, m_color->width, m_color->height);
    clearToSky(view);
    startDepth(m_color->depth, m_color->width, m_color->height, prepass, m_color->framebuffer.id());
    return drawPicture(scene, casters, m_programs.main(view.setup.clipmap.has_value()), view);
}

DrawStats CameraPasses::drawPicture(const GpuScene& scene, const CasterLists& casters, const PassPrograms& programs,
                                    const CameraView& view) {
    m_mainTimer.begin();
    m_mainSamples.begin();
    ++m_viewsDrawn;
    const DrawStats draws = drawInView(scene, casters, programs, view);
    m_mainSamples.end();
    m_mainTimer.end();
    endDepth();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return draws;
}

} // namespace shadowkit::gl
