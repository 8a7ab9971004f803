// Materials: glTF 2.0's base colour and alpha (§3.9.2, §3.9.4) — what a surface needs for the
// shadows it casts. A leaf card is a quad whose texture's alpha says where the leaf is; a
// shadow map that ignores it casts the card's rectangle.
//
// Base colour = baseColorFactor × texture(baseColorTexture, uv) × vertex colour (the vertex's
// `albedo`, which already holds factor × COLOR_0 for files without a texture). Alpha decides
// coverage:
//   - Opaque: alpha ignored; the surface covers everything it rasterises.
//   - Mask:   covered where alpha ≥ alphaCutoff (glTF's default 0.5), discarded elsewhere.
//   - Blend:  shadowkit has no transparency; a blended surface is drawn and casts as Mask
//             at its cutoff (docs/materials.md says why: a shadow map holds one depth per
//             texel, and the truth must agree with what is drawn).
#pragma once

#include "shadowkit/scene/image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>

namespace shadowkit::scene {

enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

// glTF sampler wrap modes (§5.26); REPEAT is the default.
enum class TextureWrap : uint8_t { Repeat, MirroredRepeat, ClampToEdge };

// A decoded RGBA8 image and how it is sampled. Rows top first: glTF's uv (0, 0) is the
// first texel of the first row, which is also where an image uploaded row by row lands in GL
// (t = 0), so uvs are used as they come.
struct Texture {
    Image image;
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    bool nearest = false; // magnification filter NEAREST (else LINEAR)
    bool mipmaps = true;  // minification through mipmaps (every glTF *_MIPMAP_* filter, or none given)
};

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int32_t baseColorTexture = -1; // index into Scene::textures; -1: none
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f; // Mask and Blend: covered where alpha ≥ cutoff
    bool doubleSided = false; // drawn and cast from both sides (no back-face culling)

    // Whether coverage depends on alpha (Mask, or Blend cast as Mask).
    bool alphaTested() const { return alphaMode != AlphaMode::Opaque; }
};

// The largest alpha of an image's texels, in [0, 1]; 0 for an empty image.
float largestAlpha(const Image& image);

// The most alpha the alpha test can meet anywhere on `material`: its factor's alpha times
// `textureAlpha`, the largest alpha its base-colour texture holds (largestAlpha; 1 without one).
float alphaAtMost(const Material& material, float textureAlpha);

// Whether the alpha test cuts `material` away everywhere — masked (or blended, cast as masked),
// its alphaAtMost below its cutoff: a pane of clear glass, a BLEND card at 12 % alpha. Nothing of
// it is drawn, cast or hit, in any pass or in the truth, so the renderer and the ray tracer leave
// it out rather than test every fragment and every hit of it. `textureAlpha` as for alphaAtMost
// (a loader that has it at hand, once per texture); the second form reads it from `textures`,
// the scene's.
bool coversNothing(const Material& material, float textureAlpha);
bool coversNothing(const Material& material, std::span<const Texture> textures);

// Texel index i of a row or column of n texels under a wrap mode (GL 4.5 §8.14.2).
int wrapTexelIndex(int i, int n, TextureWrap wrap);

// The texture's value at `uv` as GL samples level 0 with a LINEAR filter (or NEAREST when
// the texture says so): texel centres at (i + ½) / size, the wrap mode applied to each texel
// index. The ray-traced truth reads alpha through this, so that it sees the card the
// rasteriser draws up close. RGBA in [0, 1].
glm::vec4 sampleLevel0(const Texture& texture, glm::vec2 uv);

} // namespace shadowkit::scene
