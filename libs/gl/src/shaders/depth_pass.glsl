// The depth pass's uniform block, shared by depth.vert and depth.frag. The C++ side is
// DepthPassUniforms in uniforms.h (member offsets checked when the program is built).
layout(std140, binding = SK_DEPTH_PASS_BINDING) uniform DepthPass {
    mat4 clipFromWorld;        // the shadow view's light clip space
    vec4 linearDepthFromWorld; // row: linear depth along the light, [0,1] over B
    float slopeBias;           // linear layout: × max depth slope
    float constantBias;        // linear layout: depth units
    vec2 ditherOrigin;         // texels added to gl_FragCoord.xy for the levels' cross-fade (material.glsl)
    vec4 wsViewer;             // the light the impostors' cards face (impostor.glsl): a direction (w 0)
};
#ifndef SK_DITHER_ORIGIN // virtual pages drawn together give each page's (depth.vert, SK_PAGES)
#define SK_DITHER_ORIGIN ditherOrigin
#endif

#ifdef SK_LINEAR_DEPTH
// The linear layout's rasterised depth: a lower bound of what depth.frag writes, so it can declare
// layout(depth_greater) and early and hierarchical depth tests reject covered fragments before they
// are shaded — as they do for the hyperbolic layout, whose fragment stage writes no depth.
//
// depth.frag writes d = dot(linearDepthFromWorld, p) at the fragment's world point p, plus biases
// ≥ 0. Across a triangle, with screen barycentrics λ_i and clip w_i at its vertices, d is
// interpolated perspective-correctly, Σ μ_i d_i with μ_i = (λ_i / w_i) / Σ_j (λ_j / w_j), while the
// rasteriser interpolates z_i / w_i with the λ_i themselves. So with z_i / w_i = d_i − e_i the
// rasterised depth is Σ λ_i d_i − Σ λ_i e_i, and it lies at or in front of d when every e_i is at
// least |Σ λ_i d_i − d|. With a_i = 1 / w_i that difference is
//   Σ_i Σ_j λ_i λ_j d_i (a_j − a_i) / Σ λ a = ½ Σ_i Σ_j λ_i λ_j (d_i − d_j)(a_j − a_i) / Σ λ a,
// at most ½ (1 − Σ λ_i²) · spread(d) · (a_max − a_min) / a_min ≤ ⅓ (w_max / w_min − 1) spread(d), as
// Σ_{i≠j} λ_i λ_j ≤ ⅔ on a triangle — and at most the spread itself, both weightings being convex.
// With L the triangle's longest edge, the spread is at most |∇d| L and w_max − w_min at most
// |∇w| L; so e = |∇d| L · min(1, |∇w| L / (3 w_min)) bounds it, and w_min ≥ w_i − |∇w| L at each
// vertex. Each vertex takes L as the longest edge of any triangle it belongs to, in any level
// (`edgeMetres`, GpuScene), so its e_i covers each of its triangles, and so does their mean
// Σ λ_i e_i. The bound is tight
// where the warp barely changes w across a triangle (exact where it does not: an orthographic map)
// and holds across the w = 0 plane too, where it falls back to the whole spread. Under depth
// clamping both depths are clamped to [0, 1] alike, which keeps their order; polygon offset, which
// would add to the rasterised depth alone, is off for this layout (it never acts on a written depth).
float skConservativeClipZ(mat4 clipFromWorld, float edgeMetres, float d, float w) {
    const float wPerMetre = length(vec3(clipFromWorld[0].w, clipFromWorld[1].w, clipFromWorld[2].w));
    const float wLeast = w - wPerMetre * edgeMetres;
    const float share = wLeast > 0.0 ? min(wPerMetre * edgeMetres / (3.0 * wLeast), 1.0) : 1.0;
    return (d - length(linearDepthFromWorld.xyz) * edgeMetres * share - 1e-6) * w;
}
#endif
