// One iteration of the eye-space, depth-dependent blur of the shadow mask (Scherzer 2005 §4.3):
// a 3x3 tent kernel whose tap distance shrinks with view depth (strong near the viewer,
// weak far away, keeping distant shadow detail) and which skips taps across depth
// discontinuities, so shadows do not bleed from one surface onto another behind it.
in vec2 uv;
layout(binding = SK_BLUR_MASK_UNIT) uniform sampler2D mask;       // shadow term, [0, 1]
layout(binding = SK_BLUR_DEPTH_UNIT) uniform sampler2D viewDepth; // metres; 0 where nothing was drawn

// The C++ side is BlurUniforms in uniforms.h.
layout(std140, binding = SK_BLUR_BINDING) uniform Blur {
    float radiusPixels;   // tap distance at view depth 0
    float depthFalloff;   // 1/m: radius / (1 + falloff · depth)
    float depthThreshold; // relative view-depth step that stops the kernel
};

layout(location = 0) out float outMask;

void main() {
    const ivec2 size = textureSize(mask, 0);
    const ivec2 pixel = ivec2(gl_FragCoord.xy);
    const float centreDepth = texelFetch(viewDepth, pixel, 0).r;
    const float centre = texelFetch(mask, pixel, 0).r;
    // Both images are sampled nearest (set by the renderer): a fractional radius picks the
    // nearest pixel, and no tap mixes values across an edge it skips.
    if (centreDepth <= 0.0) { outMask = centre; return; } // sky: nothing to blur
    const float radius = radiusPixels / (1.0 + depthFalloff * centreDepth);
    float sum = 0.0, weights = 0.0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const vec2 tapUv = (vec2(pixel) + 0.5 + radius * vec2(i, j)) / vec2(size);
            const float d = texture(viewDepth, tapUv).r;
            // NaN-safe: a tap off the surface (or off the image) is not averaged in.
            if (!(abs(d - centreDepth) <= depthThreshold * centreDepth)) continue;
            const float w = (2.0 - abs(float(i))) * (2.0 - abs(float(j))); // tent: 4 centre, 2 edge, 1 corner
            sum += w * texture(mask, tapUv).r;
            weights += w;
        }
    outMask = weights > 0.0 ? sum / weights : centre;
}
