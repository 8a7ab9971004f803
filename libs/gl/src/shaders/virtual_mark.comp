// Virtual shadow maps' page marking (virtual_pages.h): every pixel of the camera's depth
// pre-pass is a visible receiver; it requests the page of the level its footprint picks
// (skVirtualLevelRule in glsl/shadowkit_shadows.glsl, core::clipmapLevelFor) — or of the first
// coarser level whose window holds it —, the same page of the next coarser level, the fallback
// a full pool serves it from, and its page of the coarsest level, the fallback of last resort. Pages within the lookup's reach of the receiver's texel
// are requested too (a corner touches four), so a filter or a float rounding that lands the
// lookup in a neighbouring page finds it resident. One bit per page of each level's window.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SK_RECEIVER_DEPTH_UNIT) uniform sampler2D viewDepth; // metres, 0: sky
layout(std430, binding = SK_PAGE_REQUEST_BINDING) buffer Requests { uint requestBits[]; };

layout(std140, binding = SK_VIRTUAL_MARK_BINDING) uniform VirtualMark {
    mat4 worldFromClip; // camera
    vec4 wsEye;         // xyz
    vec4 wsViewForward; // xyz, unit
    mat4 levelClipFromWorld[SK_MAX_CASCADES];
    int levels;
    int firstExponent;
    float footprintPerMetre;
    float lodBias;
    int pagesPerSide;
    int pageTexels;
    float reachTexels; // how far from its texel a lookup reads (filter, normal offset, rounding)
    int pad0;
};

// The same rule as skVirtualLevelRule (glsl/shadowkit_shadows.glsl), which a compute shader
// cannot include (that file reads gl_FragCoord).
int levelRule(float z) {
    const int e = int(floor(log2(max(z * footprintPerMetre, 1e-30)) + lodBias));
    return clamp(e - firstExponent, 0, levels - 1);
}

// Requests the pages of `level` within reach of `ws`; false when the level's window misses it.
bool request(int level, vec3 ws) {
    const vec4 clip = levelClipFromWorld[level] * vec4(ws, 1.0);
    const vec2 texel = (clip.xy / clip.w * 0.5 + 0.5) * float(pagesPerSide * pageTexels);
    const float side = float(pagesPerSide * pageTexels);
    if (any(lessThan(texel, vec2(0.0))) || any(greaterThanEqual(texel, vec2(side)))) return false;
    const ivec2 lo = clamp(ivec2(floor((texel - reachTexels) / float(pageTexels))), ivec2(0), ivec2(pagesPerSide - 1));
    const ivec2 hi = clamp(ivec2(floor((texel + reachTexels) / float(pageTexels))), ivec2(0), ivec2(pagesPerSide - 1));
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            const uint bit = uint((level * pagesPerSide + y) * pagesPerSide + x);
            atomicOr(requestBits[bit >> 5u], 1u << (bit & 31u));
        }
    return true;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = textureSize(viewDepth, 0);
    if (any(greaterThanEqual(pixel, size))) return;
    const float z = texelFetch(viewDepth, pixel, 0).r;
    if (z <= 0.0) return;
    // The pixel centre's ray, scaled to its view depth (as receiver_mask.comp).
    const vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    const vec4 farPoint = worldFromClip * vec4(ndc, 1.0, 1.0);
    const vec3 ray = farPoint.xyz / farPoint.w - wsEye.xyz;
    const vec3 ws = wsEye.xyz + ray * (z / dot(ray, wsViewForward.xyz));
    for (int level = levelRule(z); level < levels; ++level) {
        if (!request(level, ws)) continue;
        if (level + 1 < levels) request(level + 1, ws);
        // And the coarsest level's, which holds the whole scene box: a few dozen pages for a
        // view, allocated first, so a pool too small for the finer ones still shadows every
        // receiver, coarsely, instead of leaving it lit.
        if (level + 2 < levels) request(levels - 1, ws);
        return;
    }
}
