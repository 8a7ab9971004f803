#include "render_targets.h"

#include "shadowkit/gl/read_backs.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace shadowkit::gl {
namespace {

// Reads a whole texture level and flips it so the top row comes first.
template <class T>
std::vector<T> readFlipped(const Texture& texture, GLenum format, GLenum type, int width, int height) {
    std::vector<T> rows(static_cast<size_t>(width) * static_cast<size_t>(height));
    readTexture(texture.id(), 0, format, type, static_cast<GLsizei>(rows.size() * sizeof(T)), rows.data());
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(rows.begin() + static_cast<ptrdiff_t>(y) * width,
                         rows.begin() + static_cast<ptrdiff_t>(y + 1) * width,
                         rows.begin() + static_cast<ptrdiff_t>(height - 1 - y) * width);
    return rows;
}

} // namespace

core::Status checkComplete(const Framebuffer& fbo, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return core::environmentError(std::string(what) +
                                      ": the GL driver could not complete the framebuffer (status " +
                                      std::to_string(status) + ")");
    return core::Ok{};
}

core::Result<ShadowTarget> ShadowTarget::create(int texels, int layerCount) {
    while (glGetError() != GL_NO_ERROR) {
    } // earlier errors are not this allocation's
    ShadowTarget target(texels, layerCount);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        const double gib = double(texels) * texels * layerCount * 4.0 / double(1u << 30);
        return core::environmentError("map_size: the GL driver is out of memory for " + std::to_string(layerCount) +
                                          " depth layers of " + std::to_string(texels) + "² (" +
                                          std::to_string(gib).substr(0, 4) + " GiB)",
                                      "map_size");
    }
    if (auto s = checkComplete(target.framebuffer, "shadow map"); !s) return s.errorInfo();
    return target;
}

ShadowTarget::ShadowTarget(int texels, int layerCount)
    : depth(createTexture2DArray(GL_DEPTH_COMPONENT32F, texels, texels, layerCount)), framebuffer(createFramebuffer()),
      size(texels), layers(layerCount) {
    // Hard test (GL_NEAREST): what the evaluation compares against ray-traced truth.
    glTextureParameteri(depth.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(depth.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(depth.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(depth.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(depth.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(depth.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glNamedFramebufferDrawBuffer(framebuffer.id(), GL_NONE);
    attachLayer(0);
}

void ShadowTarget::attachLayer(int layer) const {
    glNamedFramebufferTextureLayer(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0, layer);
}

void ShadowTarget::attachAllLayers() const {
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

scene::Image ShadowTarget::readAsGreys() const { return readDepthAsGreys(depth, size, size, layers); }

scene::Image readDepthAsGreys(const Texture& depth, int width, int height, int layers) {
    detail::countReadBack();
    // All layers come back stacked (layer-major), each bottom row first.
    const size_t layerTexels = static_cast<size_t>(width) * static_cast<size_t>(height);
    std::vector<float> d(layerTexels * static_cast<size_t>(layers));
    readTexture(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(d.size() * sizeof(float)), d.data());
    scene::Image image(width * layers, height);
    for (int layer = 0; layer < layers; ++layer) {
        const float* texels = d.data() + static_cast<size_t>(layer) * layerTexels;
        float lo = 1.0f, hi = 0.0f;
        for (size_t i = 0; i < layerTexels; ++i)
            if (texels[i] < 1.0f) lo = std::min(lo, texels[i]), hi = std::max(hi, texels[i]);
        const float range = hi > lo ? hi - lo : 1.0f;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float v =
                    texels[static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
                const auto grey = static_cast<uint8_t>(v < 1.0f ? 40.0f + 215.0f * (1.0f - (v - lo) / range) : 0.0f);
                uint8_t* p = image.pixel(layer * width + x, y);
                p[0] = p[1] = p[2] = grey;
                p[3] = 255;
            }
    }
    return image;
}

ColorTarget::ColorTarget(int w, int h)
    : color(createTexture2D(GL_RGBA8, w, h)), depth(createTexture2D(GL_DEPTH_COMPONENT32F, w, h)),
      framebuffer(createFramebuffer()), width(w), height(h) {
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

scene::Image ColorTarget::read() const {
    detail::countReadBack();
    scene::Image image(width, height);
    const auto pixels = readFlipped<uint32_t>(color, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    std::memcpy(image.rgba.data(), pixels.data(), image.rgba.size());
    return image;
}

MaskPingPong::MaskPingPong(int w, int h)
    : images{createTexture2D(GL_R32F, w, h), createTexture2D(GL_R32F, w, h)}, framebuffers{createFramebuffer(),
                                                                                           createFramebuffer()},
      width(w), height(h) {
    for (int i = 0; i < 2; ++i) {
        // Nearest: a tap never mixes the mask across a depth edge it was meant to skip.
        glTextureParameteri(images[i].id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(images[i].id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(images[i].id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(images[i].id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(framebuffers[i].id(), GL_COLOR_ATTACHMENT0, images[i].id(), 0);
    }
}

std::vector<float> MaskPingPong::read(int index) const {
    detail::countReadBack();
    return readFlipped<float>(images[index], GL_RED, GL_FLOAT, width, height);
}

CameraDepthTarget::CameraDepthTarget(int w, int h)
    : viewDepth(createTexture2D(GL_R32F, w, h)), depth(createTexture2D(GL_DEPTH_COMPONENT32F, w, h)),
      framebuffer(createFramebuffer()), width(w), height(h) {
    glTextureParameteri(viewDepth.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(viewDepth.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, viewDepth.id(), 0);
    glNamedFramebufferDrawBuffer(framebuffer.id(), GL_COLOR_ATTACHMENT0);
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

void CameraDepthTarget::clear() const {
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far = 1.0f;
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(framebuffer.id(), GL_DEPTH, 0, &far);
}

EvalTarget::EvalTarget(int w, int h)
    : shadowTerm(createTexture2D(GL_R32F, w, h)), surfaceId(createTexture2D(GL_R32UI, w, h)),
      viewDepth(createTexture2D(GL_R32F, w, h)), normal(createTexture2D(GL_RGBA16F, w, h)),
      texel(createTexture2D(GL_RG32F, w, h)), texelFromPixel(createTexture2D(GL_RGBA32F, w, h)),
      depth(createTexture2D(GL_DEPTH_COMPONENT32F, w, h)), framebuffer(createFramebuffer()), width(w), height(h) {
    const Texture* colors[] = {&shadowTerm, &surfaceId, &viewDepth, &normal, &texel, &texelFromPixel};
    for (const Texture* t : {&shadowTerm, &viewDepth}) { // read by the blur: texel exact
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    GLenum drawBuffers[6];
    for (GLenum i = 0; i < 6; ++i) {
        glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0 + i, colors[i]->id(), 0);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(framebuffer.id(), 6, drawBuffers);
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

void EvalTarget::clearColors() const {
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
    const GLuint none[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, one); // nothing drawn: lit
    glClearNamedFramebufferuiv(framebuffer.id(), GL_COLOR, 1, none);
    for (GLint i = 2; i < 6; ++i) glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, i, zero);
}

Framebuffer evalAndColorFramebuffer(const EvalTarget& eval, const ColorTarget& color) {
    Framebuffer framebuffer = createFramebuffer();
    const Texture* attached[] = {&eval.shadowTerm, &eval.surfaceId,      &eval.viewDepth, &eval.normal,
                                 &eval.texel,      &eval.texelFromPixel, &color.color};
    GLenum drawBuffers[7];
    for (GLenum i = 0; i < 7; ++i) {
        glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0 + i, attached[i]->id(), 0);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(framebuffer.id(), 7, drawBuffers);
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, color.depth.id(), 0);
    return framebuffer;
}

std::vector<float> EvalTarget::readViewDepth() const {
    detail::countReadBack();
    // Row order does not matter to a min/max; the same read keeps one code path.
    return readFlipped<float>(viewDepth, GL_RED, GL_FLOAT, width, height);
}

core::RasterBuffers EvalTarget::read() const {
    detail::countReadBack(); // every buffer after one wait
    core::RasterBuffers b;
    b.width = width;
    b.height = height;
    b.shadowTerm = readFlipped<float>(shadowTerm, GL_RED, GL_FLOAT, width, height);
    b.surfaceId = readFlipped<uint32_t>(surfaceId, GL_RED_INTEGER, GL_UNSIGNED_INT, width, height);
    b.viewDepth = readFlipped<float>(viewDepth, GL_RED, GL_FLOAT, width, height);
    const auto normals = readFlipped<glm::vec4>(normal, GL_RGBA, GL_FLOAT, width, height);
    b.wsNormal.reserve(normals.size());
    for (const glm::vec4& n : normals) b.wsNormal.emplace_back(n);
    b.tsTexel = readFlipped<glm::vec2>(texel, GL_RG, GL_FLOAT, width, height);
    const auto jacobians = readFlipped<glm::vec4>(texelFromPixel, GL_RGBA, GL_FLOAT, width, height);
    b.texelFromPixel.reserve(jacobians.size());
    for (const glm::vec4& j : jacobians) b.texelFromPixel.emplace_back(j.x, j.y, j.z, j.w); // columns d/dx, d/dy
    return b;
}

} // namespace shadowkit::gl
