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
}
