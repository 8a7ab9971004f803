// Depth-only pass into the shadow map: one instanced draw per mesh batch.
layout(location = 0) in vec3 osPosition;
#ifdef SK_MATERIAL
layout(location = 3) in vec2 uv; // the base colour texture's coordinates (material.glsl)
out vec2 vUv;
#endif

layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };

// World position for the linear layout: interpolated perspective-correctly, so the
// fragment shader can compute the exact linear depth (see depth.frag).
out vec3 wsPosition;

#if defined(SK_LINEAR_DEPTH) && defined(SK_PAGES)
#error "depth.vert: views drawn together are hyperbolic (the linear bound reads the pass's one clipFromWorld)"
#endif
#ifdef SK_LINEAR_DEPTH
// The longest edge, in object space, of the mesh's triangles this vertex belongs to (every
// level's; GpuScene), for the rasterised depth's bound (skConservativeClipZ).
layout(location = SK_EDGE_ATTRIBUTE) in float osLongestEdge;
#endif

#ifdef SK_PAGES
// Views drawn together (depth_views.h): virtual pages (VirtualPages::drawPages), or with
// SK_VIEW_LAYERS the fixed maps of a set-up (SunPass::drawMapsTogether), where "page" below reads
// "map" and "viewport" its layer. One multi-draw takes a batch's level for
// several pages, the draw's index in it (SK_DRAW_ID: gl_DrawIDARB, program.h) naming the page
// (pagePerDraw 1), whose matrix and dither origin come from its block, and its slot's viewport
// (GL_ARB_shader_viewport_layer_array). The pages' CPU lists drawn together (every caster of
// pages culled on the CPU; a large mesh's runs of clusters meeting each page) have a draw or
// several a page: a table names each draw's page (pagePerDraw 2). A call that draws one page (a batch's levels, its runs — multi-draws too, whose
// index names the level or the run) has pagePerDraw 0: pageBase and viewportBase name its block
// and viewport.
struct SkPage {
    mat4 clipFromWorld;
    vec4 ditherOrigin; // xy: DepthPass's ditherOrigin for the page
};
layout(std430, binding = SK_PAGES_BINDING) readonly buffer Pages { SkPage pages[]; };
layout(std430, binding = SK_DRAW_PAGES_BINDING) readonly buffer DrawPages { uint drawPages[]; };
layout(location = SK_PAGE_BASE_LOCATION) uniform uint pageBase;
layout(location = SK_VIEWPORT_BASE_LOCATION) uniform int viewportBase;
layout(location = SK_PAGE_PER_DRAW_LOCATION) uniform uint pagePerDraw; // 0, 1 or 2: above
flat out vec2 vDitherOrigin;
#ifndef SK_DRAW_ID
#define SK_DRAW_ID 0u
#endif
#endif

void main() {
    const uint entry = skVisibleEntry(uint(gl_InstanceID));
    vec3 os = osPosition;
#ifdef SK_MATERIAL
    vUv = uv;
#endif
    if (skImpostorGrid.x > 0) { // an impostor's card, turned to the light
        vec2 cardUv;
        os = skImpostorCorner(osPosition, worldFromObject[skInstanceOf(entry)], wsViewer, cardUv);
#ifdef SK_MATERIAL
        vUv = cardUv;
#endif
    }
    const vec4 ws = worldFromObject[skInstanceOf(entry)] * vec4(os, 1.0);
    wsPosition = ws.xyz;
    SK_PASS_CROSSING(entry);
#ifdef SK_PAGES
    const uint k = pagePerDraw == 2u ? drawPages[SK_DRAW_ID] : SK_DRAW_ID * pagePerDraw;
    const SkPage page = pages[pageBase + k];
    vDitherOrigin = page.ditherOrigin.xy;
#ifdef SK_VIEW_LAYERS
    gl_Layer = viewportBase + int(k);
#else
    gl_ViewportIndex = viewportBase + int(k);
#endif
    gl_Position = page.clipFromWorld * ws;
#else
    gl_Position = clipFromWorld * ws;
#endif
#ifdef SK_LINEAR_DEPTH
    const float wsLongestEdge = osLongestEdge * skLargestStretch(worldFromObject[skInstanceOf(entry)]);
    gl_Position.z = skConservativeClipZ(clipFromWorld, wsLongestEdge, dot(linearDepthFromWorld, ws), gl_Position.w);
#else
    // The hyperbolic layout's constant bias, in the stored depth's units (2^-24 of [0, 1], as
    // depth.frag adds it for the linear layout), rather than glPolygonOffset's: for a float
    // depth buffer GL scales those by the exponent of the largest depth in the primitive
    // (GL 4.5 §14.6.5), and under depth clamping a caster spanning a warped map's w = 0 plane
    // (a wide ground behind LiSPSM's projection centre) has no bounded largest depth: NVIDIA's
    // driver (580) pushed the whole primitive to the far plane, llvmpipe did not. Added to z in
    // clip space it is the same after the divide, for every primitive on every driver.
    gl_Position.z += constantBias * gl_Position.w;
#endif
}
