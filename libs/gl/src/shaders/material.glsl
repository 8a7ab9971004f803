// Materials in the fragment stages of every pass that draws the scene (gpu_scene.h,
// PassPrograms). The SK_MATERIAL variant of a program samples the batch's base colour
// texture and discards what its alpha does not cover — glTF 2.0 §3.9.4: alpha is
// baseColorFactor.a × the texture's alpha; MASK, and BLEND cast as MASK (scene/material.h),
// cover where alpha ≥ alphaCutoff. The plain variant reads no texture and discards nothing,
// so opaque batches keep depth-only fragment work and early depth tests.
//
// SK_DISCARD_UNCOVERED goes at the end of main() (and before any early return): derivatives
// taken after a discard in part of a quad are undefined (GLSL 4.50 §8.14.1).
#ifdef SK_MATERIAL
layout(binding = SK_BASE_COLOR_UNIT) uniform sampler2D skBaseColorTexture;
layout(location = SK_BASE_ALPHA_LOCATION) uniform float skBaseAlpha;     // baseColorFactor.a
layout(location = SK_ALPHA_CUTOFF_LOCATION) uniform float skAlphaCutoff; // < 0: opaque, never discarded
in vec2 vUv;

vec4 skSurfaceBaseColor() { return texture(skBaseColorTexture, vUv) * vec4(1.0, 1.0, 1.0, skBaseAlpha); }
#define SK_DISCARD_UNCOVERED(baseColor) \
    if ((baseColor).a < skAlphaCutoff) discard
#else
vec4 skSurfaceBaseColor() { return vec4(1.0); }
#define SK_DISCARD_UNCOVERED(baseColor)
#endif
