// Materials in the fragment stages of every pass that draws the scene (gpu_scene.h,
// PassPrograms). The SK_MATERIAL variant of a program samples the batch's base colour
// texture and discards what its alpha does not cover — glTF 2.0 §3.9.4: alpha is
// baseColorFactor.a × the texture's alpha; MASK, and BLEND cast as MASK (scene/material.h),
// cover where alpha ≥ alphaCutoff. The plain variant reads no texture and discards nothing,
// so opaque batches keep depth-only fragment work and early depth tests.
//
// An instance crossing between two levels of detail (visible.glsl) is drawn at both, and each
// draw keeps its level's share of the pixels: those whose threshold in an 8 × 8 ordered dither
// (Bayer 1973) lies below the coarser level's share go to the coarser level, the others to the finer,
// so together the two draws cover each pixel once, and the share moves smoothly with distance
// instead of the whole tree switching at once. The dither is taken over the pixels of the
// target the pass draws into, shifted by SK_DITHER_ORIGIN (a virtual page's place in its level,
// depth_pass.glsl): the same texels get the same thresholds whichever atlas slot holds the page.
//
// SK_DISCARD_UNCOVERED goes at the end of main() (and before any early return): derivatives
// taken after a discard in part of a quad are undefined (GLSL 4.50 §8.14.1).
#ifdef SK_MATERIAL
layout(binding = SK_BASE_COLOR_UNIT) uniform sampler2D skBaseColorTexture;
layout(location = SK_BASE_ALPHA_LOCATION) uniform float skBaseAlpha;     // baseColorFactor.a
layout(location = SK_ALPHA_CUTOFF_LOCATION) uniform float skAlphaCutoff; // < 0: opaque, never discarded
in vec2 vUv;
flat in uint vCrossing; // the list entry's top byte: the coarser level's share in 128ths, bit 7 the coarser level
#ifndef SK_DITHER_ORIGIN
#define SK_DITHER_ORIGIN vec2(0.0)
#endif

vec4 skSurfaceBaseColor() { return texture(skBaseColorTexture, vUv) * vec4(1.0, 1.0, 1.0, skBaseAlpha); }

// The 8 × 8 Bayer matrix's rank of pixel p, 0–63: the bits of x ^ y and x interleaved, reversed.
uint skBayer8(uvec2 p) {
    const uint x = p.x & 7u, xy = (p.x ^ p.y) & 7u;
    return (xy & 1u) << 5 | (x & 1u) << 4 | (xy & 2u) << 2 | (x & 2u) << 1 | (xy & 4u) >> 1 | (x & 4u) >> 2;
}
// The share of the pixels this draw of the instance keeps: 1 unless it is crossing levels.
float skCrossingShare() {
    const float coarser = float(vCrossing & 0x7Fu) / 128.0;
    return (vCrossing & 0x7Fu) == 0u ? 1.0 : (vCrossing & 0x80u) != 0u ? coarser : 1.0 - coarser;
}
// True where the other level of a crossing instance draws this pixel.
bool skCrossedOut() {
    if ((vCrossing & 0x7Fu) == 0u) return false;
    const uvec2 p = uvec2(ivec2(floor(gl_FragCoord.xy + SK_DITHER_ORIGIN)));
    const bool coarser = (float(skBayer8(p)) + 0.5) / 64.0 < float(vCrossing & 0x7Fu) / 128.0;
    return coarser != ((vCrossing & 0x80u) != 0u);
}
#define SK_DISCARD_UNCOVERED(baseColor) \
    if ((baseColor).a < skAlphaCutoff || skCrossedOut()) discard
#else
vec4 skSurfaceBaseColor() { return vec4(1.0); }
#define SK_DISCARD_UNCOVERED(baseColor)
#endif
