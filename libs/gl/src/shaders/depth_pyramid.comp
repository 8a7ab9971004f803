// Depth pyramid for GPU occlusion culling (gl/src/gpu_culling.h), in one storage buffer:
// level 0 is W0 x H0 texels (powers of two, at least half the pixels a side), each the
// farthest depth of its 2 x 2 pixels, and every level the same of the one below, down to
// 1 x 1 — so texel t of level k covers pixels [t 2^(k+1), (t+1) 2^(k+1)), and a box whose
// nearest depth is behind the texels over its pixels is hidden (gpu_cull.comp). Sources
// past the edge are clamped onto the last row or column: they hold real depths, so a texel
// over them is only the more conservative. (A buffer, not a mipmapped R32F texture: with one
// written level by level through image stores, the culling read wrong depths at coarser
// levels on llvmpipe, here, though each level read back right; a buffer has no levels.)
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SK_CULL_PYRAMID_UNIT) uniform sampler2D depth; // the pre-pass's depth (fromDepth)
layout(std430, binding = SK_CULL_STAGE_BINDING) buffer Pyramid { float pyramid[]; };
uniform bool fromDepth;
uniform ivec2 sourceSize, targetSize;
uniform int sourceOffset, targetOffset; // in pyramid[]

void main() {
    const ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, targetSize))) return;
    float farthest = 0.0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            const ivec2 s = min(2 * t + ivec2(x, y), sourceSize - 1);
            farthest = max(farthest, fromDepth ? texelFetch(depth, s, 0).r
                                               : pyramid[sourceOffset + s.y * sourceSize.x + s.x]);
        }
    pyramid[targetOffset + t.y * targetSize.x + t.x] = farthest;
}
