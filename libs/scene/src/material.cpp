#include "shadowkit/scene/material.h"

#include <algorithm>
#include <cmath>

namespace shadowkit::scene {

float largestAlpha(const Image& image) {
    uint8_t most = 0;
    for (size_t i = 3; i < image.rgba.size(); i += 4) most = std::max(most, image.rgba[i]);
    return float(most) / 255.0f;
}

float alphaAtMost(const Material& material, float textureAlpha) { return material.baseColorFactor.a * textureAlpha; }

bool coversNothing(const Material& material, float textureAlpha) {
    return material.alphaTested() && alphaAtMost(material, textureAlpha) < material.alphaCutoff;
}

bool coversNothing(const Material& material, std::span<const Texture> textures) {
    if (!material.alphaTested()) return false; // opaque: covers wherever it lies, no texture to scan
    const int32_t t = material.baseColorTexture;
    return coversNothing(material,
                         t >= 0 && size_t(t) < textures.size() ? largestAlpha(textures[size_t(t)].image) : 1.0f);
}

int wrapTexelIndex(int i, int n, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::ClampToEdge:
        return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case TextureWrap::MirroredRepeat: {
        const int period = 2 * n;
        int m = i % period;
        if (m < 0) m += period;
        return m < n ? m : period - 1 - m;
    }
    case TextureWrap::Repeat:
    default: {
        const int m = i % n;
        return m < 0 ? m + n : m;
    }
    }
}

namespace {

glm::vec4 texel(const Texture& t, int x, int y) {
    const uint8_t* p =
        t.image.pixel(wrapTexelIndex(x, t.image.width, t.wrapS), wrapTexelIndex(y, t.image.height, t.wrapT));
    return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
}

} // namespace

glm::vec4 sampleLevel0(const Texture& texture, glm::vec2 uv) {
    if (texture.image.width <= 0 || texture.image.height <= 0) return glm::vec4(1.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f); // NaN-safe: a degenerate hit
    const glm::vec2 size(float(texture.image.width), float(texture.image.height));
    // Clamped where a float has no fraction left (and an int conversion would overflow).
    const glm::vec2 st = glm::clamp(uv * size, glm::vec2(-16777216.0f), glm::vec2(16777216.0f));
    if (texture.nearest) return texel(texture, int(std::floor(st.x)), int(std::floor(st.y)));
    const glm::vec2 p = st - 0.5f;
    const glm::vec2 base = glm::floor(p);
    const glm::vec2 f = p - base;
    const int x = int(base.x), y = int(base.y);
    const glm::vec4 top = glm::mix(texel(texture, x, y), texel(texture, x + 1, y), f.x);
    const glm::vec4 bottom = glm::mix(texel(texture, x, y + 1), texel(texture, x + 1, y + 1), f.x);
    return glm::mix(top, bottom, f.y);
}

} // namespace shadowkit::scene
