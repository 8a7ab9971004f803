// Depth-only pass into the shadow map: one instanced draw per mesh batch.
layout(location = 0) in vec3 osPosition;
#ifdef SK_MATERIAL
layout(location = 3) in vec2 uv; // the base colour texture's coordinates (material.glsl)
out vec2 vUv;
#endif

layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };
// The batch-local indices of the instances this pass draws (gl/src/visibility.h).
layout(std430, binding = SK_VISIBLE_BINDING) readonly buffer Visible { uint visibleInstances[]; };
layout(location = SK_INSTANCE_OFFSET_LOCATION) uniform uint instanceOffset;

// World position for the linear layout: interpolated perspective-correctly, so the
// fragment shader can compute the exact linear depth (see depth.frag).
out vec3 wsPosition;

void main() {
    const vec4 ws = worldFromObject[visibleInstances[instanceOffset + uint(gl_InstanceID)]] * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
#ifdef SK_MATERIAL
    vUv = uv;
#endif
    gl_Position = clipFromWorld * ws;
}
