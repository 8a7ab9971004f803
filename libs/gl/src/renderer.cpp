#include "shadowkit/gl/renderer.h"

#include "gl_object.h"
#include "gl_shaders.h"
#include "gpu_scene.h"
#include "program.h"
#include "uniforms.h"

#include <algorithm>
#include <optional>
#include <string>

namespace shadowkit::gl {
namespace {

glm::mat4 toFloat(const core::Mat4& m) { return glm::mat4(m); }

// Depth texture + framebuffer of the shadow pass, compare mode on for sampler2DShadow.
struct ShadowTarget {
    Texture depth;
    Framebuffer framebuffer;
    int size = 0;

    explicit ShadowTarget(int texels) : depth(createTexture2D(GL_DEPTH_COMPONENT32F, texels, texels)), size(texels) {
        // Hard test (GL_NEAREST): what the evaluation compares against ray-traced truth.
        glTextureParameteri(depth.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(depth.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(depth.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(depth.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(depth.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(depth.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        framebuffer = Framebuffer(fbo);
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth.id(), 0);
        glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    }
};

struct ColorTarget {
    Texture color, depth;
    Framebuffer framebuffer;
    int width = 0, height = 0;

    ColorTarget(int w, int h)
        : color(createTexture2D(GL_RGBA8, w, h)), depth(createTexture2D(GL_DEPTH_COMPONENT32F, w, h)), width(w), height(h) {
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        framebuffer = Framebuffer(fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color.id(), 0);
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth.id(), 0);
    }
};

core::Status checkComplete(const Framebuffer& fbo, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return core::makeError(std::string(what) + ": framebuffer incomplete (status 0x" + std::to_string(status) + ")");
    return core::Ok{};
}

// Measures the GPU time of the commands between begin() and end().
class PassTimer {
public:
    PassTimer() {
        GLuint id = 0;
        glCreateQueries(GL_TIME_ELAPSED, 1, &id);
        m_query = Query(id);
    }
    void begin() const { glBeginQuery(GL_TIME_ELAPSED, m_query.id()); }
    void end() const { glEndQuery(GL_TIME_ELAPSED); }
    double milliseconds() const {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(m_query.id(), GL_QUERY_RESULT, &ns);
        return static_cast<double>(ns) * 1e-6;
    }

private:
    Query m_query;
};

} // namespace

struct Renderer::Impl {
    std::optional<GpuScene> scene;
    Program depthProgram, mainProgram;
    Buffer depthUniforms, frameUniforms;
    std::optional<ShadowTarget> shadow;
    std::optional<ColorTarget> target;
    PassTimer shadowTimer, mainTimer;
};

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

core::Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Scene& scene) {
    auto renderer = std::unique_ptr<Renderer>(new Renderer);
    Impl& r = *renderer->m_impl;
    auto depth = buildProgram("depth pass", shaders::kDepthVert, shaders::kDepthFrag);
    if (!depth) return core::makeError(depth.error());
    auto main = buildProgram("main pass", shaders::kMainVert, shaders::kMainFrag);
    if (!main) return core::makeError(main.error());
    if (auto s = checkUniformBlock(*depth, "depth pass", "DepthPass", sizeof(DepthPassUniforms)); !s)
        return core::makeError(s.error());
    if (auto s = checkUniformBlock(*main, "main pass", "Frame", sizeof(FrameUniforms)); !s) return core::makeError(s.error());
    r.depthProgram = std::move(depth).value();
    r.mainProgram = std::move(main).value();
    r.depthUniforms = createBuffer(nullptr, sizeof(DepthPassUniforms));
    r.frameUniforms = createBuffer(nullptr, sizeof(FrameUniforms));
    r.scene.emplace(scene);
    // Conventions (core/conventions.h): clip depth [0,1].
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    return renderer;
}

core::Result<FrameStats> Renderer::render(const core::PerspectiveCamera& camera, const core::DirectionalLight& light,
                                          const core::ShadowSetup& setup, const RenderSettings& settings) {
    Impl& r = *m_impl;
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (settings.shadowMapSize < 16 || settings.shadowMapSize > maxSize)
        return core::makeError("map size: must be in [16, " + std::to_string(maxSize) + "] texels, got " +
                               std::to_string(settings.shadowMapSize));
    if (settings.width < 1 || settings.height < 1 || settings.width > maxSize || settings.height > maxSize)
        return core::makeError("image size: each side must be in [1, " + std::to_string(maxSize) + "] pixels");
    if (setup.views.size() != 1)
        return core::makeError("renderer: set-ups with " + std::to_string(setup.views.size()) +
                               " shadow maps are not supported yet (one map only)");

    if (!r.shadow || r.shadow->size != settings.shadowMapSize) {
        r.shadow.emplace(settings.shadowMapSize);
        if (auto s = checkComplete(r.shadow->framebuffer, "shadow map"); !s) return core::makeError(s.error());
    }
    if (!r.target || r.target->width != settings.width || r.target->height != settings.height) {
        r.target.emplace(settings.width, settings.height);
        if (auto s = checkComplete(r.target->framebuffer, "main pass"); !s) return core::makeError(s.error());
    }
    FrameStats stats;
    const core::ShadowView& view = setup.views[0];

    // --- 1. shadow pass: depth only, polygon offset for bias, depth clamp per set-up.
    const DepthPassUniforms depthUniforms{toFloat(view.clipFromWorld)};
    glNamedBufferSubData(r.depthUniforms.id(), 0, sizeof depthUniforms, &depthUniforms);
    glBindBufferBase(GL_UNIFORM_BUFFER, kDepthPassBinding, r.depthUniforms.id());
    glBindFramebuffer(GL_FRAMEBUFFER, r.shadow->framebuffer.id());
    glViewport(0, 0, r.shadow->size, r.shadow->size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(r.shadow->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
    if (setup.depthClamp) glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(settings.biasSlope, settings.biasConstant);
    glUseProgram(r.depthProgram.id());
    r.shadowTimer.begin();
    const DrawStats shadowDraws = r.scene->drawAll();
    r.shadowTimer.end();
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);

    // --- 2. main pass: shaded camera view with the shadow lookup.
    FrameUniforms frame{};
    frame.clipFromWorld = toFloat(camera.clipFromWorld());
    frame.shadowClipFromWorld = toFloat(view.clipFromWorld);
    frame.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    frame.wsTowardsLight = glm::vec4(glm::vec3(light.wsTowardsLight()), 0.0f);
    frame.sunRadiance = glm::vec4(1.05f, 1.0f, 0.9f, 0.0f);
    frame.ambientRadiance = glm::vec4(0.28f, 0.32f, 0.40f, 0.0f);
    const glm::vec3 sky(0.62f, 0.72f, 0.85f);
    frame.fogColorDensity = glm::vec4(glm::pow(sky, glm::vec3(2.2f)), settings.fogDensity);
    glNamedBufferSubData(r.frameUniforms.id(), 0, sizeof frame, &frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, r.frameUniforms.id());
    glBindFramebuffer(GL_FRAMEBUFFER, r.target->framebuffer.id());
    glViewport(0, 0, r.target->width, r.target->height);
    const float clearColor[4] = {sky.r, sky.g, sky.b, 1.0f};
    glClearNamedFramebufferfv(r.target->framebuffer.id(), GL_COLOR, 0, clearColor);
    glClearNamedFramebufferfv(r.target->framebuffer.id(), GL_DEPTH, 0, &clearDepth);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glBindTextureUnit(kShadowMapUnit, r.shadow->depth.id());
    glUseProgram(r.mainProgram.id());
    r.mainTimer.begin();
    const DrawStats mainDraws = r.scene->drawAll();
    r.mainTimer.end();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    stats.shadow = {r.shadowTimer.milliseconds(), shadowDraws.triangles, shadowDraws.drawCalls};
    stats.main = {r.mainTimer.milliseconds(), mainDraws.triangles, mainDraws.drawCalls};
    return stats;
}

scene::Image Renderer::readColor() const {
    const Impl& r = *m_impl;
    if (!r.target) return {};
    scene::Image image(r.target->width, r.target->height);
    glGetTextureImage(r.target->color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(image.rgba.size()),
                      image.rgba.data());
    // GL's first row is the bottom one.
    const size_t row = static_cast<size_t>(image.width) * 4;
    for (int y = 0; y < image.height / 2; ++y)
        std::swap_ranges(image.pixel(0, y), image.pixel(0, y) + row, image.pixel(0, image.height - 1 - y));
    return image;
}

scene::Image Renderer::readShadowMap() const {
    const Impl& r = *m_impl;
    if (!r.shadow) return {};
    const int n = r.shadow->size;
    std::vector<float> depth(static_cast<size_t>(n) * static_cast<size_t>(n));
    glGetTextureImage(r.shadow->depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(depth.size() * sizeof(float)),
                      depth.data());
    // Stretch the used depth range to the full grey scale; cleared texels (1.0) stay black.
    float lo = 1.0f, hi = 0.0f;
    for (float d : depth)
        if (d < 1.0f) lo = std::min(lo, d), hi = std::max(hi, d);
    const float range = hi > lo ? hi - lo : 1.0f;
    scene::Image image(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float d = depth[static_cast<size_t>(n - 1 - y) * static_cast<size_t>(n) + static_cast<size_t>(x)];
            const auto grey = static_cast<uint8_t>(d < 1.0f ? 40.0f + 215.0f * (1.0f - (d - lo) / range) : 0.0f);
            uint8_t* p = image.pixel(x, y);
            p[0] = p[1] = p[2] = grey;
            p[3] = 255;
        }
    return image;
}

} // namespace shadowkit::gl
