// The depth pass's uniform block, shared by depth.vert and depth.frag. The C++ side is
// DepthPassUniforms in uniforms.h (member offsets checked when the program is built).
layout(std140, binding = SK_DEPTH_PASS_BINDING) uniform DepthPass {
    mat4 clipFromWorld;        // the shadow view's light clip space
    vec4 linearDepthFromWorld; // row: linear depth along the light, [0,1] over B
    float slopeBias;           // linear layout: × max depth slope
    float constantBias;        // linear layout: depth units
    vec2 ditherOrigin;         // texels added to gl_FragCoord.xy for the levels' cross-fade (material.glsl)
};
#ifndef SK_DITHER_ORIGIN // virtual pages drawn together give each page's (depth.vert, SK_PAGES)
#define SK_DITHER_ORIGIN ditherOrigin
#endif
