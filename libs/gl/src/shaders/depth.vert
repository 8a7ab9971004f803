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

void main() {
    const uint entry = skVisibleEntry(uint(gl_InstanceID));
    const vec4 ws = worldFromObject[skInstanceOf(entry)] * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    SK_PASS_CROSSING(entry);
#ifdef SK_MATERIAL
    vUv = uv;
#endif
    gl_Position = clipFromWorld * ws;
#ifndef SK_LINEAR_DEPTH
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
